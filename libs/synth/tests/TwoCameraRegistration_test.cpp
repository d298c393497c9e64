// Depth registration (srp::rawlog::DepthRegistration) against exact geometry:
// one scene rendered by two synthetic cameras of an RGB-D sensor whose depth
// is not registered to colour (640x480 depth, 1280x720 colour, other intrinsics,
// a 15 mm baseline and a 0.4 degree turn).
#include <gtest/gtest.h>

#include <iostream>
#include <opencv2/imgproc.hpp>

#include "srp/core/Scene.h"
#include "srp/kb/ShapeMeshes.h"
#include "srp/rawlog/DepthRegistration.h"
#include "srp/synth/SceneRenderer.h"

namespace {

constexpr double kDepthTol_m = 1e-3;  // acceptance: 1 mm ...
constexpr int kPixelTol_px = 1;       // ... within 1 px
constexpr double kMaxOffFraction = 1e-4;   // pixels beyond 1 px / 1 mm (silhouettes; measured 3.5e-5)
constexpr double kMaxHoleFraction = 1e-5;  // seen by the depth camera but left empty (measured 3e-6)
constexpr double kSeenTol_m = 0.01;   // a colour pixel's point is seen by the depth camera when its depth matches

struct TwoCameraScene {
  srp::core::Scene scene = srp::core::Scene::load(std::string(SRP_SIM_DIR) + "/scenes/default.json");
  srp::core::CameraIntrinsics Kc{910.0, 912.0, 641.3, 358.2, 1280, 720};  // colour (RealSense D435-like)
  srp::core::CameraIntrinsics Kd{385.0, 385.0, 318.7, 241.6, 640, 480};   // depth
  srp::core::Pose3 X_colour_depth = srp::core::Pose3::Identity();
  TwoCameraScene() {
    X_colour_depth.translation() = Eigen::Vector3d(-0.015, 0.0003, 0.0002);
    X_colour_depth.linear() = (Eigen::AngleAxisd(0.006, Eigen::Vector3d::UnitY()) *
                               Eigen::AngleAxisd(-0.004, Eigen::Vector3d::UnitX()))
                                  .toRotationMatrix();
  }
  void addBodies(srp::synth::SceneRenderer& r) const {
    r.addBody("table", srp::kb::makeBoxMesh({-0.8, -0.6, -0.02}, {0.8, 0.6, 0.0}), {0.7, 0.7, 0.6});
    const int cube = r.addBody("cube", srp::kb::makeBoxMesh({-0.02, -0.02, 0.0}, {0.02, 0.02, 0.04}), {0.9, 0.2, 0.1});
    r.setBodyPose(cube, srp::core::makePoseYPR({0.05, 0.12, 0.0}, 0.4, 0.0, 0.0));
    const int tall = r.addBody("tall", srp::kb::makeBoxMesh({-0.015, -0.03, 0.0}, {0.015, 0.03, 0.12}), {0.1, 0.3, 0.9});
    r.setBodyPose(tall, srp::core::makePoseYPR({-0.08, 0.05, 0.0}, -0.3, 0.0, 0.0));
    const int plate = r.addBody("slanted", srp::kb::makeBoxMesh({-0.05, -0.04, 0.0}, {0.05, 0.04, 0.004}), {0.2, 0.8, 0.2});
    r.setBodyPose(plate, srp::core::makePoseYPR({0.12, 0.0, 0.05}, 0.2, 0.5, 0.3));
  }
};

}  // namespace

TEST(TwoCameraRegistration, RegisteredDepthMatchesTheColourCamerasOwnRender) {
  const TwoCameraScene s;
  const srp::core::Pose3 X_world_colour = s.scene.X_world_camera;
  const srp::core::Pose3 X_world_depth = X_world_colour * s.X_colour_depth;
  // Both renderers alive in one thread, of different sizes (SceneRenderer
  // makes its own EGL context current before rendering).
  srp::synth::SceneRenderer colourRenderer(s.Kc), depthRenderer(s.Kd);
  s.addBodies(colourRenderer);
  s.addBodies(depthRenderer);
  const cv::Mat depth = depthRenderer.render(X_world_depth).depth_m;
  const cv::Mat truth = colourRenderer.render(X_world_colour).depth_m;
  // The renderer draws ideal pinhole images, so the colour camera is given no distortion.
  const srp::rawlog::DepthRegistration reg({s.Kd, {}}, {s.Kc, {}}, s.X_colour_depth);
  const cv::Mat registered = reg.registerDepth(depth);
  ASSERT_EQ(registered.cols, s.Kc.width_px);
  ASSERT_EQ(registered.rows, s.Kc.height_px);

  const srp::core::Pose3 X_depth_colour = s.X_colour_depth.inverse();
  const auto seenByDepthCamera = [&](int u, int v) {
    const float z = truth.at<float>(v, u);
    if (!(z > 0.f)) return false;
    const Eigen::Vector3d p_depth = X_depth_colour * s.Kc.backProject(u, v, z);
    const auto uv = s.Kd.project(p_depth);
    if (!uv) return false;
    const int ud = static_cast<int>(std::lround(uv->x())), vd = static_cast<int>(std::lround(uv->y()));
    if (ud < 0 || vd < 0 || ud >= s.Kd.width_px || vd >= s.Kd.height_px) return false;
    const float zd = depth.at<float>(vd, ud);
    return zd > 0.f && std::abs(zd - p_depth.z()) < kSeenTol_m;
  };
  cv::Mat seen(truth.size(), CV_8UC1, cv::Scalar(0));
  for (int v = 0; v < truth.rows; ++v)
    for (int u = 0; u < truth.cols; ++u) seen.at<uchar>(v, u) = seenByDepthCamera(u, v) ? 255 : 0;
  // Pixels the depth camera cannot see, grown by the pixel tolerance: holes are allowed there.
  cv::Mat unseenRim;
  cv::dilate(seen == 0, unseenRim, cv::Mat::ones(2 * kPixelTol_px + 1, 2 * kPixelTol_px + 1, CV_8UC1));

  int registeredPixels = 0, offPixels = 0, offAt2px = 0, exactPixels = 0, holes = 0, seenPixels = 0, allowedHoles = 0;
  double worstOff_m = 0.0;
  for (int v = 0; v < truth.rows; ++v)
    for (int u = 0; u < truth.cols; ++u) {
      const float z = registered.at<float>(v, u);
      if (seen.at<uchar>(v, u)) ++seenPixels;
      if (!(z > 0.f)) {
        if (seen.at<uchar>(v, u)) (unseenRim.at<uchar>(v, u) ? ++allowedHoles : ++holes);
        continue;
      }
      ++registeredPixels;
      if (std::abs(truth.at<float>(v, u) - z) <= kDepthTol_m) ++exactPixels;
      // Off by how much from the truth depths within `radius` pixels: 0 when
      // it lies between their lowest and highest (the surface takes that
      // value at some point within the radius, by continuity), else the
      // distance to the nearer bound.
      const auto offFromTruth_m = [&](int radius) {
        double lo = 1e9, hi = -1e9;
        for (int dv = -radius; dv <= radius; ++dv)
          for (int du = -radius; du <= radius; ++du) {
            const int uu = u + du, vv = v + dv;
            if (uu < 0 || vv < 0 || uu >= truth.cols || vv >= truth.rows) continue;
            const float t = truth.at<float>(vv, uu);
            if (t > 0.f) lo = std::min(lo, static_cast<double>(t)), hi = std::max(hi, static_cast<double>(t));
          }
        return lo > hi ? 1e9 : std::max({0.0, lo - z, z - hi});
      };
      const double off = offFromTruth_m(kPixelTol_px);
      worstOff_m = std::max(worstOff_m, off);
      if (off > kDepthTol_m) {
        ++offPixels;
        if (offFromTruth_m(2 * kPixelTol_px) > kDepthTol_m) ++offAt2px;
      }
    }
  std::cout << "[measured] registered " << registeredPixels << " colour pixels of " << truth.total() << "; "
            << 100.0 * exactPixels / registeredPixels << " % within 1 mm at the same pixel, " << offPixels
            <<  " farther than 1 mm from the truth within 1 px (worst " << 1e3 * worstOff_m << " mm), " << offAt2px
            << " farther within 2 px; "
            << "seen by the depth camera " << seenPixels << ", holes there " << holes << " (+" << allowedHoles
            << " within 1 px of what it cannot see)\n";
  EXPECT_GT(registeredPixels, static_cast<int>(0.8 * truth.total()));
  // Within 1 px and 1 mm but at a few silhouette pixels, where a depth pixel
  // (2.4 colour pixels wide) and the parallax at the jump leave the edge
  // uncertain by its footprint: those are within 2 px.
  EXPECT_LT(offPixels, static_cast<int>(kMaxOffFraction * registeredPixels));
  EXPECT_EQ(offAt2px, 0);
  EXPECT_LT(holes, static_cast<int>(kMaxHoleFraction * seenPixels));
}
