#pragma once
// Internal: OpenCV's (rvec, tvec) pose pairs as srp poses.

#include <opencv2/calib3d.hpp>

#include "srp/core/Pose.h"

namespace srp::calib::detail {

/// X_camera_object from the rotation vector and translation of solvePnP / calibrateCamera.
inline core::Pose3 poseFromRvecTvec(const cv::Mat& rvec, const cv::Mat& tvec) {
  cv::Mat R;
  cv::Rodrigues(rvec, R);
  core::Pose3 X = core::Pose3::Identity();
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) X.matrix()(r, c) = R.at<double>(r, c);
    X.matrix()(r, 3) = tvec.at<double>(r);
  }
  return X;
}

}  // namespace srp::calib::detail
