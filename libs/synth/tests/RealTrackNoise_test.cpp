// The real-track noise model reproduces the statistics of the thesis author's
// two real recordings, and grasp/release hold under it.
#include "srp/motion/RealTrackNoise.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <algorithm>
#include <map>

#include "NoisyDemos.h"
#include "srp/motion/Segmenter.h"

namespace srp::motion {
namespace {

using testing::EventErrors;
using testing::Recording;

// The first real recording's figures.
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

TEST(RealTrackNoise, ReproducesTheFirstRecordingsStatistics) {
  // Ranges over the demos (the README's table).
  double scatterMax = 0, fracMin = 1, fracMax = 0, outMin = 1, outMax = 0, medMin = 1, medMax = 0, p95Min = 1, p95Max = 0,
         jumpMax = 0, lingerMin = 99, lingerMax = 0, nudgeMin = 99, nudgeMax = 0, carryMin = 99, carryMax = 0, onHand = 0;
  int demos = 0, nudges = 0, placements = 0;
  std::vector<double> p95s;  // per demo: the 95th percentile sits where hand jumps meet fast motion, so it varies
  for (std::uint32_t seed = 1; seed <= 20; ++seed) {
    RealTrackNoise::Result r;
    try {
      r = testing::noisySynthDemo(seed, Recording::First);
    } catch (const std::exception&) {
      continue;  // the synth planner finds no free spot for this seed
    }
    const auto s = RealTrackNoise::measure(r);
    ++demos;
    p95s.push_back(s.handStepP95_m);
    scatterMax = std::max(scatterMax, s.partRestScatterMedian_m);
    for (double f : s.partOutlierFraction) fracMin = std::min(fracMin, f), fracMax = std::max(fracMax, f);
    outMin = std::min(outMin, s.outlierMin_m), outMax = std::max(outMax, s.outlierMax_m);
    medMin = std::min(medMin, s.handStepMedian_m), medMax = std::max(medMax, s.handStepMedian_m);
    p95Min = std::min(p95Min, s.handStepP95_m), p95Max = std::max(p95Max, s.handStepP95_m);
    jumpMax = std::max(jumpMax, s.handStepMax_m);
    onHand += s.onHandOutlierShare;
    for (double l : s.linger_s) lingerMin = std::min(lingerMin, l), lingerMax = std::max(lingerMax, l), ++placements;
    for (double l : s.nudgeAfter_s) nudgeMin = std::min(nudgeMin, l), nudgeMax = std::max(nudgeMax, l), ++nudges;
    for (double l : s.carry_s) carryMin = std::min(carryMin, l), carryMax = std::max(carryMax, l);
    EXPECT_LT(s.partRestScatterMedian_m, kRestScatterMax_m);
    for (double f : s.partOutlierFraction) {
      EXPECT_GE(f, kOutlierFractionMin - kOutlierFractionSlack);
      EXPECT_LE(f, kOutlierFractionMax + kOutlierFractionSlack);
    }
    EXPECT_GE(s.outlierMin_m, kOutlierMin_m);
    EXPECT_LE(s.outlierMax_m, kOutlierMax_m + 0.05);
    EXPECT_NEAR(s.handStepMedian_m, kHandStepMedian_m, kHandStepMedianTol_m);
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
  EXPECT_GE(demos, 15);
  std::sort(p95s.begin(), p95s.end());
  const double p95Median = p95s[p95s.size() / 2];
  EXPECT_NEAR(p95Median, kHandStepP95_m, kHandStepP95Tol_m);
  std::cout << "over " << demos << " demos (seeds 1-20): rest scatter median <= " << scatterMax * 1e3
            << " mm; outlier fraction per part " << fracMin * 100 << "-" << fracMax * 100 << " %, at " << outMin * 100
            << "-" << outMax * 100 << " cm, " << onHand / demos * 100 << " % of them on the hand; hand step median "
            << medMin * 1e3 << "-" << medMax * 1e3 << " mm, p95 " << p95Min * 1e3 << "-" << p95Max * 1e3
            << " mm (median " << p95Median * 1e3 << "), largest " << jumpMax * 100 << " cm; linger " << lingerMin << "-" << lingerMax << " s; " << nudges
            << "/" << placements << " placements nudged, " << nudgeMin << "-" << nudgeMax << " s after; carries "
            << carryMin << "-" << carryMax << " s\n";
}

// The second real recording's placement behaviours (issue text, ranges).
constexpr double kHoverMin_s = 1.5, kHoverMax_s = 3.5;
constexpr double kFrame_s = 1.0 / 30.0;                  // durations are whole frames
constexpr double kHoverHandMax_m = 0.02 + 0.003 + 0.002;  // hover point + wander + the choreography's tremor
constexpr double kHiddenShareMin = 0.15;                 // nothing / another part / the hand: each a real share
constexpr double kGhostFractionMin = 0.1, kGhostFractionMax = 0.4, kGhostFractionSlack = 0.08;

TEST(RealTrackNoise, ReproducesTheSecondRecordingsPlacementBehaviours) {
  double hoverMin = 99, hoverMax = 0, spreadMin = 1, spreadMax = 0, graspHiddenMin = 99, graspHiddenMax = 0,
         releaseHiddenMin = 99, releaseHiddenMax = 0, ghostMin = 1, ghostMax = 0, fracMax = 0, nothing = 0, other = 0,
         hand = 0;
  int demos = 0, ghosts = 0, placements = 0, noPause = 0;
  for (std::uint32_t seed = 1; seed <= 20; ++seed) {
    RealTrackNoise::Result r;
    try {
      r = testing::noisySynthDemo(seed, Recording::Both);
    } catch (const std::exception&) {
      continue;
    }
    const auto s = RealTrackNoise::measure(r);
    ++demos;
    placements += static_cast<int>(r.truth.planOrder.size());
    for (bool kept : r.pauseKept) noPause += !kept;
    ASSERT_EQ(s.hover_s.size(), r.truth.planOrder.size()) << "seed " << seed << ": a hover before every placement";
    for (double h : s.hover_s) {
      hoverMin = std::min(hoverMin, h), hoverMax = std::max(hoverMax, h);
      EXPECT_GE(h, kHoverMin_s - kFrame_s);
      EXPECT_LE(h, kHoverMax_s + kFrame_s);
    }
    for (double d : s.hoverHandSpread_m) {
      spreadMin = std::min(spreadMin, d), spreadMax = std::max(spreadMax, d);
      EXPECT_LE(d, kHoverHandMax_m);
    }
    for (std::size_t k = 0; k < s.hiddenGrasp_s.size(); ++k) {
      EXPECT_GT(s.hiddenGrasp_s[k], 0.0) << "seed " << seed << ": part hidden at its grasp";
      EXPECT_GT(s.hiddenRelease_s[k], s.hover_s[k]) << "seed " << seed << ": part hidden from the hover on";
      graspHiddenMin = std::min(graspHiddenMin, s.hiddenGrasp_s[k]), graspHiddenMax = std::max(graspHiddenMax, s.hiddenGrasp_s[k]);
      releaseHiddenMin = std::min(releaseHiddenMin, s.hiddenRelease_s[k]);
      releaseHiddenMax = std::max(releaseHiddenMax, s.hiddenRelease_s[k]);
    }
    for (double g : s.ghostFraction) {
      ++ghosts;
      ghostMin = std::min(ghostMin, g), ghostMax = std::max(ghostMax, g);
      EXPECT_GE(g, kGhostFractionMin - kGhostFractionSlack);
      EXPECT_LE(g, kGhostFractionMax + kGhostFractionSlack);
    }
    EXPECT_GE(s.hiddenNothingShare, kHiddenShareMin);
    EXPECT_GE(s.hiddenOtherShare, kHiddenShareMin);
    EXPECT_GE(s.hiddenHandShare, kHiddenShareMin);
    nothing += s.hiddenNothingShare, other += s.hiddenOtherShare, hand += s.hiddenHandShare;
    // Outside the hidden spans and ghosts, the first recording's figures hold.
    EXPECT_LT(s.partRestScatterMedian_m, kRestScatterMax_m);
    for (double f : s.partOutlierFraction) fracMax = std::max(fracMax, f);
    EXPECT_EQ(s.notDetectedPartSamples, 0);
  }
  EXPECT_GE(demos, 15);
  EXPECT_GT(ghosts, 0);
  EXPECT_GT(noPause, 0);
  EXPECT_LT(noPause, placements);
  EXPECT_LE(fracMax, kOutlierFractionMax + kOutlierFractionSlack);
  std::cout << "over " << demos << " demos (seeds 1-20): hover " << hoverMin << "-" << hoverMax << " s, hand within "
            << spreadMin * 100 << "-" << spreadMax * 100 << " cm of its release pose; " << noPause << "/" << placements
            << " placements without the pause after the release; part hidden " << graspHiddenMin << "-" << graspHiddenMax
            << " s at the grasp, " << releaseHiddenMin << "-" << releaseHiddenMax << " s at the placement, holding nothing "
            << nothing / demos * 100 << " %, another part " << other / demos * 100 << " %, the hand " << hand / demos * 100
            << " %; " << ghosts << " ghosted parts, " << ghostMin * 100 << "-" << ghostMax * 100
            << " % of their samples from the ghost's release on; outliers elsewhere <= " << fracMax * 100 << " % per part\n";
}

}  // namespace
}  // namespace srp::motion

namespace srp::motion {
namespace {

// The acceptance on seeded noisy demos: >= 95 % of the events within +-3
// frames, worst <= 10. The estimator's parameters were chosen on development
// seeds (printed by DevelopmentSeeds): 1-20 and 21-240 of both models, and
// 3001-3024 of both (once report seeds: a release caught by a nudge there made
// them development data). The report seeds 4001-4024 (both recordings'
// behaviours) were not used to choose anything; 2001-2024 (the first
// recording's behaviours alone) were the report seeds of the model before the
// placement behaviours and are checked as such.
constexpr int kEventTol_frames = 3;
constexpr double kWithinShare = 0.95;
constexpr int kWorstTol_frames = 10;
constexpr int kMinDemos = 20;  // >= 20 seeded noisy demos with all four parts

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

bool isDefault(const Segmenter::Options& c) {
  return c.robust && c.placementCues && c.events == Segmenter::EventEstimator::HandDwellBoundary;
}

std::vector<std::pair<std::string, Segmenter::Options>> estimators() {
  Segmenter::Options robust18;
  robust18.placementCues = false;
  Segmenter::Options before;
  before.robust = false;
  Segmenter::Options thesis;
  thesis.events = Segmenter::EventEstimator::ThesisPublished;
  Segmenter::Options fig610;
  fig610.events = Segmenter::EventEstimator::Thesis;
  return {{"default", {}}, {"default without the placement cues", robust18}, {"default, not robust", before},
          {"thesis published", thesis}, {"thesis fig 6.10 (old)", fig610}};
}

/// Every estimator on `demos`; the default must meet the acceptance.
void evaluateAll(const std::vector<testing::NoisyDemo>& demos, const std::string& set, bool defaultOnly) {
  const bool print = std::getenv("SRP_PRINT_EVENTS") != nullptr;
  for (const auto& [label, config] : estimators()) {
    if (defaultOnly && !isDefault(config)) continue;
    const auto e = testing::evaluateNoisy(demos, config, set + ", " + label, print);
    printSummary(set + ", " + label, e);
    EXPECT_EQ(e.count(), 8 * e.demos);  // grasp and release of four parts per demo
    if (isDefault(config)) {
      EXPECT_GE(e.within(kEventTol_frames), kWithinShare * e.count()) << set;
      EXPECT_LE(e.worst(), kWorstTol_frames) << set;
    }
  }
}

TEST(RealTrackSegmentation, DevelopmentSeeds) {
  // SRP_DEV_SEEDS=from,count widens the development set while choosing parameters (the default estimator only).
  std::uint32_t from = 1, count = 20;
  const char* env = std::getenv("SRP_DEV_SEEDS");
  if (env) std::sscanf(env, "%u,%u", &from, &count);
  const auto seeds = testing::seedRange(from, count);
  const std::string range = std::to_string(from) + "-" + std::to_string(from + count - 1);
  evaluateAll(testing::noisyDemos(seeds, Recording::Both), "dev seeds " + range + ", both recordings", env != nullptr);
  evaluateAll(testing::noisyDemos(seeds, Recording::First), "dev seeds " + range + ", first recording", true);
}

TEST(RealTrackSegmentation, ReportSeedsMeetTheAcceptance) {
  const auto demos = testing::noisyDemos(testing::seedRange(4001, 24), Recording::Both);
  EXPECT_GE(static_cast<int>(demos.size()), kMinDemos);
  evaluateAll(demos, "report seeds 4001-4024, both recordings", false);
}

TEST(RealTrackSegmentation, FormerReportSeedsNowDevelopment) {
  const auto demos = testing::noisyDemos(testing::seedRange(3001, 24), Recording::Both);
  EXPECT_GE(static_cast<int>(demos.size()), kMinDemos);
  evaluateAll(demos, "dev seeds 3001-3024, both recordings", true);
}

TEST(RealTrackSegmentation, FirstRecordingReportSeeds) {
  const auto demos = testing::noisyDemos(testing::seedRange(2001, 24), Recording::First);
  EXPECT_GE(static_cast<int>(demos.size()), kMinDemos);
  evaluateAll(demos, "report seeds 2001-2024, first recording", false);
}

}  // namespace
}  // namespace srp::motion
