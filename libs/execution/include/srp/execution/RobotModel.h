#pragma once
/// \file RobotModel.h
/// \brief The 6-joint serial arm of the simulated cell (a UR5) read from a URDF:
/// kinematics, joint limits and lumped rigid-body inertias per moving link.
///
/// Frames: `base` is the URDF root link (`base_link`, ROS convention), each link
/// frame is its URDF link frame, every joint rotates about its own z axis. The
/// fixed links below the last joint (flange, tool0, the tool, tcp) are lumped into
/// the last moving link; their frames are kept as fixed offsets from it.
/// Units: metres, radians, kilograms, seconds.

#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

#include "srp/core/Pose.h"

namespace srp::execution {

/// Joint positions [rad] of the six arm joints, base to wrist.
using JointVector = Eigen::Matrix<double, 6, 1>;

/// One revolute joint of the arm (axis = z of its joint frame).
struct ArmJoint {
  std::string name;
  std::string parentLink;
  std::string childLink;
  srp::core::Pose3 X_parent_joint;  ///< joint frame (= child link frame at q = 0) in the parent link
  double lower_rad = 0.0;
  double upper_rad = 0.0;
  double maxVelocity_radps = 0.0;
  double maxEffort_Nm = 0.0;
};

/// Rigid-body inertia of one link in its own frame (fixed children lumped in).
struct LinkInertia {
  std::string name;
  double mass_kg = 0.0;
  Eigen::Vector3d p_link_com_m = Eigen::Vector3d::Zero();
  Eigen::Matrix3d I_com_kgm2 = Eigen::Matrix3d::Zero();  ///< about the centre of mass, link axes
  std::string collisionMesh;  ///< absolute path of the link's collision mesh, "" if none
  srp::core::Pose3 X_link_mesh = srp::core::Pose3::Identity();
};

/// A UR-type arm read from URDF with urdfdom. Immutable after construction.
class RobotModel {
 public:
  /// Reads `urdfPath`; mesh paths are resolved relative to the URDF's folder.
  /// Throws FileError when the file is missing or not URDF, InvalidInputError when
  /// the chain from the root is not six revolute joints ending in `tool0` and `tcp`.
  static RobotModel fromUrdf(const std::string& urdfPath);

  /// The shipped UR5, `sim/ur5/ur5.urdf` of srp's data folder (core::DataPaths).
  static RobotModel defaultUr5();

  const std::array<ArmJoint, 6>& joints() const { return joints_; }
  /// Link inertias: [0] base link, [1..6] the links moved by joints 1..6.
  const std::array<LinkInertia, 7>& links() const { return links_; }
  const std::string& name() const { return name_; }

  /// Pose of tool0 (flange, ROS convention) in the last moving link.
  const srp::core::Pose3& X_wrist3_tool0() const { return X_wrist3_tool0_; }
  /// Pose of the tool centre point in the last moving link.
  const srp::core::Pose3& X_wrist3_tcp() const { return X_wrist3_tcp_; }
  /// Pose of the tool centre point in tool0 (the tool's length along z).
  srp::core::Pose3 X_tool0_tcp() const { return X_wrist3_tool0_.inverse() * X_wrist3_tcp_; }

  /// Poses of the 7 links ([0] = base) in the base frame at joint positions q.
  std::array<srp::core::Pose3, 7> linkPoses(const JointVector& q) const;
  /// Forward kinematics: pose of tool0 in the base frame.
  srp::core::Pose3 X_base_tool0(const JointVector& q) const;
  /// Forward kinematics: pose of the tool centre point in the base frame.
  srp::core::Pose3 X_base_tcp(const JointVector& q) const;

  /// True when every joint is within its position limits (inclusive).
  bool withinLimits(const JointVector& q) const;
  JointVector lowerLimits_rad() const;
  JointVector upperLimits_rad() const;
  JointVector maxVelocities_radps() const;

 private:
  std::string name_;
  std::array<ArmJoint, 6> joints_;
  std::array<LinkInertia, 7> links_;
  srp::core::Pose3 X_wrist3_tool0_ = srp::core::Pose3::Identity();
  srp::core::Pose3 X_wrist3_tcp_ = srp::core::Pose3::Identity();
};

}  // namespace srp::execution
