// Issue 17 item 4 on the user's path: a real demonstrator (HRT1 task2 and
// task3, datasets/real/hrt1-pick-place, MIT, credits in its README) imported
// as `srp import <folder> x.rawlog --fps 10` does (calib::importImageFolder)
// and perceived as `srp perceive --demo x.rawlog --hand marker-free` does
// (perceiveRawlog with the default catalogue, every class moving). Each
// frame's palm (camera frame, metres, depth carried along the ray where the
// palm has none) is projected with the recording's intrinsics and compared
// with our palm labels (palm_labels.json). The detector's own tests
// (MarkerFreeHandDetector_test, MarkerFreeHandRobustness_test) score its
// pixel output; this one scores what the command reports. Slow label: two
// recordings perceived with every default class (~5 s each).
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "Hrt1Palms.h"
#include "srp/calib/RgbdImporter.h"
#include "srp/core/ObjectCatalogue.h"
#include "srp/kb/KnowledgeBase.h"
#include "srp/perception/RawlogPerception.h"

namespace srp::perception {
namespace {

using testing::kPalmTol_px;                // issue 17: palm within 40 px of the labelled palm
constexpr double kMinRate = 0.90;          // issue 17: in >= 90 % of the frames with the hand visible
constexpr double kMaxPalmError_px = 80.0;  // never on the torso or head (~250-300 px from the hand here)

testing::PalmScore scoreTask(const std::string& task) {
  const std::filesystem::path dir = std::filesystem::path(SRP_BINARY_DIR) / "acceptance_real_demonstrator";
  std::filesystem::create_directories(dir);
  const std::string rawlog = (dir / (task + ".rawlog")).string();
  calib::ImportOptions io;
  io.fps = 10.0;  // HRT1 is about 10 Hz
  calib::importImageFolder(testing::hrt1Root() + "/" + task, rawlog, io);

  const auto catalogue = kb::loadCatalogue(std::string(SRP_DATASETS_DIR) + "/kb/catalogue.json");
  PerceptionOptions options;
  options.hand = PerceptionOptions::HandMethod::MarkerFree;
  const PerceptionResult r = perceiveRawlog(rawlog, catalogue, options);
  EXPECT_EQ(r.hand.size(), static_cast<std::size_t>(r.frames));

  std::vector<testing::RealFrameError> errors;
  for (const auto& [frame, label] : testing::hrt1PalmLabels(task)) {
    testing::RealFrameError e;
    e.frame = frame;
    e.label_px = label;
    const bool seen = frame < static_cast<int>(r.hand.size()) && r.hand[static_cast<std::size_t>(frame)].valid;
    const auto palm_px = seen ? r.intrinsics.project(r.hand[static_cast<std::size_t>(frame)].p_m) : std::nullopt;
    e.detected = palm_px.has_value();
    if (palm_px) {
      e.palm_px = *palm_px;
      e.error_px = (*palm_px - label).norm();
    }
    errors.push_back(e);
  }
  const testing::PalmScore s = testing::score(errors);
  std::printf("[ figures  ] srp perceive --hand marker-free, HRT1 %s: %d/%d frames within %.0f px (%d missed), "
              "median %.1f px, worst %.1f px; hand reported in %d of %d frames\n",
              task.c_str(), s.within, s.labelled, kPalmTol_px, s.missed, s.median_px, s.worst_px, r.handDetected,
              r.frames);
  return s;
}

TEST(RealDemonstrator, PalmReportedByPerceiveOnImportedHrt1Recordings) {
  for (const std::string task : {"task2", "task3"}) {
    const testing::PalmScore s = scoreTask(task);
    ASSERT_GT(s.labelled, 30) << task;
    EXPECT_GE(s.rate(), kMinRate) << task << ": " << s.within << "/" << s.labelled;
    EXPECT_LE(s.worst_px, kMaxPalmError_px) << task << ": a reported palm off the hand";
  }
}

}  // namespace
}  // namespace srp::perception
