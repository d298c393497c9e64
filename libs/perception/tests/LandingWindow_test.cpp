// landingWindow against the pixels that do land, found by projecting every pixel of a drawn depth image.
#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/imgproc.hpp>

#include "srp/perception/LandingWindow.h"

namespace srp::perception {
namespace {

/// A drawn scene in the source camera: a table 0.9 m away with a box 0.45 m away on it.
cv::Mat drawnDepth_m(const core::CameraIntrinsics& k) {
  cv::Mat depth(k.height_px, k.width_px, CV_32FC1, cv::Scalar(0.9f));
  cv::rectangle(depth, cv::Rect(k.width_px / 3, k.height_px / 3, k.width_px / 5, k.height_px / 4), cv::Scalar(0.45f),
                cv::FILLED);
  return depth;
}

/// The source pixels whose point lands in the destination image (the warp's rule: in front of the
/// camera, rounded pixel inside), and whether all lie inside `window`.
bool allLandInside(const cv::Mat& depth_m, const core::CameraIntrinsics& Ks, const core::Pose3& X_dst_src,
                   const core::CameraIntrinsics& Kd, const cv::Rect& window, int& landed) {
  landed = 0;
  bool inside = true;
  for (int v = 0; v < depth_m.rows; ++v)
    for (int u = 0; u < depth_m.cols; ++u) {
      const double z = depth_m.at<float>(v, u);
      const Eigen::Vector3d q = X_dst_src * Ks.backProject(u, v, z);
      if (q.z() <= 0.0) continue;
      const double ud = Kd.fx_px * q.x() / q.z() + Kd.cx_px, vd = Kd.fy_px * q.y() / q.z() + Kd.cy_px;
      if (std::lround(ud) < 0 || std::lround(ud) >= Kd.width_px || std::lround(vd) < 0 || std::lround(vd) >= Kd.height_px)
        continue;
      ++landed;
      inside = inside && window.contains({u, v});
    }
  return inside;
}

// A widened source image (a moving camera's background) warped into a camera that swayed by a few
// centimetres and degrees: every pixel that lands is inside the window, and the window leaves out
// much of the widened margin.
TEST(LandingWindow, HoldsEveryPixelThatLands) {
  const core::CameraIntrinsics Kd{525.0, 525.0, 319.5, 239.5, 640, 480};
  core::CameraIntrinsics Ks = Kd;
  Ks.width_px = 832;
  Ks.height_px = 624;
  Ks.cx_px += 96;
  Ks.cy_px += 72;
  const cv::Mat depth = drawnDepth_m(Ks);
  int checked = 0;
  for (const double turn_deg : {-4.0, 0.0, 3.0})
    for (const double shift_m : {-0.05, 0.02}) {
      const core::Pose3 X_dst_src =
          core::makePose(Eigen::Vector3d(shift_m, -0.5 * shift_m, 0.3 * shift_m),
                         Eigen::Quaterniond(Eigen::AngleAxisd(turn_deg * M_PI / 180.0, Eigen::Vector3d(0.3, 1, 0.2).normalized())));
      const cv::Rect window = landingWindow(Ks, 0.45f, 0.9f, X_dst_src, Kd);
      int landed = 0;
      EXPECT_TRUE(allLandInside(depth, Ks, X_dst_src, Kd, window, landed))
          << "turn " << turn_deg << " deg, shift " << shift_m << " m";
      EXPECT_GT(landed, Kd.width_px * Kd.height_px / 2);
      EXPECT_LT(window.area(), Ks.width_px * Ks.height_px * 9 / 10);  // the margin mostly left out
      ++checked;
    }
  EXPECT_EQ(checked, 6);
}

// No valid depth range, or a destination camera facing away: the whole source image.
TEST(LandingWindow, WholeImageWhenNoBoundHolds) {
  const core::CameraIntrinsics K{525.0, 525.0, 319.5, 239.5, 640, 480};
  const cv::Rect whole(0, 0, 640, 480);
  EXPECT_EQ(landingWindow(K, 0.f, 0.f, core::Pose3::Identity(), K), whole);
  const core::Pose3 facingAway =
      core::makePose(Eigen::Vector3d::Zero(), Eigen::Quaterniond(Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitY())));
  EXPECT_EQ(landingWindow(K, 0.5f, 1.0f, facingAway, K), whole);
}

}  // namespace
}  // namespace srp::perception
