#include "srp/language/AnnotationPrecedents.h"

#include <gtest/gtest.h>

#include "srp/core/Error.h"

using namespace srp::language;

namespace {
AnnotatedSentence sentence(std::vector<std::string> tokens, std::vector<EntitySpan> entities) {
  AnnotatedSentence s;
  s.tokens = std::move(tokens);
  s.entities = std::move(entities);
  return s;
}
const std::vector<std::string> kBehind{"Pick", "up", "the", "blue", "block", "behind", "the", "orange", "block"};
const std::vector<std::string> kMiddle{"take", "the", "cup", "in", "the", "middle", ",", "please"};
}  // namespace

TEST(AnnotationPrecedents, CountsTheLabelsOfTheSameContext) {
  const std::vector<EntitySpan> behind{{0, 1, "Action"}, {5, 6, "SpatialIndicator"}};
  const AnnotationPrecedents train({sentence(kBehind, behind), sentence(kBehind, behind), sentence(kBehind, {})});
  EXPECT_EQ(AnnotationPrecedents::labelAt(sentence(kBehind, behind), 5), "SpatialIndicator:1");
  EXPECT_EQ(AnnotationPrecedents::labelAt(sentence(kBehind, behind), 4), "none");
  auto lower = kBehind;
  lower[0] = "pick";  // contexts are lower-case
  const auto counts = train.at(lower, 5);
  ASSERT_EQ(counts.size(), 2u);
  EXPECT_EQ(counts.at("SpatialIndicator:1"), 2);
  EXPECT_EQ(counts.at("none"), 1);
  EXPECT_EQ(AnnotationPrecedents::majority(counts), "SpatialIndicator:1");
  EXPECT_EQ(AnnotationPrecedents::majority({{"none", 1}, {"SpatialIndicator:1", 1}}), "");  // a tie has none
  auto red = kBehind;
  red[3] = "red";  // another word within 3 of the position: another context
  EXPECT_TRUE(train.at(red, 5).empty());
  EXPECT_THROW(AnnotationPrecedents({}, -1), srp::core::InvalidInputError);
}

// Errors where the reference corpus annotates the same context as the model
// predicted are counted, and the "if consistent" scores count them right,
// each position once even when a boundary error has a gold and a predicted side.
TEST(AnnotationPrecedents, ErrorsAgainstPrecedentAreCountedOnce) {
  constexpr double kTol = 1e-12;
  const std::vector<EntitySpan> behind{{0, 1, "Action"}, {5, 6, "SpatialIndicator"}};
  const std::vector<EntitySpan> inOnly{{0, 1, "Action"}, {3, 4, "SpatialIndicator"}};
  const std::vector<EntitySpan> inTheMiddle{{0, 1, "Action"}, {3, 6, "SpatialIndicator"}};
  const AnnotationPrecedents train({sentence(kBehind, behind), sentence(kMiddle, inOnly)});
  const auto unseen = std::vector<std::string>{"grab", "the", "mug", "beside", "the", "sink"};
  const std::vector<AnnotatedSentence> gold{sentence(kBehind, {{0, 1, "Action"}}),  // "behind" not annotated
                                            sentence(kMiddle, inTheMiddle),
                                            sentence(unseen, {{0, 1, "Action"}, {3, 4, "SpatialIndicator"}})};
  const std::vector<AnnotatedSentence> predicted{sentence(kBehind, behind), sentence(kMiddle, inOnly),
                                                 sentence(unseen, {{0, 1, "Action"}})};
  const auto check = checkAgainstPrecedents(gold, predicted, train, {"SpatialIndicator"});
  EXPECT_EQ(check.errors, 4);  // spurious "behind", boundary gold + predicted, missed "beside"
  EXPECT_EQ(check.withPrecedent, 3);
  EXPECT_EQ(check.againstPrecedent, 3);
  const TypeScore& s = check.ifConsistent.at("SpatialIndicator");
  EXPECT_EQ(s.truePositives, 2);  // "behind" and "in" accepted
  EXPECT_EQ(s.falsePositives, 0);
  EXPECT_EQ(s.falseNegatives, 1);  // "beside": no precedent, still missed
  EXPECT_NEAR(s.f1(), 0.8, kTol);
  EXPECT_EQ(check.ifConsistent.count("Action"), 0u);  // only the checked types
  EXPECT_NE(check.report.find("[behind]"), std::string::npos) << check.report;
  EXPECT_NE(check.report.find("AGAINST PRECEDENT"), std::string::npos) << check.report;
}
