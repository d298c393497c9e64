#pragma once
/// \file QuaternionDmp.h
/// \brief Discrete DMP for orientations (unit quaternions), for the tool's
/// orientation during Reach/Move (Ude et al. 2014 formulation).
///
/// In normalised time s = t / tau: eta' = alpha (beta 2 log(g * conj(q)) +
/// (eta_g - eta)) + f(z), q' = 1/2 eta * q, where eta = tau omega is the
/// angular velocity [rad per unit s] in the fixed frame (the frame the
/// orientations are expressed in, e.g. "camera"), log the quaternion
/// logarithm (rotation vector / 2) and f the same Gaussian-basis forcing term
/// as srp::motion::Dmp (one per rotation axis). Quaternions are (w, x, y, z),
/// mapping the body frame to the fixed frame.
///
/// Use: imitate(t_s, q), then configure(q_start, q_goal, duration) and
/// rollout(dt) -> times, quaternions and angular velocities [rad/s].

#include <Eigen/Geometry>
#include <nlohmann/json.hpp>
#include <optional>
#include <vector>

#include "srp/motion/Dmp.h"

namespace srp::motion {

struct QuaternionDmpRollout {
  Eigen::VectorXd t_s;                  ///< n times [s], from 0
  std::vector<Eigen::Quaterniond> q;    ///< n orientations
  Eigen::MatrixXd omega_radps;          ///< n x 3 angular velocity in the fixed frame [rad/s]
};

class QuaternionDmp {
 public:
  /// Learns from N >= 3 orientations at strictly increasing times (Default
  /// mode formulation; a Reference-mode config is rejected: the reference
  /// library's DMP has no orientation part in the thesis' use).
  static QuaternionDmp imitate(const Eigen::VectorXd& t_s, const std::vector<Eigen::Quaterniond>& q,
                               const Dmp::Options& config);

  /// New start and goal orientation, optional duration [s]; start/goal angular
  /// velocities are the demo's (pass zero vectors to start/stop at rest).
  void configure(const Eigen::Quaterniond& start, const Eigen::Quaterniond& goal,
                 std::optional<double> duration_s = std::nullopt,
                 std::optional<Eigen::Vector3d> startOmega_radps = std::nullopt,
                 std::optional<Eigen::Vector3d> goalOmega_radps = std::nullopt);

  /// Orientation every dt_s from 0 to the duration (last sample at the duration).
  QuaternionDmpRollout rollout(double dt_s) const;

  const Eigen::MatrixXd& weights() const { return weights_; }  ///< 3 x N
  double lambda() const { return lambda_; }
  double duration_s() const { return duration_s_; }
  double demoDuration_s() const { return demoDuration_s_; }
  const Eigen::Quaterniond& start() const { return start_; }
  const Eigen::Quaterniond& goal() const { return goal_; }

  /// Lossless JSON ("class": "srp::motion::QuaternionDmp", "schema_version": 1).
  nlohmann::json toJson() const;
  static QuaternionDmp fromJson(const nlohmann::json& j);

 private:
  QuaternionDmp() = default;
  Dmp::Options config_;
  Eigen::MatrixXd weights_;
  double lambda_ = 0.0;
  Eigen::Quaterniond demoStart_, demoGoal_, start_, goal_;
  Eigen::Vector3d startEta_ = Eigen::Vector3d::Zero(), goalEta_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d demoStartEta_ = Eigen::Vector3d::Zero(), demoGoalEta_ = Eigen::Vector3d::Zero();
  double demoDuration_s_ = 1.0, duration_s_ = 1.0;
};

}  // namespace srp::motion
