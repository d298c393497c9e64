#include "srp/synth/SceneRenderer.h"

#include <gtest/gtest.h>

#include <iostream>

#include "srp/core/Scene.h"
#include "srp/kb/ShapeMeshes.h"

namespace {

constexpr double kPositionTol_m = 2e-3;      // acceptance: back-projected depth vs truth
constexpr double kSurfaceTol_m = 1e-3;       // each back-projected pixel lies on the box surface
constexpr double kPixelCentroidTol_px = 0.15;  // pixel convention (a half-pixel shift would fail)

srp::core::Scene defaultScene() { return srp::core::Scene::load(std::string(SRP_SIM_DIR) + "/scenes/default.json"); }

double distanceToBoxSurface(const Eigen::Vector3d& p, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  const Eigen::Vector3d outside = (lo - p).cwiseMax(p - hi).cwiseMax(0.0);
  if (outside.norm() > 0.0) return outside.norm();
  return std::min((p - lo).minCoeff(), (hi - p).minCoeff());
}

// Renders a cuboid at a known pose on the table of the default scene,
// back-projects its pixels with the intrinsics and recovers its geometry.
TEST(SceneRenderer, BackProjectedDepthRecoversTheObjectPosition) {
  const auto scene = defaultScene();
  srp::synth::SceneRenderer renderer(scene.intrinsics);
  renderer.addBody("table", srp::kb::makeBoxMesh({-0.8, -0.6, -0.02}, {0.8, 0.6, 0.0}), {0.7, 0.7, 0.6});
  const Eigen::Vector3d lo(-0.025, -0.015, 0.0), hi(0.025, 0.015, 0.03);
  const int cuboid = renderer.addBody("cuboid", srp::kb::makeBoxMesh(lo, hi), {0.9, 0.2, 0.1});
  const srp::core::Pose3 X_world_cuboid = srp::core::makePoseYPR({0.083, 0.151, 0.0}, 0.52, 0.0, 0.0);
  renderer.setBodyPose(cuboid, X_world_cuboid);
  const auto frame = renderer.render(scene.X_world_camera);
  ASSERT_EQ(frame.depth_m.cols, scene.intrinsics.width_px);

  const srp::core::Pose3 X_cuboid_camera = X_world_cuboid.inverse() * scene.X_world_camera;
  Eigen::Vector3d topSum_object = Eigen::Vector3d::Zero();
  Eigen::Vector2d topPixelSum = Eigen::Vector2d::Zero();
  int topCount = 0, objectCount = 0;
  double worstSurface_m = 0.0;
  for (int v = 0; v < frame.depth_m.rows; ++v)
    for (int u = 0; u < frame.depth_m.cols; ++u) {
      const float d = frame.depth_m.at<float>(v, u);
      ASSERT_GT(d, 0.f) << "table must fill the view";
      const Eigen::Vector3d p_object = X_cuboid_camera * scene.intrinsics.backProject(u, v, d);
      if (p_object.z() < 0.002) continue;  // table
      ++objectCount;
      worstSurface_m = std::max(worstSurface_m, distanceToBoxSurface(p_object, lo, hi));
      if (std::abs(p_object.z() - hi.z()) < kSurfaceTol_m) {
        topSum_object += p_object;
        topPixelSum += Eigen::Vector2d(u, v);
        ++topCount;
      }
    }
  ASSERT_GT(topCount, 500);
  EXPECT_LT(worstSurface_m, kSurfaceTol_m) << "over " << objectCount << " object pixels";
  const Eigen::Vector3d topCentre_object = topSum_object / topCount;
  std::cout << "[measured] top-face centre error " << 1e3 * (topCentre_object - Eigen::Vector3d(0, 0, hi.z())).norm()
            << " mm, worst pixel off the surface " << 1e3 * worstSurface_m << " mm\n";
  EXPECT_LT((topCentre_object - Eigen::Vector3d(0, 0, hi.z())).norm(), kPositionTol_m)
      << "top-face centre in the object frame: " << topCentre_object.transpose();
  // The top face is parallel to the image plane: its pixel centroid is the
  // projection of its centre.
  const auto expected_px =
      scene.intrinsics.project(scene.X_world_camera.inverse() * X_world_cuboid * Eigen::Vector3d(0, 0, hi.z()));
  ASSERT_TRUE(expected_px);
  EXPECT_LT((topPixelSum / topCount - *expected_px).norm(), kPixelCentroidTol_px)
      << "pixel centroid " << (topPixelSum / topCount).transpose() << " expected " << expected_px->transpose();
}

TEST(SceneRenderer, ColourFollowsTheBodyColourAndVisibility) {
  srp::core::CameraIntrinsics K{200, 200, 79.5, 59.5, 160, 120};
  srp::synth::SceneRenderer renderer(K);
  renderer.setLighting({1.0, 0.0, Eigen::Vector3d(0, 0, 1)});  // ambient only: exact colours
  const int plane = renderer.addBody("plane", srp::kb::makeBoxMesh({-1, -1, 0}, {1, 1, 0.01}), {0.0, 1.0, 0.0});
  // Camera 1 m above, looking down (optical z = -world z).
  srp::core::Pose3 X_world_camera = srp::core::makePose({0, 0, 1}, Eigen::Quaterniond(0, 1, 0, 0));
  auto frame = renderer.render(X_world_camera);
  const cv::Vec3b centre = frame.colour_bgr8.at<cv::Vec3b>(60, 80);
  EXPECT_LT(centre[0], 10);   // B
  EXPECT_GT(centre[1], 245);  // G
  EXPECT_LT(centre[2], 10);   // R
  EXPECT_NEAR(frame.depth_m.at<float>(60, 80), 0.99f, 5e-4f);
  renderer.setBodyVisible(plane, false);
  frame = renderer.render(X_world_camera);
  EXPECT_EQ(frame.depth_m.at<float>(60, 80), 0.f);
}

// The light's colour scales each channel of what it lights; white leaves the image as without it.
TEST(SceneRenderer, LightColourScalesEachChannel) {
  constexpr double kLevelTol = 2.0;  // 8-bit rounding
  srp::core::CameraIntrinsics K{200, 200, 79.5, 59.5, 160, 120};
  const srp::core::Pose3 X_world_camera = srp::core::makePose({0, 0, 1}, Eigen::Quaterniond(0, 1, 0, 0));
  const srp::core::SceneLighting ambientOnly{0.8, 0.0, Eigen::Vector3d(0, 0, 1)};
  auto centre = [&](const Eigen::Vector3d* rgb) {
    srp::synth::SceneRenderer renderer(K);
    if (rgb)
      renderer.setLighting(ambientOnly, *rgb);
    else
      renderer.setLighting(ambientOnly);
    renderer.addBody("plane", srp::kb::makeBoxMesh({-1, -1, 0}, {1, 1, 0.01}), {1.0, 1.0, 1.0});
    const cv::Mat colour = renderer.render(X_world_camera).colour_bgr8;
    return std::make_pair(colour.at<cv::Vec3b>(60, 80), colour);
  };
  const Eigen::Vector3d white = Eigen::Vector3d::Ones(), warm(1.0, 0.9, 0.78);
  const auto [plain, plainImage] = centre(nullptr);
  const auto [whiteLit, whiteImage] = centre(&white);
  const auto [warmLit, warmImage] = centre(&warm);
  EXPECT_EQ(cv::norm(plainImage, whiteImage, cv::NORM_INF), 0.0) << "white: the same image, byte for byte";
  EXPECT_NEAR(plain[2], 0.8 * 255, kLevelTol);  // R
  EXPECT_NEAR(warmLit[2], 0.8 * 255, kLevelTol);
  EXPECT_NEAR(warmLit[1], 0.8 * 0.9 * 255, kLevelTol);  // G
  EXPECT_NEAR(warmLit[0], 0.8 * 0.78 * 255, kLevelTol);  // B
}

}  // namespace
