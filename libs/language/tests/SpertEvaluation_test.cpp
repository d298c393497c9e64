#include "srp/language/SpertEvaluation.h"

#include <gtest/gtest.h>

#include "srp/core/Error.h"

using namespace srp::language;

TEST(SpertEvaluation, ExactSpanAndTypeAndBothEntitiesOfARelation) {
  constexpr double kTol = 1e-12;
  AnnotatedSentence gold;
  gold.tokens = {"put", "the", "cube", "on", "top", "of", "the", "box"};
  gold.entities = {{0, 1, "Action"}, {3, 6, "GoalIndicator"}};
  gold.relations = {{0, 1, "Transition"}};
  AnnotatedSentence pred = gold;
  pred.entities = {{0, 1, "Action"}, {3, 4, "GoalIndicator"}, {2, 3, "Trajector"}};  // span too short, extra entity
  pred.relations = {{0, 1, "Transition"}};
  const auto s = scoreSpert({gold}, {pred});
  EXPECT_EQ(s.types.at("Action").truePositives, 1);
  EXPECT_EQ(s.types.at("GoalIndicator").falsePositives, 1);
  EXPECT_EQ(s.types.at("GoalIndicator").falseNegatives, 1);
  EXPECT_EQ(s.types.at("Trajector").falsePositives, 1);
  // The relation's tail has the wrong span, so the relation is wrong too.
  EXPECT_EQ(s.types.at("Transition").truePositives, 0);
  EXPECT_EQ(s.types.at("Transition").support(), 1);
  EXPECT_NEAR(s.types.at("Action").f1(), 1.0, kTol);
  EXPECT_NEAR(s.types.at("GoalIndicator").f1(), 0.0, kTol);
  const auto perfect = scoreSpert({gold}, {gold});
  EXPECT_NEAR(perfect.types.at("Transition").f1(), 1.0, kTol);
  EXPECT_NEAR(perfect.types.at("GoalIndicator").precision(), 1.0, kTol);
}

TEST(SpertEvaluation, MismatchedCorporaAreRejected) {
  AnnotatedSentence a;
  a.tokens = {"pick"};
  EXPECT_THROW(scoreSpert({a}, {}), srp::core::InvalidInputError);
}

// Cross-validation on a slice of the training corpus: every sentence gets one
// out-of-fold prediction, the pooled supports are the gold counts, the fold
// threads do not change the result, and actions are still found.
TEST(SpertEvaluation, CrossValidationIsOutOfFoldAndDeterministic) {
  constexpr double kMinActionF1 = 0.9;
  auto corpus = readSpertCorpus(std::string(SRP_DATASETS_DIR) + "/language/train.json");
  corpus.resize(90);
  const auto oneThread = crossValidate(corpus, {}, 3, 1);
  const auto twoThreads = crossValidate(corpus, {}, 3, 2);
  ASSERT_EQ(oneThread.predictions.size(), corpus.size());
  int goalIndicators = 0;
  for (const auto& s : corpus)
    for (const auto& e : s.entities) goalIndicators += e.type == "GoalIndicator";
  EXPECT_EQ(oneThread.scores.types.at("GoalIndicator").support(), goalIndicators);
  for (const auto& [type, score] : oneThread.scores.types) {
    SCOPED_TRACE(type);
    EXPECT_EQ(score.truePositives, twoThreads.scores.types.at(type).truePositives);
    EXPECT_EQ(score.falsePositives, twoThreads.scores.types.at(type).falsePositives);
  }
  EXPECT_GT(oneThread.scores.types.at("Action").f1(), kMinActionF1);
  EXPECT_THROW(crossValidate(corpus, {}, 1), srp::core::InvalidInputError);
}

// The pooled protocol: every (seed, fold) scores each sentence of its fold once,
// the per-fold supports add up to the corpus' gold counts per seed, a variant
// with the baseline's rules has zero difference, and threads change nothing.
TEST(SpertEvaluation, RepeatedCrossValidationIsPairedAndDeterministic) {
  constexpr double kTol = 1e-12;
  auto corpus = readSpertCorpus(std::string(SRP_DATASETS_DIR) + "/language/train.json");
  corpus.resize(36);
  LanguageModel::Options options;
  DecodingRules noSpans = options.rules;
  noSpans.spanLengths = false;
  const auto cv = repeatedCrossValidate(corpus, options, 3, 2, 2, {{"same", options.rules}, {"no_spans", noSpans}});
  ASSERT_EQ(cv.folds.size(), 3u);
  ASSERT_EQ(cv.folds[0].size(), 6u);
  int goals = 0;
  for (const auto& s : corpus)
    for (const auto& e : s.entities) goals += e.type == "GoalIndicator";
  for (int seed = 0; seed < 2; ++seed) {
    int support = 0;
    for (int fold = 0; fold < 3; ++fold) support += cv.folds[0][seed * 3 + fold].types.at("GoalIndicator").support();
    EXPECT_EQ(support, goals);
  }
  for (const std::string type : {"Action", "SpatialIndicator", "Transition", "macro"}) {
    const auto same = cvF1Difference(cv.folds[1], cv.folds[0], type);
    EXPECT_NEAR(same.mean, 0.0, kTol);
    EXPECT_NEAR(same.std, 0.0, kTol);
  }
  const auto oneThread = repeatedCrossValidate(corpus, options, 3, 2, 1);
  for (size_t job = 0; job < 6; ++job)
    EXPECT_EQ(oneThread.folds[0][job].types.at("Trajector").truePositives,
              cv.folds[0][job].types.at("Trajector").truePositives);
  ASSERT_EQ(cv.firstSeedPredictions.size(), corpus.size());
  EXPECT_EQ(cv.firstSeedPredictions[7].tokens, corpus[7].tokens);
  const std::string table = formatCrossValidation(cv);
  EXPECT_NE(table.find("3-fold cross-validation x 2 seeds"), std::string::npos) << table;
  EXPECT_NE(table.find("no_spans"), std::string::npos) << table;
  EXPECT_THROW(repeatedCrossValidate(corpus, options, 3, 0), srp::core::InvalidInputError);
}

TEST(SpertEvaluation, EntityErrorsAreClassifiedByKind) {
  AnnotatedSentence gold, pred;
  gold.tokens = pred.tokens = {"take", "the", "cup", "near", "to", "the", "box", "on", "the", "table", "in", "it"};
  gold.entities = {{0, 1, "Action"}, {2, 3, "Trajector"}, {3, 4, "SpatialIndicator"}, {7, 8, "SpatialIndicator"}};
  pred.entities = {{0, 1, "Action"}, {2, 3, "Trajector"}, {3, 5, "SpatialIndicator"}, {7, 8, "GoalIndicator"},
                   {10, 11, "SpatialIndicator"}};
  const auto errors = entityErrors({gold}, {pred});
  ASSERT_EQ(errors.size(), 4u);
  EXPECT_EQ(errors[0].kind, "boundary");  // gold "near" vs predicted "near to"
  EXPECT_TRUE(errors[0].goldSide);
  EXPECT_EQ(errors[1].kind, "type");  // "on": spatial predicted as a goal, listed once
  EXPECT_EQ(errors[1].otherType, "GoalIndicator");
  EXPECT_EQ(errors[2].kind, "boundary");  // predicted "near to"
  EXPECT_FALSE(errors[2].goldSide);
  EXPECT_EQ(errors[3].kind, "spurious");  // predicted "in"
  const std::string dump = formatEntityErrors({gold}, {pred}, {"SpatialIndicator"});
  EXPECT_NE(dump.find("gold boundary 1;"), std::string::npos) << dump;
  EXPECT_NE(dump.find("pred spurious SpatialIndicator \"in\""), std::string::npos) << dump;
  EXPECT_NE(dump.find("[near to]SpatialIndicator"), std::string::npos) << dump;
  EXPECT_EQ(formatEntityErrors({gold}, {gold}).find("#0"), std::string::npos);  // no error, no sentence
  EXPECT_THROW(entityErrors({gold}, {}), srp::core::InvalidInputError);
}
