// `srp experiment hand` on the quick study (one seeded demo, its first 100
// frames, rendered and perceived for real): the marker detector must meet
// issue 5's figures, the tables and the figure must be complete.
#include <gtest/gtest.h>

#include <filesystem>

#include "srp/core/Error.h"
#include "srp/experiment/Experiments.h"

using namespace srp::experiment;

namespace {

ExperimentOptions quickOptions()
{
  ExperimentOptions o;
  o.outDir = std::filesystem::path(SRP_BINARY_DIR) / "experiment_perception_test";  // shared with the objects test
  o.quick = true;
  return o;
}

}  // namespace

TEST(HandExperiment, QuickStudyMeetsIssue5MarkerFigures)
{
  const ExperimentResult r = runHandExperiment(quickOptions());
  const auto& m = r.metrics;
  std::printf("[ figures  ] %s\n", r.summary.c_str());
  std::printf("[ figures  ] hand frames %d, tag frames %d, marker %.3f (tag %.3f), marker-free %.3f, errors %s / %s\n",
              m.at("hand_frames").get<int>(), m.at("tag_frames").get<int>(), m.at("marker_rate").get<double>(),
              m.at("marker_tag_rate").get<double>(), m.at("marker_free_rate").get<double>(),
              m.at("marker_error").dump().c_str(), m.at("marker_free_error").dump().c_str());

  // A few dozen frames with the hand, most with the tag readable.
  EXPECT_GE(m.at("hand_frames").get<int>(), 24);
  EXPECT_GE(m.at("tag_frames").get<int>(), 12);
  // Issue 5: the marker detector finds the tag in >= 99 % of the tag-readable
  // frames, palm error median <= 5 mm and p95 <= 15 mm, no hand where there is none.
  constexpr double kTagRate = 0.99, kMedianTol_m = 0.005, kP95Tol_m = 0.015;
  EXPECT_GE(m.at("marker_tag_rate").get<double>(), kTagRate);
  EXPECT_LT(m.at("marker_error").at("median_m").get<double>(), kMedianTol_m);
  EXPECT_LT(m.at("marker_error").at("p95_m").get<double>(), kP95Tol_m);
  EXPECT_EQ(m.at("marker_false_detections").get<int>(), 0);
  EXPECT_GT(m.at("hand_free_frames").get<int>(), 0);
  // The marker-free detector on the same frames: the hand enters the image here, so the
  // rate is below the whole-demo 99 % of the perception README (measured 95.7 %, palm
  // median 4.6 mm); the bounds leave room for noise, not for a broken detector.
  constexpr double kMarkerFreeRate = 0.92, kMarkerFreeMedianTol_m = 0.008;
  EXPECT_GE(m.at("marker_free_rate").get<double>(), kMarkerFreeRate);
  EXPECT_GE(m.at("marker_free_error").at("frames").get<int>(), 40);
  EXPECT_LT(m.at("marker_free_error").at("median_m").get<double>(), kMarkerFreeMedianTol_m);

  ASSERT_EQ(r.tables.size(), 2u);
  EXPECT_EQ(r.tables[0].rows.size(), 2u);  // one demo + "All"
  EXPECT_EQ(r.tables[0].rows[0][2], "100.00 %");  // thesis video 1 beside demo 1
  EXPECT_NO_THROW(r.tables[0].toMarkdown());
  EXPECT_EQ(r.tables[1].rows.size(), 2u);
  ASSERT_EQ(r.figures.size(), 1u);
  EXPECT_GT(std::filesystem::file_size(r.figures[0]), 10000u);
  EXPECT_NE(r.summary.find("hand-visible frames"), std::string::npos);
}

TEST(HandExperiment, RejectsANonPositiveDemoCount)
{
  ExperimentOptions o = quickOptions();
  o.quick = false;
  o.demoCount = 0;
  EXPECT_THROW(runHandExperiment(o), srp::core::InvalidInputError);
}

TEST(HandExperiment, MissingSceneNamesTheFile)
{
  ExperimentOptions o = quickOptions();
  o.outDir = std::filesystem::path(SRP_BINARY_DIR) / "experiment_perception_test_noscene";
  o.simDir = std::filesystem::path(SRP_BINARY_DIR) / "no-such-sim-dir";
  try {
    runHandExperiment(o);
    FAIL() << "expected an error naming the scene file";
  } catch (const srp::core::Error& e) {
    EXPECT_NE(std::string(e.what()).find("default.json"), std::string::npos) << e.what();
  }
}
