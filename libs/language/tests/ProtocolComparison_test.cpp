#include "srp/language/ProtocolComparison.h"

#include <gtest/gtest.h>

#include "srp/core/Error.h"

using namespace srp::language;

namespace {
const std::vector<std::string> kTypes{"Action", "Trajector", "SpatialIndicator", "GoalIndicator",
                                      "Color",  "Spatial",   "Transition",       "macro"};

// 5 folds x 1 seed; every type's F1 is `base` plus the fold's offset.
ProtocolComparison::Configuration configuration(double base, double suiteEntity, double suiteRelation) {
  ProtocolComparison::Configuration c;
  c.folds = 5;
  c.seeds = 1;
  for (const auto& t : kTypes) c.foldF1[t] = {base, base + 0.01, base - 0.01, base + 0.02, base - 0.02};
  c.suiteF1["source_goal"] = {suiteEntity, suiteRelation};
  return c;
}
}  // namespace

TEST(ProtocolComparison, ACapabilityRuleIsKeptWhenItRaisesItsSuiteAndHarmsNoType) {
  const auto baseline = configuration(0.90, 0.85, 0.70);
  const ProtocolComparison same(configuration(0.90, 0.99, 0.95), baseline);
  EXPECT_TRUE(same.raisesASuite());
  EXPECT_TRUE(same.harmsNoType());
  EXPECT_TRUE(same.holdsTheMacroMean());
  EXPECT_FALSE(same.keptByCrossValidation());  // no CV gain
  EXPECT_TRUE(same.kept());
  EXPECT_NE(same.format().find("kept (capability"), std::string::npos) << same.format();

  // The same suite gain with a type lowered on every fold: (b) and (c) fail.
  auto lower = configuration(0.90, 0.99, 0.95);
  for (auto& f1 : lower.foldF1["SpatialIndicator"]) f1 -= 0.01;
  for (auto& f1 : lower.foldF1["macro"]) f1 -= 0.01 / 7;
  const ProtocolComparison harmful(lower, baseline);
  EXPECT_FALSE(harmful.harmsNoType());
  EXPECT_FALSE(harmful.holdsTheMacroMean());
  EXPECT_FALSE(harmful.kept());

  // A suite that falls: (a) fails even if another rises.
  auto mixed = configuration(0.90, 0.99, 0.60);
  EXPECT_FALSE(ProtocolComparison(mixed, baseline).lowersNoSuite());
  EXPECT_FALSE(ProtocolComparison(mixed, baseline).kept());
}

TEST(ProtocolComparison, AConsistentCvGainIsKeptWithoutASuite) {
  const auto baseline = configuration(0.90, 0.85, 0.70);
  auto better = configuration(0.90, 0.85, 0.70);
  for (auto& [type, folds] : better.foldF1)
    for (auto& f1 : folds) f1 += 0.005;
  const ProtocolComparison c(better, baseline);
  EXPECT_TRUE(c.keptByCrossValidation());
  EXPECT_FALSE(c.raisesASuite());
  EXPECT_TRUE(c.kept());
}

TEST(ProtocolComparison, UnpairedRunsAreRejected) {
  auto other = configuration(0.90, 0.85, 0.70);
  other.seeds = 3;
  EXPECT_THROW(ProtocolComparison(other, configuration(0.90, 0.85, 0.70)), srp::core::InvalidInputError);
}

// The --cv-json form round-trips: a configuration read back equals the one written.
TEST(ProtocolComparison, ReadsTheCvJsonItWrites) {
  constexpr double kTol = 1e-12;
  RepeatedCrossValidation cv;
  cv.numFolds = 2;
  cv.numSeeds = 1;
  cv.variantNames = {"baseline"};
  SpertScores fold;
  for (const auto& t : kTypes)
    if (t != "macro") fold.types[t] = {8, 2, 2};  // F1 0.8
  cv.folds = {{fold, fold}};
  CapabilitySuites::Result suite = CapabilitySuites::summarise("no_landmark", 3, fold);
  const auto j = toJson(cv, {{suite}});
  const auto read = ProtocolComparison::Configuration::fromJson(j, "baseline");
  const auto direct = ProtocolComparison::Configuration::fromCrossValidation(cv, 0, {suite});
  EXPECT_EQ(read.folds, 2);
  ASSERT_EQ(read.foldF1.at("Spatial").size(), 2u);
  EXPECT_NEAR(read.foldF1.at("macro")[1], 0.8, kTol);
  EXPECT_NEAR(read.suiteF1.at("no_landmark").first, direct.suiteF1.at("no_landmark").first, kTol);
  EXPECT_THROW(ProtocolComparison::Configuration::fromJson(j, "missing"), srp::core::InvalidInputError);
}
