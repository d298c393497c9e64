#pragma once
/// \file Dmp.h
/// \brief Discrete dynamic movement primitive for positions (any number of
/// dimensions; 3 for a Cartesian point), learned from one demonstration.
///
/// Transformation system, in normalised time s = t / tau (tau = duration [s]):
///   y'' = alpha (beta (g - y) + (g'_s - y')) + S f(z),   z = exp(-alpha_z s),
///   f(z) = z * sum_i psi_i(z) w_i / sum_i psi_i(z),      psi_i = exp(-h_i (z - c_i)^2),
/// i.e. tau^2 ydd = alpha (beta (g - y) + tau (gd - yd)) + S f (SPEC.md §3, thesis eq. 6.4).
/// y, g in the demo's frame [m]; yd, gd in [m/s]; S is the forcing scaling
/// (identity for the demo; Dmp::Options::scaling when re-targeted).
///
/// Use by the execution module:
/// \code
///   srp::motion::Dmp dmp = srp::motion::Dmp::fromJson(skillRow.parameters);  // or Dmp::imitate(...)
///   dmp.configure(p_camera_start_m, p_camera_goal_m, 2.0);   // new start, goal [m], duration [s]
///   srp::motion::DmpRollout r = dmp.rollout(0.01);           // sampled every 10 ms, t = 0 .. 2 s
///   // r.t_s (n), r.y (n x 3) positions [m], r.yd (n x 3) velocities [m/s]; r.y row n-1 is at the goal.
/// \endcode
/// configure() with the demo's own start/goal/duration reproduces the demo.
/// Start velocity: the demo's (scaled to the new duration and shape) unless
/// given; pass Eigen::Vector3d::Zero() to start at rest. Reference mode always starts at rest.

#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

namespace srp::motion {

/// How the forcing term is scaled when a DMP is re-targeted to a new start/goal.
enum class ForcingScaling {
  None,          ///< f unchanged (dfki-ric movement_primitives; shape kept in metres)
  PerDimension,  ///< f_d * (g'-y0')_d / (g-y0)_d (Ijspeert 2013, thesis eq. 6.5); 1 where |g-y0|_d < 1 mm
  Spatial,       ///< rotation taking (g-y0) onto (g'-y0') times the length ratio (no per-axis blow-up)
};

/// A sampled DMP output: n samples of D dimensions.
struct DmpRollout {
  Eigen::VectorXd t_s;  ///< n times [s], from 0
  Eigen::MatrixXd y;    ///< n x D positions [m]
  Eigen::MatrixXd yd;   ///< n x D velocities [m/s]
};

/// Intermediate values of imitate() (the reference library's names): demo
/// derivatives and the forcing-term targets the weights are fitted to.
struct DmpImitationTargets {
  Eigen::VectorXd z;    ///< phase per demo sample
  Eigen::MatrixXd yd;   ///< N x D demo velocity [m/s]
  Eigen::MatrixXd ydd;  ///< N x D demo acceleration [m/s^2]
  Eigen::MatrixXd f;    ///< N x D forcing targets
};

class Dmp {
 public:
  /// Parameters of a discrete DMP (this class and QuaternionDmp): formulation mode,
  /// basis, gains, regularisation.
  struct Options {
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
    static Options reference(double lambda) {
      Options c;
      c.mode = Mode::Reference;
      c.lambda = lambda;
      return c;
    }
    /// Throws InvalidInputError naming the bad field.
    void validate() const;
  };

  /// Learns a DMP from a demo sampled at times t_s (N, strictly increasing)
  /// with positions Y (N x D, finite). Needs N >= 3. Throws InvalidInputError.
  /// The DMP is configured to reproduce the demo (its start, goal, duration).
  static Dmp imitate(const Eigen::VectorXd& t_s, const Eigen::MatrixXd& Y, const Options& config);

  /// Re-targets: new start and goal [m] (D), duration [s] (nullopt: keep),
  /// optional start/goal velocity [m/s] (nullopt: the demo's, transformed; ignored in Reference mode).
  void configure(const Eigen::VectorXd& start, const Eigen::VectorXd& goal,
                 std::optional<double> duration_s = std::nullopt,
                 std::optional<Eigen::VectorXd> startVelocity = std::nullopt,
                 std::optional<Eigen::VectorXd> goalVelocity = std::nullopt);

  /// Integrates from t = 0 to the duration, output every dt_s [s] (the last
  /// sample at exactly the duration in Default mode; Reference mode uses the
  /// library's grid t_i = i dt, i < ceil((tau + dt) / dt)).
  DmpRollout rollout(double dt_s) const;
  /// Rollout at the demo's sample period (Reference mode: options().referenceDt_s).
  DmpRollout rollout() const;

  int dimensions() const { return static_cast<int>(weights_.rows()); }
  const Options& options() const { return config_; }
  const Eigen::MatrixXd& weights() const { return weights_; }   ///< D x N basis weights
  double lambda() const { return lambda_; }                    ///< ridge coefficient used
  double gcvError() const { return gcv_; }                     ///< GCV error at lambda (Default mode)
  const DmpImitationTargets& imitationTargets() const { return targets_; }
  Eigen::VectorXd basisCenters() const;                        ///< N phase values c_i
  Eigen::VectorXd basisWidths() const;                         ///< N widths h_i
  const Eigen::VectorXd& start() const { return start_; }
  const Eigen::VectorXd& goal() const { return goal_; }
  double duration_s() const { return duration_s_; }
  const Eigen::VectorXd& demoStart() const { return demoStart_; }
  const Eigen::VectorXd& demoGoal() const { return demoGoal_; }
  double demoDuration_s() const { return demoDuration_s_; }
  double demoSamplePeriod_s() const { return demoDt_s_; }

  /// Lossless JSON ("class": "srp::motion::Dmp", "schema_version": 1): a DMP
  /// read back rolls out bit-identically. Imitation targets are not stored.
  nlohmann::json toJson() const;
  /// Throws InvalidInputError on a wrong class, an unknown schema version or a bad field.
  static Dmp fromJson(const nlohmann::json& j);

 private:
  Dmp() = default;
  Eigen::MatrixXd forcingScale() const;

  Options config_;
  Eigen::MatrixXd weights_;
  double lambda_ = 0.0;
  double gcv_ = 0.0;
  DmpImitationTargets targets_;
  // Demo: start, goal, normalised start/goal velocities dy/ds, duration, sample period.
  Eigen::VectorXd demoStart_, demoGoal_, demoStartVel_s_, demoGoalVel_s_;
  double demoDuration_s_ = 1.0;
  double demoDt_s_ = 0.05;
  // Current configuration.
  Eigen::VectorXd start_, goal_, startVel_s_, goalVel_s_;
  double duration_s_ = 1.0;
};

std::string toString(ForcingScaling s);
ForcingScaling forcingScalingFromString(const std::string& text);

void to_json(nlohmann::json& j, const Dmp::Options& c);
void from_json(const nlohmann::json& j, Dmp::Options& c);

}  // namespace srp::motion
