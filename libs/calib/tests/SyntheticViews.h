#pragma once
// Test helper: renders a planar board image into a camera with ViSP-model
// radial distortion, by inverse mapping every output pixel to the board
// (undistort -> ray -> board plane -> board image) and bilinear sampling of a
// pre-blurred, finer board image (a cheap anti-aliasing).

#include <opencv2/imgproc.hpp>
#include <vector>

#include "srp/calib/CalibrationPattern.h"
#include "srp/calib/CameraCalibration.h"
#include "srp/core/Pose.h"

namespace srp::calib::test {

/// The viewing ray (x, y, 1) of every pixel of a distorted camera, row-major:
/// the same for every view, so computed once per camera.
inline std::vector<Eigen::Vector3d> pixelRays(const CameraCalibration& cam) {
  const auto& K = cam.intrinsics;
  std::vector<Eigen::Vector3d> rays;
  rays.reserve(static_cast<size_t>(K.width_px) * K.height_px);
  for (int v = 0; v < K.height_px; ++v)
    for (int u = 0; u < K.width_px; ++u) {
      const Eigen::Vector2d pu = cam.undistortPixel({double(u), double(v)});
      rays.emplace_back((pu.x() - K.cx_px) / K.fx_px, (pu.y() - K.cy_px) / K.fy_px, 1.0);
    }
  return rays;
}

inline cv::Mat renderBoardView(const CalibrationPattern::BoardImage& board, const CameraCalibration& cam,
                               const std::vector<Eigen::Vector3d>& rays, const srp::core::Pose3& X_camera_board,
                               unsigned char background = 140) {
  const auto& K = cam.intrinsics;
  cv::Mat blurred;
  cv::GaussianBlur(board.grey8, blurred, cv::Size(0, 0), 0.8);
  cv::Mat mapX(K.height_px, K.width_px, CV_32FC1), mapY(K.height_px, K.width_px, CV_32FC1);
  const Eigen::Matrix3d R = X_camera_board.linear();
  const Eigen::Vector3d t = X_camera_board.translation();
  const Eigen::Vector3d n = R.col(2);  // board normal in camera frame
  const double d = n.dot(t);
  for (int v = 0; v < K.height_px; ++v)
    for (int u = 0; u < K.width_px; ++u) {
      const Eigen::Vector3d& ray = rays[static_cast<size_t>(v) * K.width_px + u];
      const double s = d / n.dot(ray);
      float bx = -1e6f, by = -1e6f;
      if (s > 0) {
        const Eigen::Vector3d p_board = R.transpose() * (s * ray - t);
        bx = static_cast<float>(board.origin_px.x + p_board.x() * board.pixelsPerMetre);
        by = static_cast<float>(board.origin_px.y + p_board.y() * board.pixelsPerMetre);
      }
      mapX.at<float>(v, u) = bx;
      mapY.at<float>(v, u) = by;
    }
  cv::Mat out;
  cv::remap(blurred, out, mapX, mapY, cv::INTER_LINEAR, cv::BORDER_CONSTANT, cv::Scalar(background));
  return out;
}

inline cv::Mat renderBoardView(const CalibrationPattern::BoardImage& board, const CameraCalibration& cam,
                               const srp::core::Pose3& X_camera_board, unsigned char background = 140) {
  return renderBoardView(board, cam, pixelRays(cam), X_camera_board, background);
}

/// Camera pose looking at the board centre from `distance_m`, tilted by
/// (tiltX, tiltY) [rad] and rolled by `roll` about the optical axis.
inline srp::core::Pose3 viewOfBoard(const Eigen::Vector3d& boardCentre_board_m, double distance_m, double tiltX_rad,
                                    double tiltY_rad, double roll_rad, const Eigen::Vector2d& offset_m = {0, 0}) {
  using Eigen::AngleAxisd;
  using Eigen::Vector3d;
  const Eigen::Matrix3d R_camera_board = (AngleAxisd(roll_rad, Vector3d::UnitZ()) *
                                          AngleAxisd(tiltX_rad, Vector3d::UnitX()) *
                                          AngleAxisd(tiltY_rad, Vector3d::UnitY()))
                                             .toRotationMatrix();
  srp::core::Pose3 X = srp::core::Pose3::Identity();
  X.linear() = R_camera_board;
  // Board centre on the optical axis (plus an offset), at the distance.
  X.translation() = Vector3d(offset_m.x(), offset_m.y(), distance_m) - R_camera_board * boardCentre_board_m;
  return X;
}

}  // namespace srp::calib::test
