#include "srp/perception/AprilTagDetector.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <opencv2/imgcodecs.hpp>

#include "RealData.h"
#include "srp/core/Error.h"
#include "srp/perception/RgbdFolder.h"

namespace srp::perception {
namespace {

constexpr double kCornerTol_px = 1.0;

TEST(AprilTagDetector, RejectsNonPositiveTagSize) {
  EXPECT_THROW({ AprilTagDetector d(AprilTagDetector::Options{0.0}); }, core::InvalidInputError);
}

TEST(AprilTagDetector, BlankImageHasNoTags) {
  AprilTagDetector detector({0.05});
  const cv::Mat blank(120, 160, CV_8UC1, cv::Scalar(200));
  EXPECT_TRUE(detector.detect(blank, {150, 150, 80, 60, 160, 120}).empty());
}

// The corners the detector finds on the real recording agree with the stored
// ViSP detections (stored as (row, column)).
TEST(AprilTagDetector, RealFrameCornersMatchStoredDetections) {
  const auto frames = readRgbdFolder(testing::rbtFolder(), 1);
  const auto j = core::readJsonFile(testing::rbtFolder() + "/apriltag_board_poses.json");
  AprilTagDetector detector({0.0955});
  const auto tags = detector.detect(frames[0].colour_bgr8, frames[0].intrinsics);
  const auto& stored = j.at("detections").at(0);
  int matched = 0;
  for (const auto& t : tags) {
    const std::string key = std::to_string(t.id);
    if (!stored.contains(key)) continue;
    ++matched;
    for (int c = 0; c < 4; ++c) {
      const auto& rc = stored[key]["tag_corners"][c];
      EXPECT_NEAR(t.corners_px[c].x(), rc[1].get<double>(), kCornerTol_px) << "tag " << t.id << " corner " << c;
      EXPECT_NEAR(t.corners_px[c].y(), rc[0].get<double>(), kCornerTol_px) << "tag " << t.id << " corner " << c;
    }
  }
  EXPECT_EQ(matched, static_cast<int>(stored.size()));
}

// Debian's visp-images-data: AprilTag.pgm with ground-truth poses of tags 8-19
// (0.053 m). Skipped when the package is not installed.
TEST(AprilTagDetector, VispImageGroundTruthPoses) {
  const std::string dir = "/usr/share/visp-images-data/ViSP-images/AprilTag";
  if (!std::filesystem::exists(dir + "/AprilTag.pgm")) FAIL() << dir << "/AprilTag.pgm missing: install Debian's visp-images-data (scripts/install-deps.sh does)";
  const cv::Mat img = cv::imread(dir + "/AprilTag.pgm", cv::IMREAD_GRAYSCALE);
  ASSERT_FALSE(img.empty());
  const core::CameraIntrinsics k{615.1674804688, 615.1675415039, 312.1889953613, 243.4373779297, img.cols, img.rows};
  AprilTagDetector detector({0.053});
  const auto tags = detector.detect(img, k);
  std::map<int, Eigen::Vector3d> truth;
  std::ifstream in(dir + "/ground_truth_pose.txt");
  std::string name;
  while (in >> name) {
    Eigen::Vector3d t, tu;
    in >> t.x() >> t.y() >> t.z() >> tu.x() >> tu.y() >> tu.z();
    truth[std::stoi(name.substr(name.rfind('_') + 1))] = t;
  }
  ASSERT_EQ(truth.size(), 12u);
  EXPECT_EQ(tags.size(), 12u);
  constexpr double kTagPositionTol_m = 5e-3;
  for (const auto& t : tags) {
    ASSERT_TRUE(truth.count(t.id)) << t.id;
    EXPECT_LT((t.X_camera_tag.translation() - truth[t.id]).norm(), kTagPositionTol_m) << "tag " << t.id;
  }
}

}  // namespace
}  // namespace srp::perception
