#pragma once
/// \file DepthCloud.h
/// \brief The organised point cloud of a depth image: one camera-frame point
/// per pixel, by pinhole back-projection through CameraModel.

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "srp/perception/CameraModel.h"

namespace srp::perception {

/// Points [m] in the camera optical frame, CV_32FC3, same size as the depth
/// image; z = 0 where depth is invalid (0, NaN or beyond maxDepth_m).
cv::Mat depthToCloud(const cv::Mat& depth_m, const CameraModel& camera, double maxDepth_m = 10.0);

/// The same into `cloud`, whose memory is reused when it already has the
/// size and type (a frame loop: no fresh 3.7 MB, no page faults, per frame).
void depthToCloud(const cv::Mat& depth_m, const CameraModel& camera, cv::Mat& cloud, double maxDepth_m = 10.0);

/// The cloud point at pixel (u, v) (integer), or nullopt-like zero z when invalid.
inline Eigen::Vector3d cloudAt(const cv::Mat& cloud, int u, int v) {
  const cv::Vec3f& p = cloud.at<cv::Vec3f>(v, u);
  return {p[0], p[1], p[2]};
}

}  // namespace srp::perception
