// `srp experiment objects` on the quick study (one seeded demo, its first 100
// frames, rendered and perceived for real): per-class scores in the thesis'
// layout, with and without the language-guided refinement.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "srp/experiment/Experiments.h"

using namespace srp::experiment;

TEST(ObjectsExperiment, QuickStudyScoresEveryClassWithAndWithoutRefinement)
{
  ExperimentOptions o;
  o.outDir = std::filesystem::path(SRP_BINARY_DIR) / "experiment_perception_test";  // shared with the hand test
  o.quick = true;
  const ExperimentResult r = runObjectsExperiment(o);
  std::printf("[ figures  ] %s\n", r.summary.c_str());
  for (const auto& t : r.tables) std::printf("%s\n", t.toText().c_str());

  const auto& without = r.metrics.at("without_refinement");
  const auto& with = r.metrics.at("with_refinement");
  for (const char* name : {"gray box", "blue box", "cuboid", "star", "parallelogram", "octagon"}) {
    SCOPED_TRACE(name);
    ASSERT_TRUE(without.contains(name));
    // One instance per frame the class is evaluated in (the scene has one of each).
    EXPECT_GE(without.at(name).at("instances").get<int>(), 60);
    for (const auto* mode : {&without, &with}) {
      const double map50 = mode->at(name).at("map50").get<double>();
      const double map50_95 = mode->at(name).at("map50_95").get<double>();
      EXPECT_GE(map50, 0.0);
      EXPECT_LE(map50, 1.0);
      EXPECT_LE(map50_95, map50 + 1e-12);  // stricter thresholds never score higher
    }
  }
  // The detector's boxes are right where it reports one (perception's
  // precision on synthetic demos is ~100 %): precision at IoU 0.5 high.
  constexpr double kMinPrecision = 0.9;
  EXPECT_GE(without.at("all").at("precision").get<double>(), kMinPrecision);
  // The quick study's class means (measured: mAP50 / mAP50-95 90.3 / 82.1 % per frame,
  // 100 / 91.9 % with refinement; the whole-demo figures of the README come from
  // `srp experiment objects`). Bounds a few points below, so a regression fails.
  constexpr double kMap50 = 0.85, kMap50_95 = 0.75, kRefinedMap50 = 0.97, kRefinedMap50_95 = 0.85;
  EXPECT_GE(without.at("all").at("map50").get<double>(), kMap50);
  EXPECT_GE(without.at("all").at("map50_95").get<double>(), kMap50_95);
  EXPECT_GE(with.at("all").at("map50").get<double>(), kRefinedMap50);
  EXPECT_GE(with.at("all").at("map50_95").get<double>(), kRefinedMap50_95);
  // Static objects fixed at their best detection are boxed in every frame:
  // the refinement cannot lose recall on the containers.
  for (const char* box : {"gray box", "blue box"})
    EXPECT_GE(with.at(box).at("recall").get<double>(), without.at(box).at("recall").get<double>()) << box;
  EXPECT_GE(with.at("gray box").at("recall").get<double>(), 0.99);

  ASSERT_EQ(r.tables.size(), 3u);
  EXPECT_EQ(r.tables[0].rows.size(), 7u);  // all + six classes, thesis order
  EXPECT_EQ(r.tables[0].rows[0][0], "all");
  EXPECT_EQ(r.tables[0].rows[0][3], "98.5 / 100.0");  // thesis tables 8.3 / 8.4 precision
  EXPECT_EQ(r.tables[2].rows.size(), 4u);
  ASSERT_EQ(r.figures.size(), 1u);
  EXPECT_GT(std::filesystem::file_size(r.figures[0]), 10000u);
}
