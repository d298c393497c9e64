#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <opencv2/imgcodecs.hpp>

#include "SyntheticFrames.h"
#include "srp/perception/MarkerFreeHandDetector.h"
#include "srp/perception/MarkerHandDetector.h"

namespace srp::perception {
namespace {

constexpr double kPalmPixelTol_px = 6.0;
constexpr double kPalmTol_m = 0.015;  // issue 5: marker-free median palm error

TEST(MarkerFreeHandDetector, FindsThePalmOfAnArmEnteringFromTheBorder) {
  const auto frames = testing::handFrames(20, 10);
  MarkerFreeHandDetector detector({});
  int detected = 0;
  for (const auto& f : frames) {
    const auto h = detector.detect(f);
    if (f.index < 10) {
      EXPECT_FALSE(h.has_value()) << "background frame " << f.index;
      continue;
    }
    ASSERT_TRUE(h.has_value()) << "frame " << f.index;
    ++detected;
    const cv::Point palm = testing::palmPixel(f.index);
    EXPECT_LT((h->palm_px - Eigen::Vector2d(palm.x, palm.y)).norm(), kPalmPixelTol_px) << "frame " << f.index;
    ASSERT_TRUE(h->hasDepth);
    const double z = testing::kHandTopDepth_m + MarkerFreeHandDetector::Options{}.palmDepth_m;
    const auto& k = f.intrinsics;
    const Eigen::Vector3d truth((palm.x - k.cx_px) * z / k.fx_px, (palm.y - k.cy_px) * z / k.fy_px, z);
    EXPECT_LT((h->p_camera_palm_m - truth).norm(), kPalmTol_m) << "frame " << f.index;
  }
  EXPECT_EQ(detected, 10);
}

TEST(MarkerFreeHandDetector, DepthHoleOnTheHandStillGivesThePixel) {
  auto frames = testing::handFrames(12, 10);
  // ToF motion blur: no depth on the hand in the last frame.
  const cv::Point palm = testing::palmPixel(11);
  cv::circle(frames[11].depth_m, palm, 40, cv::Scalar(0.0), cv::FILLED);
  MarkerFreeHandDetector detector({});
  std::optional<HandObservation> h;
  for (const auto& f : frames) h = detector.detect(f);
  ASSERT_TRUE(h.has_value());
  EXPECT_FALSE(h->hasDepth);
  EXPECT_LT((h->palm_px - Eigen::Vector2d(palm.x, palm.y)).norm(), 2 * kPalmPixelTol_px);
}

// The glove's tag, on ViSP's real AprilTag image (ground truth of tag 8,
// 0.053 m): the palm is p_tag_palm in the tag frame.
TEST(MarkerHandDetector, PalmFromTheTagPoseOnARealImage) {
  const std::string dir = "/usr/share/visp-images-data/ViSP-images/AprilTag";
  if (!std::filesystem::exists(dir + "/AprilTag.pgm")) GTEST_SKIP() << "visp-images-data not installed";
  rawlog::RgbdFrame f;
  cv::cvtColor(cv::imread(dir + "/AprilTag.pgm", cv::IMREAD_GRAYSCALE), f.colour_bgr8, cv::COLOR_GRAY2BGR);
  f.intrinsics = {615.1674804688, 615.1675415039, 312.1889953613, 243.4373779297, f.colour_bgr8.cols, f.colour_bgr8.rows};
  f.depth_m = cv::Mat(f.colour_bgr8.size(), CV_32FC1, cv::Scalar(0.0));  // a depth hole everywhere
  MarkerHandDetector::Options o;
  o.tagSize_m = 0.053;
  o.tagId = 8;
  MarkerHandDetector detector(o);
  const auto h = detector.detect(f);
  ASSERT_TRUE(h.has_value());
  EXPECT_TRUE(h->hasDepth);  // from the tag size, despite the hole
  // Ground truth of tag 8: translation; the palm lies p_tag_palm (1.5 cm) from it.
  const Eigen::Vector3d t_tag(-0.02337223475, -0.1727708343, 0.5605219405);
  constexpr double kMarkerTol_m = 0.005;  // issue 5: marker median 3D error
  EXPECT_NEAR((h->p_camera_palm_m - t_tag).norm(), o.p_tag_palm_m.norm(), kMarkerTol_m);
  o.tagId = 99;  // not in the image
  MarkerHandDetector absent(o);
  EXPECT_FALSE(absent.detect(f).has_value());
}

}  // namespace
}  // namespace srp::perception
