#include "srp/core/Pose.h"

#include <cmath>

namespace srp::core {

Pose3 makePose(const Eigen::Vector3d& translation_m, const Eigen::Quaterniond& rotation) {
  Pose3 X = Pose3::Identity();
  X.linear() = rotation.normalized().toRotationMatrix();
  X.translation() = translation_m;
  return X;
}

Pose3 makePoseYPR(const Eigen::Vector3d& translation_m, double yaw_rad, double pitch_rad,
                  double roll_rad) {
  const Eigen::Quaterniond q = Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ()) *
                               Eigen::AngleAxisd(pitch_rad, Eigen::Vector3d::UnitY()) *
                               Eigen::AngleAxisd(roll_rad, Eigen::Vector3d::UnitX());
  return makePose(translation_m, q);
}

double yawOf(const Eigen::Matrix3d& R) { return std::atan2(R(1, 0), R(0, 0)); }

double rotationAngleBetween(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
  return Eigen::AngleAxisd(a.transpose() * b).angle();
}

double translationDistance(const Pose3& a, const Pose3& b) {
  return (a.translation() - b.translation()).norm();
}

double angleDifference(double a_rad, double b_rad) {
  double d = std::remainder(a_rad - b_rad, 2.0 * M_PI);
  if (d <= -M_PI) d += 2.0 * M_PI;
  return d;
}

}  // namespace srp::core
