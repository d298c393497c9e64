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
/// (identity for the demo; DmpConfig::scaling when re-targeted).
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

#include "srp/motion/DmpConfig.h"

namespace srp::motion {

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
  /// Learns a DMP from a demo sampled at times t_s (N, strictly increasing)
  /// with positions Y (N x D, finite). Needs N >= 3. Throws InvalidInputError.
  /// The DMP is configured to reproduce the demo (its start, goal, duration).
  static Dmp imitate(const Eigen::VectorXd& t_s, const Eigen::MatrixXd& Y, const DmpConfig& config);

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
  /// Rollout at the demo's sample period (Reference mode: config.referenceDt_s).
  DmpRollout rollout() const;

  int dimensions() const { return static_cast<int>(weights_.rows()); }
  const DmpConfig& config() const { return config_; }
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

  DmpConfig config_;
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

}  // namespace srp::motion
