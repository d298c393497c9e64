#pragma once
/// \file PlaneFit.h
/// \brief The support plane (table) in an organised cloud, by RANSAC.

#include <Eigen/Core>
#include <optional>
#include <opencv2/core.hpp>

#include "srp/core/Pose.h"

namespace srp::perception {

/// Plane n . p + d = 0 in the camera frame; n is a unit normal pointing to
/// the camera's side (d > 0), so n . p + d is the height of p above the plane [m].
struct Plane {
  Eigen::Vector3d n = Eigen::Vector3d::UnitZ();
  double d = 0.0;
  int inliers = 0;
  double height(const Eigen::Vector3d& p) const { return n.dot(p) + d; }
  /// A frame on the plane: origin = the foot of the camera's optical axis
  /// projected on the plane, z = n, x = the camera x axis projected on the plane.
  core::Pose3 X_camera_plane() const;
};

struct PlaneFitOptions {
  double inlierTol_m = 0.008;
  int iterations = 300;
  int sampleStride_px = 4;  ///< pixels between the samples RANSAC considers
  /// When set, only planes whose normal is within maxTilt_rad of this camera-frame direction.
  std::optional<Eigen::Vector3d> expectedNormal;
  double maxTilt_rad = 0.5;
  unsigned seed = 1;
};

/// The plane with the most inliers (refined by least squares on them);
/// nullopt when fewer than 3 valid points or no plane fits the constraint.
std::optional<Plane> fitDominantPlane(const cv::Mat& cloud, const PlaneFitOptions& options = {});

}  // namespace srp::perception
