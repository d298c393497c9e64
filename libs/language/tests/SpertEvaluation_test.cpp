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
