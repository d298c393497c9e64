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

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "srp/calib/RgbdImporter.h"
#include "srp/core/Json.h"
#include "srp/core/ObjectCatalogue.h"
#include "srp/perception/DemoPerception.h"

namespace srp::perception {
namespace {

constexpr double kPalmTol_px = 40.0;       // issue 17: palm within 40 px of the labelled palm
constexpr double kMinRate = 0.90;          // issue 17: in >= 90 % of the frames with the hand visible
constexpr double kMaxPalmError_px = 80.0;  // never on the torso or head (~250-300 px from the hand here)

struct CommandScore {
  int labelled = 0, within = 0, missed = 0;
  double worst_px = 0.0;
  std::vector<double> errors_px;
};

CommandScore scoreTask(const std::string& task) {
  const std::string root = std::string(SRP_DATASETS_DIR) + "/real/hrt1-pick-place";
  const std::filesystem::path dir = std::filesystem::path(SRP_BINARY_DIR) / "acceptance_real_demonstrator";
  std::filesystem::create_directories(dir);
  const std::string rawlog = (dir / (task + ".rawlog")).string();
  calib::ImportOptions io;
  io.fps = 10.0;  // HRT1 is about 10 Hz
  calib::importImageFolder(root + "/" + task, rawlog, io);

  const auto catalogue = core::ObjectCatalogue::load(std::string(SRP_DATASETS_DIR) + "/kb/catalogue.json");
  PerceptionOptions options;
  options.hand = PerceptionOptions::HandMethod::MarkerFree;
  const PerceptionResult r = perceiveRawlog(rawlog, catalogue, options);
  EXPECT_EQ(r.hand.size(), static_cast<std::size_t>(r.frames));

  std::map<int, Eigen::Vector2d> label_px;
  const auto labels = core::readJsonFile(root + "/palm_labels.json");  // kept: the loop reads into it
  for (const auto& l : labels.at("tasks").at(task).at("visible"))
    label_px[l[0].get<int>()] = {l[1].get<double>(), l[2].get<double>()};
  CommandScore s;
  const auto& k = r.intrinsics;
  for (const auto& [frame, label] : label_px) {
    ++s.labelled;
    if (frame >= static_cast<int>(r.hand.size()) || !r.hand[static_cast<std::size_t>(frame)].valid) {
      ++s.missed;
      continue;
    }
    const Eigen::Vector3d p = r.hand[static_cast<std::size_t>(frame)].p_m;
    const Eigen::Vector2d palm_px(k.fx_px * p.x() / p.z() + k.cx_px, k.fy_px * p.y() / p.z() + k.cy_px);
    const double e = (palm_px - label).norm();
    s.errors_px.push_back(e);
    s.worst_px = std::max(s.worst_px, e);
    if (e <= kPalmTol_px) ++s.within;
  }
  std::sort(s.errors_px.begin(), s.errors_px.end());
  std::printf("[ figures  ] srp perceive --hand marker-free, HRT1 %s: %d/%d frames within %.0f px (%d missed), "
              "median %.1f px, worst %.1f px; hand reported in %d of %d frames\n",
              task.c_str(), s.within, s.labelled, kPalmTol_px, s.missed,
              s.errors_px.empty() ? 0.0 : s.errors_px[s.errors_px.size() / 2], s.worst_px, r.handDetected, r.frames);
  return s;
}

TEST(RealDemonstrator, PalmReportedByPerceiveOnImportedHrt1Recordings) {
  for (const std::string task : {"task2", "task3"}) {
    const CommandScore s = scoreTask(task);
    ASSERT_GT(s.labelled, 30) << task;
    EXPECT_GE(static_cast<double>(s.within) / s.labelled, kMinRate) << task << ": " << s.within << "/" << s.labelled;
    EXPECT_LE(s.worst_px, kMaxPalmError_px) << task << ": a reported palm off the hand";
  }
}

}  // namespace
}  // namespace srp::perception
