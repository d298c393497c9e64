#pragma once
/// \file DmpConfig.h
/// \brief Parameters of a discrete dynamic movement primitive (srp::motion::Dmp,
/// srp::motion::QuaternionDmp): formulation mode, basis, gains, regularisation.

#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>

namespace srp::motion {

/// How the forcing term is scaled when a DMP is re-targeted to a new start/goal.
enum class ForcingScaling {
  None,          ///< f unchanged (dfki-ric movement_primitives; shape kept in metres)
  PerDimension,  ///< f_d * (g'-y0')_d / (g-y0)_d (Ijspeert 2013, thesis eq. 6.5); 1 where |g-y0|_d < 1 mm
  Spatial,       ///< rotation taking (g-y0) onto (g'-y0') times the length ratio (no per-axis blow-up)
};

struct DmpConfig {
  enum class Mode {
    /// dfki-ric movement_primitives 0.9.1 exactly as the thesis' code used it:
    /// no forcing scaling, demo end velocity/acceleration forced to 0, start
    /// at rest, RK4 with the forcing term evaluated one output step ahead,
    /// weights by pinv ridge regression with the given lambda.
    Reference,
    /// Start/goal velocities from the demo, RK4 with the forcing term at the
    /// correct stage times and sub-steps, selectable forcing scaling, lambda
    /// chosen by minimising the GCV error of the forcing-term fit (NLopt)
    /// unless `lambda` is set.
    Default,
  };

  Mode mode = Mode::Default;
  int basisCount = 20;                         ///< N Gaussian basis functions per dimension
  double alpha_y = 25.0;                       ///< spring-damper gain alpha
  double beta_y = 6.25;                        ///< beta = alpha / 4 (critical damping)
  double alpha_z = 4.605170185988091;          ///< phase decay, z(tau) = exp(-alpha_z) = 0.01
  double overlap = 0.8;                        ///< basis overlap of neighbours
  ForcingScaling scaling = ForcingScaling::None;
  /// Ridge coefficient lambda of w = (Phi^T Phi + lambda I)^-1 Phi^T f. Reference
  /// mode: required (the thesis used 0.1). Default mode: nullopt = chosen by GCV.
  std::optional<double> lambda;
  double lambdaSearchMin = 1e-12;              ///< GCV search interval (Default mode)
  double lambdaSearchMax = 1e2;
  /// Output sample period [s] of the reference library (Reference mode; its `dt`).
  double referenceDt_s = 0.05;
  /// Largest RK4 step as a fraction of the system's time constant tau/(alpha/2) (Default mode).
  double maxStepFraction = 0.1;

  /// The configuration the thesis used with dfki-ric movement_primitives.
  static DmpConfig reference(double lambda) {
    DmpConfig c;
    c.mode = Mode::Reference;
    c.lambda = lambda;
    return c;
  }
  /// Throws InvalidInputError naming the bad field.
  void validate() const;
};

std::string toString(ForcingScaling s);
ForcingScaling forcingScalingFromString(const std::string& text);

void to_json(nlohmann::json& j, const DmpConfig& c);
void from_json(const nlohmann::json& j, DmpConfig& c);

}  // namespace srp::motion
