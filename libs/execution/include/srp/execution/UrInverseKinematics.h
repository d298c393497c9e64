#pragma once
/// \file UrInverseKinematics.h
/// \brief Closed-form inverse kinematics of a UR-geometry arm (Hawkins' analytic
/// solution on the Denavit-Hartenberg model), up to eight solutions per pose.
///
/// The DH lengths d1, a2, a3, d4, d5, d6 are read from the RobotModel's joint
/// origins (nothing hard-coded), and the constant offset between the DH frame 6
/// and the URDF's tool0 is measured once from the model, so IK inverts exactly
/// RobotModel::X_base_tool0. Poses are in the arm's base frame (metres, radians).

#include <optional>
#include <vector>

#include "srp/execution/RobotModel.h"

namespace srp::execution {

/// Denavit-Hartenberg lengths of a UR arm [m] (a2, a3 negative as UR publishes them).
struct UrDhParameters {
  double d1_m = 0.0, a2_m = 0.0, a3_m = 0.0, d4_m = 0.0, d5_m = 0.0, d6_m = 0.0;
};

class UrInverseKinematics {
 public:
  /// Throws InvalidInputError if the model's joint origins are not of UR geometry.
  explicit UrInverseKinematics(const RobotModel& model);

  const UrDhParameters& dh() const { return dh_; }

  /// Forward kinematics of the DH model: pose of tool0 in the base frame.
  srp::core::Pose3 forwardTool0(const JointVector& q) const;

  /// All solutions (up to 8, each joint wrapped to (-pi, pi]) placing tool0 at
  /// X_base_tool0; empty when the pose is out of reach. Near the wrist singularity
  /// (|sin q5| < 1e-9) q6 is taken from `q6Hint_rad`.
  std::vector<JointVector> solveAll(const srp::core::Pose3& X_base_tool0,
                                    double q6Hint_rad = 0.0) const;

  /// The solution nearest to q_current (each joint shifted by multiples of 2 pi
  /// towards q_current, within the model's limits); nullopt when unreachable or
  /// no solution lies within the joint limits.
  std::optional<JointVector> solveNearest(const srp::core::Pose3& X_base_tool0,
                                          const JointVector& q_current) const;

  /// As solveNearest, for a pose of the tool centre point instead of tool0.
  std::optional<JointVector> solveNearestTcp(const srp::core::Pose3& X_base_tcp,
                                             const JointVector& q_current) const;

 private:
  RobotModel model_;
  UrDhParameters dh_;
  srp::core::Pose3 X_dh6_tool0_ = srp::core::Pose3::Identity();
  srp::core::Pose3 X_base_dh0_ = srp::core::Pose3::Identity();
};

}  // namespace srp::execution
