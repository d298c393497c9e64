#include "srp/calib/TaskModelOverlay.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <opencv2/imgcodecs.hpp>

#include "srp/calib/RawlogReplay.h"
#include "srp/core/Error.h"
#include "srp/rawlog/RawlogWriter.h"
#include "srp/taskdb/TaskDatabase.h"
#include "srp/taskdb/TaskModelStore.h"

using namespace srp::calib;
namespace fs = std::filesystem;

namespace {

const srp::core::CameraIntrinsics kK{300.0, 300.0, 159.5, 119.5, 320, 240};

/// Hand moving right along x at 0.5 m depth; one object (class 2) moving down in y.
srp::taskdb::TaskModel makeModel() {
  srp::taskdb::TaskModel m;
  m.info.name = "overlay-test";
  m.info.frame = "camera";
  m.groundedProducts.push_back({2, "blue box", std::nullopt, std::nullopt, std::string("blue")});
  for (int t = 0; t < 10; ++t) {
    srp::taskdb::HandPositionRow h;
    h.timeId = t;
    h.p_m = {-0.2 + 0.04 * t, -0.1, 0.5};
    m.handPositions.push_back(h);
    srp::taskdb::ProductPoseRow p;
    p.classId = 2;
    p.timeId = t;
    p.p_m = {0.1, -0.1 + 0.02 * t, 0.5};
    m.productPoses.push_back(p);
  }
  srp::taskdb::SkillRow s;
  s.classId = 2;
  s.skill = srp::core::SkillType::Move;
  s.startTimeId = 3;
  s.endTimeId = 7;
  m.skills.push_back(s);
  return m;
}

cv::Point pixelOf(const Eigen::Vector3d& p) {
  const auto uv = kK.project(p);
  return {cvRound(uv->x()), cvRound(uv->y())};
}

srp::rawlog::RgbdFrame blackFrame(int index) {
  srp::rawlog::RgbdFrame f;
  f.index = index;
  f.t_s = index / 30.0;
  f.intrinsics = kK;
  f.colour_bgr8 = cv::Mat(kK.height_px, kK.width_px, CV_8UC3, cv::Scalar::all(0));
  f.depth_m = cv::Mat(kK.height_px, kK.width_px, CV_32FC1, cv::Scalar(0.5));
  return f;
}

}  // namespace

TEST(TaskModelOverlay, DrawsTrackUpToTheCurrentFrameAndTheCurrentPositions) {
  const auto model = makeModel();
  const TaskModelOverlay overlay(model);
  const auto frame = blackFrame(5);
  cv::Mat img = frame.colour_bgr8.clone();
  overlay.draw(img, frame);
  const cv::Vec3b white(255, 255, 255);
  EXPECT_EQ(img.at<cv::Vec3b>(pixelOf(model.handPositions[5].p_m)), white) << "current hand";
  EXPECT_EQ(img.at<cv::Vec3b>(pixelOf(model.handPositions[2].p_m)), white) << "past hand track";
  EXPECT_EQ(img.at<cv::Vec3b>(pixelOf(model.handPositions[9].p_m)), cv::Vec3b(0, 0, 0)) << "future not drawn";
  EXPECT_NE(img.at<cv::Vec3b>(pixelOf(model.productPoses[5].p_m)), cv::Vec3b(0, 0, 0)) << "current object";
  EXPECT_EQ(img.at<cv::Vec3b>(pixelOf(model.productPoses[9].p_m)), cv::Vec3b(0, 0, 0)) << "future object";
}

TEST(TaskModelOverlay, BaseFrameNeedsTheCameraPose) {
  auto model = makeModel();
  model.info.frame = "base";
  EXPECT_THROW(TaskModelOverlay{model}, srp::core::InvalidInputError);
  model.info.X_base_camera = srp::core::makePose({0.0, 0.0, 1.0}, Eigen::Quaterniond(0, 1, 0, 0));
  EXPECT_NO_THROW(TaskModelOverlay{model});
  model.info.frame = "table";
  EXPECT_THROW(TaskModelOverlay{model}, srp::core::InvalidInputError);
}

TEST(TaskModelOverlay, ReplayWritesOverlaidFrames) {
  const std::string path = (fs::temp_directory_path() / "srp_calib_overlay.rawlog").string();
  {
    srp::rawlog::RawlogWriter writer(path, 1e-3);
    for (int i = 0; i < 10; ++i) writer.write(blackFrame(i));
  }
  const fs::path dir = fs::temp_directory_path() / "srp_calib_overlay_export";
  fs::remove_all(dir);
  // Through a real task database, as `srp replay --overlay task.db` reads it.
  const std::string dbPath = (fs::temp_directory_path() / "srp_calib_overlay.db").string();
  for (const char* suffix : {"", "-wal", "-shm"}) fs::remove(dbPath + suffix);
  srp::taskdb::TaskModel model;
  {
    auto db = srp::taskdb::TaskDatabase::open(dbPath);
    srp::taskdb::TaskModelStore store(db);
    model = store.read(store.write(makeModel()));
  }
  const TaskModelOverlay overlay(model);
  ReplayOptions options;
  options.exportDir = dir.string();
  options.exportOverlay = true;
  options.overlay = [&](cv::Mat& img, const srp::rawlog::RgbdFrame& f) { overlay.draw(img, f); };
  EXPECT_EQ(replayRawlog(path, options).frames, 10);
  const cv::Mat drawn = cv::imread((dir / "overlay_0007.png").string());
  ASSERT_FALSE(drawn.empty());
  EXPECT_EQ(drawn.at<cv::Vec3b>(pixelOf(model.handPositions[7].p_m)), cv::Vec3b(255, 255, 255));
  const cv::Mat plain = cv::imread((dir / "color_0007.png").string());
  EXPECT_EQ(cv::countNonZero(plain.reshape(1)), 0) << "the plain export stays untouched";
}
