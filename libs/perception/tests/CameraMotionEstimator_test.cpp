// CameraMotionEstimator against known camera poses (BoxWorld.h, a ray-cast
// table scene with a bin and boxes): a still camera is not reported as moved;
// a camera that pans and slides is, and its poses follow the rendered ones.
#include "srp/perception/CameraMotionEstimator.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "BoxWorld.h"
#include "srp/core/Error.h"

namespace srp::perception {
namespace {

using testing::BoxWorld;

constexpr double kStillTranslation_m = 1e-3;            // a still camera's largest estimated travel
constexpr double kStillRotation_rad = 0.05 * M_PI / 180;  // ... and turn
constexpr double kTranslation_m = 0.01;                 // a moving camera's pose against the rendered one
constexpr double kRotation_rad = 0.5 * M_PI / 180;
constexpr double kDepthNoise_m = 0.0015;                // the still camera's depth noise (sd)

BoxWorld scene() {
  BoxWorld w;
  w.boxes = testing::openBox({0.2, 0.1, 0.0}, {0.30, 0.22, 0.09}, 0.008, {128, 128, 128});
  w.boxes.push_back(testing::solidBox({-0.25, 0.05, 0.0}, {0.10, 0.06, 0.14}, {200, 90, 30}, 0.3));
  w.boxes.push_back(testing::solidBox({-0.1, 0.35, 0.0}, {0.2, 0.08, 0.25}, {40, 160, 40}, -0.2));
  return w;
}

const core::Pose3 kStart = testing::lookAt({0.0, -0.75, 0.65}, {0.0, 0.1, 0.0});

/// The camera of frame i: still until frame 10, then panning 0.3 deg a frame
/// about the vertical through its centre and sliding 4 mm a frame along the table's x.
core::Pose3 movingCamera(int i) {
  const int k = std::max(0, i - 10);
  core::Pose3 X = kStart;
  X.linear() = Eigen::AngleAxisd(k * 0.3 * M_PI / 180, Eigen::Vector3d::UnitZ()).toRotationMatrix() * kStart.linear();
  X.translation() += Eigen::Vector3d(0.004 * k, 0.0, 0.0);
  return X;
}

double angleOf(const core::Pose3& X) { return Eigen::AngleAxisd(X.linear()).angle(); }

TEST(CameraMotionEstimator, AStillCameraIsNotMoved) {
  const BoxWorld w = scene();
  const rawlog::RgbdFrame f0 = w.render(kStart, 0, 0.0);
  CameraMotionEstimator motion(f0.intrinsics);
  for (int i = 0; i < 15; ++i) {
    // Each frame with its own depth noise (sd kDepthNoise_m), as a real sensor's.
    rawlog::RgbdFrame f = f0;
    f.index = i;
    f.depth_m = f0.depth_m.clone();
    cv::Mat noise(f.depth_m.size(), CV_32FC1);
    cv::RNG(static_cast<std::uint64_t>(100 + i)).fill(noise, cv::RNG::NORMAL, 0.0, kDepthNoise_m);
    noise.setTo(0.0f, f0.depth_m <= 0.0f);  // no depth stays no depth
    f.depth_m += noise;
    motion.add(f);
  }
  EXPECT_FALSE(motion.moved());
  EXPECT_EQ(motion.movedAt(), -1);
  EXPECT_EQ(motion.poses().size(), 15u);
  EXPECT_LT(motion.maxTranslation_m(), kStillTranslation_m);
  EXPECT_LT(motion.maxRotation_rad(), kStillRotation_rad);
  EXPECT_EQ(motion.failures(), 0);
}

TEST(CameraMotionEstimator, APanningCameraIsNoticedAndFollowed) {
  const BoxWorld w = scene();
  CameraMotionEstimator motion(w.intrinsics);
  constexpr int kFrames = 30;
  for (int i = 0; i < kFrames; ++i) motion.add(w.render(movingCamera(i), i, i / 10.0));
  ASSERT_TRUE(motion.moved());
  // The rendered camera passes 0.5 deg at frame 12; while still, every checkStride-th frame is aligned.
  EXPECT_GE(motion.movedAt(), 11);
  EXPECT_LE(motion.movedAt(), 12 + motion.options().checkStride);
  double worstT = 0.0, worstR = 0.0;
  for (int i = 0; i < kFrames; ++i) {
    const core::Pose3 truth = kStart.inverse() * movingCamera(i);  // X_camera0_camera
    const core::Pose3 error = truth.inverse() * motion.poses()[static_cast<std::size_t>(i)];
    worstT = std::max(worstT, error.translation().norm());
    worstR = std::max(worstR, angleOf(error));
  }
  std::printf("[ figures  ] panning camera, 30 frames: worst pose error %.1f mm, %.2f deg\n", 1e3 * worstT,
              worstR * 180 / M_PI);
  EXPECT_LT(worstT, kTranslation_m);
  EXPECT_LT(worstR, kRotation_rad);
  const core::Pose3 last = kStart.inverse() * movingCamera(kFrames - 1);
  EXPECT_NEAR(motion.maxRotation_rad(), angleOf(last), kRotation_rad);
  EXPECT_NEAR(motion.maxTranslation_m(), last.translation().norm(), kTranslation_m);
}

TEST(CameraMotionEstimator, BadOptionsAreRefusedNamingThem) {
  CameraMotionEstimator::Options o;
  o.downscale = 0;
  try {
    CameraMotionEstimator motion(scene().intrinsics, o);
    FAIL() << "downscale 0 accepted";
  } catch (const core::InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("downscale 0"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace srp::perception
