#include "srp/language/LanguageModel.h"

#include <gtest/gtest.h>

#include <map>

#include "srp/core/Error.h"
#include "srp/language/SpertEvaluation.h"

using namespace srp::language;

namespace {
const std::string kTrain = std::string(SRP_DATASETS_DIR) + "/language/train.json";
const std::string kVal = std::string(SRP_DATASETS_DIR) + "/language/val.json";

// SpERT validation F1 (thesis table 5.7, SPEC.md section 3), fractions.
const std::map<std::string, double> kSpertValF1{{"Action", 0.9913},     {"Trajector", 0.8429},
                                                {"SpatialIndicator", 0.8280}, {"GoalIndicator", 0.8571},
                                                {"Color", 0.9601},      {"Spatial", 0.7516},
                                                {"Transition", 0.8346}};
}  // namespace

// Training is deterministic: a fresh run on train.json scores exactly as the
// shipped model on val.json (tolerance: one entity in ~70 would move F1 by >1e-3).
TEST(LanguageModel, FreshTrainingReproducesTheShippedScores) {
  constexpr double kF1Tol = 1e-3;
  const auto val = readSpertCorpus(kVal);
  const auto shipped = evaluateModel(LanguageModel::load(defaultModelPath()), val);
  const auto fresh = evaluateModel(LanguageModel::train(readSpertCorpus(kTrain)), val);
  for (const auto& [type, score] : shipped.types) {
    SCOPED_TRACE(type);
    EXPECT_NEAR(fresh.types.at(type).f1(), score.f1(), kF1Tol);
    EXPECT_EQ(fresh.types.at(type).support(), score.support());
  }
}

// The shipped model beats the SpERT validation row on every type.
TEST(LanguageModel, ShippedModelBeatsSpertOnEveryType) {
  const auto scores = evaluateModel(LanguageModel::load(defaultModelPath()), readSpertCorpus(kVal));
  for (const auto& [type, spertF1] : kSpertValF1) {
    SCOPED_TRACE(type);
    EXPECT_GT(scores.types.at(type).f1(), spertF1);
  }
}

TEST(LanguageModel, AnnotatesAPickAndPlaceSentence) {
  const auto model = LanguageModel::load(defaultModelPath());
  const auto s = model.annotate({"pick", "the", "red", "block", "and", "put", "it", "on", "the", "green", "block"});
  const std::vector<EntitySpan> expected{{0, 1, "Action"}, {2, 3, "Color"}, {5, 6, "Action"},
                                         {7, 8, "GoalIndicator"}, {9, 10, "Color"}};
  EXPECT_EQ(s.entities, expected);
  ASSERT_EQ(s.relations.size(), 1u);
  EXPECT_EQ(s.relations[0].type, "Transition");
  EXPECT_EQ(s.entities[s.relations[0].head].start, 5);
  EXPECT_EQ(s.entities[s.relations[0].tail].start, 7);
  EXPECT_TRUE(model.annotate({}).entities.empty());
}

// "take / get X on Y" locates X (the corpus' convention for these actions), and
// the trajector is the object, not the person it is fetched for.
TEST(LanguageModel, IndicatorOfAFetchVerbIsSpatial) {
  const auto model = LanguageModel::load(defaultModelPath());
  const auto s = model.annotate({"get", "me", "the", "wallet", "on", "the", "pillow"});
  const std::vector<EntitySpan> expected{{0, 1, "Action"}, {3, 4, "Trajector"}, {4, 5, "SpatialIndicator"}};
  EXPECT_EQ(s.entities, expected);
  ASSERT_EQ(s.relations.size(), 1u);
  EXPECT_EQ(s.relations[0].type, "Spatial");
}

// A participle phrase locates the object; the clause's goal is the next phrase.
TEST(LanguageModel, ParticiplePhraseIsSpatialAndTheNextIsTheGoal) {
  const auto model = LanguageModel::load(defaultModelPath());
  const auto s = model.annotate({"put", "the", "grey", "pyramid", "which", "is", "putted", "on", "a", "green", "box",
                                 "on", "another", "green", "box"});
  std::vector<std::string> indicatorTypes;
  for (const auto& e : s.entities)
    if (e.type == "SpatialIndicator" || e.type == "GoalIndicator") indicatorTypes.push_back(e.type);
  EXPECT_EQ(indicatorTypes, (std::vector<std::string>{"SpatialIndicator", "GoalIndicator"}));
}

TEST(LanguageModel, MissingOrCorruptModelFileNamesThePath) {
  try {
    LanguageModel::load("/nonexistent/language_model.dat");
    FAIL() << "no exception";
  } catch (const srp::core::FileError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/language_model.dat"), std::string::npos);
  }
  EXPECT_THROW(LanguageModel::load(kVal), srp::core::FileError);  // a JSON file is not a model
}
