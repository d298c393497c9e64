#pragma once
/// \file Pose.h
/// \brief Rigid poses of srp, with the frame convention used everywhere.
///
/// Convention (as Drake's X_AB and ViSP's aMb): `X_A_B` is the pose of frame B
/// expressed in frame A. It maps a point from B coordinates to A coordinates,
/// `p_A = X_A_B * p_B`, and composes as `X_A_C = X_A_B * X_B_C`. Positions are
/// named `p_A_point` (metres); angles are radians. Common frames: `base` (robot
/// base), `camera` (optical frame: x right, y down, z forward), `table`,
/// `world`, `tag`, `hand`, `object`.

#include <Eigen/Geometry>

namespace srp::core {

/// A rigid transform (rotation + translation in metres).
using Pose3 = Eigen::Isometry3d;

/// Pose from a translation [m] and a unit quaternion (normalised here).
Pose3 makePose(const Eigen::Vector3d& translation_m, const Eigen::Quaterniond& rotation);

/// Pose from a translation [m] and yaw/pitch/roll [rad] about Z, Y, X
/// (R = Rz(yaw) Ry(pitch) Rx(roll), as MRPT's CPose3D).
Pose3 makePoseYPR(const Eigen::Vector3d& translation_m, double yaw_rad, double pitch_rad,
                  double roll_rad);

/// Yaw [rad] in (-pi, pi] of the ZYX decomposition R = Rz(yaw) Ry(pitch) Rx(roll).
double yawOf(const Eigen::Matrix3d& rotation);

/// Angle [rad] in [0, pi] of the rotation taking a to b.
double rotationAngleBetween(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b);

/// Euclidean distance [m] between the translations of two poses.
double translationDistance(const Pose3& a, const Pose3& b);

/// Smallest signed difference a - b [rad] of two angles, in (-pi, pi].
double angleDifference(double a_rad, double b_rad);

}  // namespace srp::core
