#pragma once
/// \file SafetyChecker.h
/// \brief Checks a joint trajectory before the arm moves: joint position limits,
/// joint velocity limits, joint acceleration limits, the tool centre point inside a workspace box, the arm
/// above the table plane and clear of the containers. A violation refuses the
/// whole trajectory with a message naming the check, the joint or link, the time
/// and the values; nothing is ever clipped silently.
///
/// The arm is approximated by spheres along its links (radii from the UR5's
/// published link radii, 0.045-0.06 m) and the tool by spheres on its axis.
/// Frames: `world` = table frame (z up, table top at z = 0); the robot base pose
/// X_world_base comes from the scene.

#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <vector>

#include "srp/execution/CellDescription.h"
#include "srp/execution/JointTrajectory.h"
#include "srp/execution/RobotModel.h"

namespace srp::execution {

struct SafetyLimits {
  /// Allowed region of the tool centre point in the world frame.
  Eigen::AlignedBox3d workspace_world_m{Eigen::Vector3d(-1.5, -1.5, 0.0), Eigen::Vector3d(1.5, 1.5, 1.2)};
  double tableClearance_m = 0.005;     ///< minimum gap between any arm sphere and the table top
  double obstacleClearance_m = 0.002;  ///< minimum gap between arm spheres and container walls
  double velocityFraction = 1.0;       ///< fraction of the URDF velocity limits allowed
  /// Largest joint acceleration allowed, every joint [rad/s^2]. The UR5's URDF data
  /// (../shared/robots/ur5/joint_limits.yaml: "acceleration limits are not publicly
  /// available") has none; 5.0 rad/s^2 is the limit Universal Robots' own ROS 2 driver
  /// gives MoveIt for time parametrisation of every UR arm, "chosen conservatively"
  /// (Universal_Robots_ROS2_Driver, ur_moveit_config/config/joint_limits.yaml).
  /// Measured on the spline the controller replays (see check()).
  double maxAcceleration_radps2 = 5.0;
};

struct SafetyViolation {
  std::string check;  ///< "joint limit", "velocity limit", "workspace", "table", "collision"
  std::size_t sampleIndex = 0;
  double t_s = 0.0;
  std::string message;  ///< full sentence naming the step, values and limits
};

/// A sphere of the arm's collision approximation, in the world frame.
struct ArmSphere {
  std::string link;
  Eigen::Vector3d centre_world_m;
  double radius_m = 0.0;
};

class SafetyChecker {
 public:
  SafetyChecker(RobotModel model, const srp::core::Pose3& X_world_base, SafetyLimits limits,
                std::vector<WorldBox> obstacles);

  /// First violation along the trajectory, or nullopt when it is safe. `what` names
  /// the motion in the message ("Reach of cuboid"). Accelerations are those of the
  /// cubic Hermite spline through the samples (JointTrajectory::at, the spline that
  /// servoj and a ROS joint trajectory controller replay): exact at both ends of every
  /// interval, where a cubic's second derivative peaks.
  std::optional<SafetyViolation> check(const JointTrajectory& trajectory, const std::string& what) const;

  /// Largest ratio of a joint's speed to its allowed speed along the trajectory
  /// (spline velocity and chord between samples, as check() measures them);
  /// above 1 the trajectory breaks the velocity limit.
  double peakVelocityRatio(const JointTrajectory& trajectory) const;

  /// Largest ratio of a joint's spline acceleration to maxAcceleration_radps2 along
  /// the trajectory; above 1 the trajectory breaks the acceleration limit. Slowing
  /// the whole trajectory down by a factor k divides it by k^2.
  double peakAccelerationRatio(const JointTrajectory& trajectory) const;

  /// Largest |joint acceleration| [rad/s^2] of the cubic Hermite spline through the
  /// samples, any joint (0 for fewer than two samples).
  static double peakSplineAcceleration_radps2(const JointTrajectory& trajectory);

  /// |acceleration| [rad/s^2] of `joint` on the cubic Hermite spline at knot k, the larger
  /// of the intervals ending and starting there (what check() compares with the limit).
  static double splineAcceleration_radps2(const JointTrajectory& trajectory, std::size_t k, int joint);

  /// Speed [rad/s] of `joint` at knot k as check() measures it: the knot velocity and the
  /// chord from the knot before.
  static double jointSpeed_radps(const JointTrajectory& trajectory, std::size_t k, int joint);

  /// First violation of one configuration (limits, workspace, table, obstacles).
  std::optional<SafetyViolation> checkConfiguration(const JointVector& q, const std::string& what) const;

  /// The arm's collision spheres at q (links below the shoulder excluded: they stand on the table).
  std::vector<ArmSphere> armSpheres(const JointVector& q) const;

  /// Smallest gap [m] between the arm spheres and the table top at q (negative: penetration).
  double tableClearance_m(const JointVector& q) const;

  const SafetyLimits& limits() const { return limits_; }
  /// Allowed joint speeds [rad/s]: the URDF limits x SafetyLimits::velocityFraction.
  JointVector maxVelocities_radps() const;

 private:
  RobotModel model_;
  srp::core::Pose3 X_world_base_;
  SafetyLimits limits_;
  std::vector<WorldBox> obstacles_;
};

}  // namespace srp::execution
