// Grasp and release on real tracks: HRT1 task2 and task3 (a person puts a
// plush toy into a bin, 10 Hz; datasets/real/hrt1-pick-place, MIT, credits in
// its README). The tracks (tracks/taskN.csv) are what `srp import --fps 10` +
// `srp program -i "Pick up the toy and put it in the bin"` perceive (the
// marker-free hand, the toy found without CAD), in the `srp segment` CSV
// format; the events are scored against our own labels (event_labels.json,
// by eye from the colour frames).
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "srp/motion/Segmenter.h"
#include "srp/motion/TrajectoryTable.h"

namespace srp::motion {
namespace {

constexpr int kEventTol_frames = 2;  // the acceptance on HRT1: grasp and release within +-2 frames at 10 Hz
constexpr double kHrt1Rate_hz = 10.0;

std::string hrt1Dir() { return std::string(SRP_DATASETS_DIR) + "/real/hrt1-pick-place/"; }

TEST(Hrt1Segmentation, GraspAndReleaseWithinTwoFramesOfOurLabels) {
  std::ifstream in(hrt1Dir() + "event_labels.json");
  ASSERT_TRUE(in) << "missing " << hrt1Dir() << "event_labels.json";
  const nlohmann::json labels = nlohmann::json::parse(in);
  for (const std::string task : {"task2", "task3"}) {
    const auto& l = labels.at("tasks").at(task);
    const std::string object = l.at("object");
    const TrajectoryTable table = TrajectoryTable::readCsv(hrt1Dir() + "tracks/" + task + ".csv", kHrt1Rate_hz);
    const Segmentation s = Segmenter().segment(table.hand, table.objects, {object});
    ASSERT_EQ(s.objects.size(), 1u);
    const ObjectSegmentation& o = s.objects[0];
    ASSERT_TRUE(o.moved) << task;
    const int graspError = o.graspFrame - l.at("grasp_frame").get<int>();
    const int releaseError = o.releaseFrame - l.at("release_frame").get<int>();
    std::printf("[ figures  ] HRT1 %s, default estimator: grasp %d (label %d, %+d), release %d (label %d, %+d) frames\n",
                task.c_str(), o.graspFrame, l.at("grasp_frame").get<int>(), graspError, o.releaseFrame,
                l.at("release_frame").get<int>(), releaseError);
    EXPECT_LE(std::abs(graspError), kEventTol_frames) << task;
    EXPECT_LE(std::abs(releaseError), kEventTol_frames) << task;
  }
}

}  // namespace
}  // namespace srp::motion
