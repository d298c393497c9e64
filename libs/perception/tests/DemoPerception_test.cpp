#include "srp/perception/DemoPerception.h"
#include "srp/kb/KnowledgeBase.h"
#include "srp/perception/RawlogPerception.h"
#include "srp/perception/DemoRawlogReader.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "SyntheticFrames.h"
#include "srp/core/Error.h"
#include "srp/motion/TrajectoryTable.h"
#include "srp/rawlog/RawlogReader.h"
#include "srp/rawlog/RawlogWriter.h"

namespace srp::perception {
namespace {

namespace fs = std::filesystem;

std::string tempPath(const std::string& name) {
  return (fs::path(SRP_BINARY_DIR) / ("perception_test_" + name)).string();
}

PerceptionOptions markerFreeOptions() {
  PerceptionOptions o;
  o.hand = PerceptionOptions::HandMethod::MarkerFree;
  o.plan = {{"cuboid", false}, {"gray box", true}};
  return o;
}

const core::ObjectCatalogue& catalogue() {
  static const auto c = kb::loadCatalogue(core::ObjectCatalogue::defaultPath());
  return c;
}

TEST(DemoPerception, ZeroFramesIsAClearError) {
  EXPECT_THROW(perceiveFrames({}, catalogue(), markerFreeOptions()), core::InvalidInputError);
}

TEST(DemoPerception, FrameWithoutDepthIsAClearError) {
  auto frames = testing::handFrames(3, 10);
  frames[1].depth_m.release();
  try {
    perceiveFrames(frames, catalogue(), markerFreeOptions());
    FAIL() << "no error";
  } catch (const core::InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("frame 1 has no depth"), std::string::npos) << e.what();
  }
}

TEST(DemoPerception, MismatchedSizesAreAClearError) {
  auto frames = testing::handFrames(3, 10);
  frames[2].intrinsics.width_px = 160;
  cv::resize(frames[2].colour_bgr8, frames[2].colour_bgr8, {160, 240});
  cv::resize(frames[2].depth_m, frames[2].depth_m, {160, 240});
  EXPECT_THROW(perceiveFrames(frames, catalogue(), markerFreeOptions()), core::InvalidInputError);
}

TEST(DemoPerception, HandNeverSeenIsAnErrorSayingSo) {
  const auto frames = testing::handFrames(15, 100);
  try {
    perceiveFrames(frames, catalogue(), markerFreeOptions());
    FAIL() << "no error";
  } catch (const core::InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("hand was never detected"), std::string::npos) << e.what();
  }
}

TEST(DemoPerception, RejectsBadReinitialisationGateOptions) {
  const auto frames = testing::handFrames(3, 10);
  for (auto bad : {+[](PerceptionOptions& o) { o.mbtMinDetectionVisibleFraction = 1.5; },
                   +[](PerceptionOptions& o) { o.mbtMinDetectionSupport = -0.1; },
                   +[](PerceptionOptions& o) { o.mbtOccluderMargin_m = -0.01; }}) {
    PerceptionOptions o = markerFreeOptions();
    bad(o);
    try {
      perceiveFrames(frames, catalogue(), o);
      FAIL() << "no error";
    } catch (const core::InvalidInputError& e) {
      EXPECT_NE(std::string(e.what()).find("mbt"), std::string::npos) << e.what();
    }
  }
}

TEST(DemoPerception, UnreadableRawlogIsAFileError) {
  EXPECT_THROW(perceiveRawlog(tempPath("missing.rawlog"), catalogue(), markerFreeOptions()), core::FileError);
  const std::string garbage = tempPath("garbage.rawlog");
  std::ofstream(garbage) << "this is not a rawlog";
  EXPECT_THROW(perceiveRawlog(garbage, catalogue(), markerFreeOptions()), core::FileError);
}

TEST(DemoPerception, RawlogToHandTrajectoryAndCsv) {
  const std::string rawlogPath = tempPath("demo.rawlog");
  {
    rawlog::RawlogWriter writer(rawlogPath);
    for (const auto& f : testing::handFrames(20, 10)) writer.write(f);
  }
  const PerceptionResult r = perceiveRawlog(rawlogPath, catalogue(), markerFreeOptions());
  EXPECT_EQ(r.frames, 20);
  EXPECT_EQ(r.handDetected, 10);
  ASSERT_EQ(r.hand.size(), 20u);
  EXPECT_FALSE(r.hand[5].valid);
  ASSERT_TRUE(r.hand[15].valid);
  EXPECT_NEAR(r.hand[15].p_m.z(), testing::kHandTopDepth_m + 0.015, 0.005);
  ASSERT_EQ(r.objects.size(), 2u);  // the plan's objects, none in these frames
  EXPECT_TRUE(r.objects[0].samples.empty());

  const std::string csv = tempPath("demo.csv");
  writeSegmentCsv(r, csv);
  std::ifstream in(csv);
  std::string header, line;
  std::getline(in, header);
  EXPECT_EQ(header, "frame,hand_x,hand_y,hand_z,cuboid_x,cuboid_y,cuboid_z,cuboid_rz,gray_box_x,gray_box_y,gray_box_z,gray_box_rz");
  int rows = 0;
  while (std::getline(in, line)) {
    if (rows == 0) EXPECT_EQ(line.substr(0, 28), "0,0.000000,0.000000,0.000000");
    ++rows;
  }
  EXPECT_EQ(rows, 20);
}

// The marker-free path previews the whole rawlog, then perceives the frames
// the preview decoded: the result is that of the frames themselves, sample
// for sample.
TEST(DemoPerception, RawlogPerceivedGivesTheResultOfItsFrames) {
  const std::string rawlogPath = tempPath("two_passes.rawlog");
  {
    rawlog::RawlogWriter writer(rawlogPath);
    for (const auto& f : testing::handFrames(20, 10)) writer.write(f);
  }
  std::vector<int> hooked;  // the per-frame hook sees every perceived frame once, in order
  const PerceptionResult fromFile =
      perceiveRawlog(rawlogPath, catalogue(), markerFreeOptions(), {}, [&](const rawlog::RgbdFrame& f, int i) {
        EXPECT_FALSE(f.depth_m.empty()) << "frame " << i;
        hooked.push_back(i);
      });
  ASSERT_EQ(hooked.size(), 20u);
  for (std::size_t i = 0; i < hooked.size(); ++i) EXPECT_EQ(hooked[i], static_cast<int>(i));
  const PerceptionResult fromFrames =
      perceiveFrames(rawlog::RawlogReader::readAll(rawlogPath), catalogue(), markerFreeOptions());
  ASSERT_EQ(fromFile.hand.size(), fromFrames.hand.size());
  ASSERT_EQ(fromFile.handDetected, 10);
  EXPECT_EQ(fromFile.handDetected, fromFrames.handDetected);
  for (std::size_t i = 0; i < fromFile.hand.size(); ++i) {
    EXPECT_EQ(fromFile.hand[i].valid, fromFrames.hand[i].valid) << "frame " << i;
    EXPECT_EQ(fromFile.hand[i].p_m, fromFrames.hand[i].p_m) << "frame " << i;  // bit for bit
  }
}

// The one reader of perceiveRawlog and `srp program`: the preview pass shows
// every frame of the file, in order, counted; the perception pass then gets
// the same frames, each decoded once; a missing file is a FileError.
TEST(DemoPerception, DemoRawlogReaderPreviewsEveryFrameAndDecodesItOnce) {
  const std::string rawlogPath = tempPath("preview.rawlog");
  {
    rawlog::RawlogWriter writer(rawlogPath);
    for (const auto& f : testing::handFrames(12, 6)) writer.write(f);
  }
  DemoPerceiver perceiver(catalogue(), markerFreeOptions());
  DemoRawlogReader reader(rawlogPath);
  std::vector<int> progress;
  EXPECT_EQ(reader.preview(perceiver, [&](int n) { progress.push_back(n); }), 12);
  ASSERT_EQ(progress.size(), 12u);
  for (std::size_t i = 0; i < progress.size(); ++i) EXPECT_EQ(progress[i], static_cast<int>(i) + 1);
  EXPECT_EQ(perceiver.framesAdded(), 0);  // previewed, not perceived
  EXPECT_TRUE(reader.previewedWholeFile());
  int frames = 0;
  while (auto f = reader.next()) EXPECT_EQ(f->index, frames++);
  EXPECT_EQ(frames, 12);
  EXPECT_FALSE(reader.readsTwice());
  EXPECT_EQ(reader.framesDecoded(), 12);
  EXPECT_FALSE(reader.damage());
  EXPECT_THROW(DemoRawlogReader(tempPath("missing.rawlog")), core::FileError);
}

// Over its memory budget (the file's size or the decoded frames') the reader
// keeps no previewed frame and reads the file again: the perception pass gets the very same frames, bit for bit,
// and perceiveRawlog's result does not depend on the budget.
TEST(DemoPerception, DemoRawlogReaderOverItsBudgetReadsTwiceTheSameFrames) {
  const std::string rawlogPath = tempPath("budget.rawlog");
  {
    rawlog::RawlogWriter writer(rawlogPath);
    for (const auto& f : testing::handFrames(12, 6)) writer.write(f);
  }
  const auto passes = [&](double budget_MB, bool& readTwice, int& decoded) {
    DemoPerceiver perceiver(catalogue(), markerFreeOptions());
    DemoRawlogReader::Options o;
    o.keptFrames_MB = budget_MB;
    DemoRawlogReader reader(rawlogPath, o);
    EXPECT_EQ(reader.preview(perceiver), 12);
    std::vector<rawlog::RgbdFrame> frames;
    while (auto f = reader.next()) {
      perceiver.add(*f);
      frames.push_back(std::move(*f));
    }
    readTwice = reader.readsTwice();
    decoded = reader.framesDecoded();
    return std::make_pair(frames, perceiver.finish());
  };
  bool twice = false;
  int decoded = 0;
  const auto [kept, keptResult] = passes(128.0, twice, decoded);
  EXPECT_FALSE(twice);
  EXPECT_EQ(decoded, 12);
  const double frame_MB =
      1e-6 * static_cast<double>(kept.front().colour_bgr8.total() * 3 + kept.front().depth_m.total() * 4);
  const double file_MB = 1e-6 * static_cast<double>(fs::file_size(rawlogPath));
  ASSERT_LT(file_MB, 5.5 * frame_MB) << "the file must fit the budget for the 6th frame to go over it";
  // Never kept; a file larger than the budget; over the budget at the 6th frame.
  for (const double budget_MB : {0.0, 0.5 * file_MB, 5.5 * frame_MB}) {
    const auto [reread, rereadResult] = passes(budget_MB, twice, decoded);
    EXPECT_TRUE(twice) << budget_MB << " MB";
    EXPECT_EQ(decoded, 24) << budget_MB << " MB";
    ASSERT_EQ(reread.size(), kept.size());
    for (std::size_t i = 0; i < kept.size(); ++i) {
      EXPECT_EQ(reread[i].index, kept[i].index);
      EXPECT_EQ(cv::norm(reread[i].depth_m, kept[i].depth_m, cv::NORM_INF), 0.0) << "frame " << i;
      EXPECT_EQ(cv::norm(reread[i].colour_bgr8, kept[i].colour_bgr8, cv::NORM_INF), 0.0) << "frame " << i;
    }
    ASSERT_EQ(rereadResult.hand.size(), keptResult.hand.size());
    EXPECT_EQ(rereadResult.handDetected, keptResult.handDetected);
    for (std::size_t i = 0; i < keptResult.hand.size(); ++i)
      EXPECT_EQ(rereadResult.hand[i].p_m, keptResult.hand[i].p_m) << "frame " << i;  // bit for bit
  }
}

// `srp perceive --csv` -> `srp segment --trajectories`: the same samples are
// detected on both sides (a carried, i.e. not-detected, object pose is "not
// detected" in the CSV, not a detection at the carried pose).
TEST(DemoPerception, CsvCarriedSamplesAreNotDetectedForSrpSegment) {
  constexpr double kPositionTol_m = 1e-6, kYawTol_rad = 1e-5;
  PerceptionResult r;
  ObjectTrajectory cuboid{"cuboid", 3, false, {}}, box{"gray box", 0, true, {}};
  for (int i = 0; i < 5; ++i) {
    r.hand.append({i, i / 30.0, Eigen::Vector3d(0.01 * i, -0.02, 0.8), i != 3});
    const core::Pose3 X = core::makePoseYPR({0.1, 0.05, 0.84}, 0.4, 0, 0);
    cuboid.samples.push_back({i, i / 30.0, X, i == 0 || i == 4, 0.9});  // 1-3: carried (pose of frame 0)
    box.samples.push_back({i, i / 30.0, core::makePoseYPR({-0.1, 0.0, 0.86}, 0.1, 0, 0), i != 2, 0.8});
  }
  r.objects = {cuboid, box, ObjectTrajectory{"star", 5, false, {}}};  // the star never seen
  const std::string csv = tempPath("carried.csv");
  writeSegmentCsv(r, csv);
  const motion::TrajectoryTable table = motion::TrajectoryTable::readCsv(csv);
  ASSERT_EQ(table.hand.size(), 5u);
  ASSERT_EQ(table.objects.size(), 3u);
  for (std::size_t i = 0; i < 5; ++i) {
    EXPECT_EQ(table.hand[i].valid, r.hand[i].valid) << "frame " << i;
    for (std::size_t k = 0; k < 2; ++k) {
      const ObjectPoseSample& s = r.objects[k].samples[i];
      const core::PositionSample& read = table.objects[k].positions[i];
      EXPECT_EQ(read.valid, s.detected) << r.objects[k].className << " frame " << i;
      if (!s.detected) continue;
      EXPECT_LT((read.p_m - s.X_camera_object.translation()).norm(), kPositionTol_m);
      EXPECT_NEAR(table.objects[k].yaw_rad[i], cameraYaw(s.X_camera_object), kYawTol_rad);
    }
    EXPECT_FALSE(table.objects[2].positions[i].valid);
  }
}

TEST(DemoPerception, CameraYawIsTheRotationAboutTheOpticalAxis) {
  const core::Pose3 X = core::makePoseYPR({0, 0, 1}, 0.3, 0.0, 0.0);
  EXPECT_NEAR(cameraYaw(X), 0.3, 1e-12);
}

}  // namespace
}  // namespace srp::perception
