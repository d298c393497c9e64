#include "srp/language/PhraseRules.h"

#include <gtest/gtest.h>

#include <set>
#include <sstream>

using namespace srp::language;

namespace {
std::vector<std::string> words(const std::string& text) {
  std::istringstream in(text);
  std::vector<std::string> out;
  for (std::string w; in >> w;) out.push_back(w);
  return out;
}
std::string lemma(const std::string& w) { return w; }
}  // namespace

// The corpus' spans of direction phrases (datasets/language/capabilities/README.md).
TEST(PhraseRules, DirectionSpanLengthFollowsTheCorpusConventions) {
  const std::vector<std::pair<std::string, int>> cases{
      {"left of the box", 2},
      {"right to the plate", 2},
      {"next to the cuboid", 2},
      {"in front of the microwave", 3},
      {"on top of the cube", 3},
      {"to top of the block", 3},
      {"to the top of the tower", 4},
      {"at the top left corner of the box", 6},
      {"in the exact center of the board", 5},
      {"in the far right corner of the board", 6},
      {"on the left side of the box", 5},
      {"to the left of the kettle", 4},
      {"to the left .", 3},
      {"in the middle , next to", 3},
      {"on top .", 2},
      {"in the center .", 3},
      // The landmark is the region or the side itself.
      {"in the corner of the board", 0},
      {"on the top right corner .", 0},
      {"on the left .", 0},
      {"at the center and", 0},
      {"on the table", 0},
      {"right next to", 0},
  };
  for (const auto& [text, length] : cases) EXPECT_EQ(PhraseRules::directionSpanLength(words(text), 0), length) << text;
  EXPECT_EQ(PhraseRules::directionSpanLength(words("on"), 3), 0);  // out of range
}

TEST(PhraseRules, DirectionSpansGrowTheTaggersIndicators) {
  // "[on] the top left corner of" grows; "right [to]" grows back; "[next] [to]" becomes one.
  auto w = words("put it on the top left corner of the tray and the cup right to the box and it next to the cup");
  std::vector<EntitySpan> e{{0, 1, "Action"}, {2, 3, "GoalIndicator"}, {14, 15, "GoalIndicator"},
                            {19, 20, "GoalIndicator"}, {20, 21, "GoalIndicator"}};
  PhraseRules::applyDirectionSpans(w, e);
  const std::vector<EntitySpan> expected{{0, 1, "Action"}, {2, 8, "GoalIndicator"}, {13, 15, "GoalIndicator"},
                                         {19, 21, "GoalIndicator"}};
  EXPECT_EQ(e, expected);
  // A span never grows over another entity that it does not contain.
  w = words("put it in the far left corner of the box");
  e = {{0, 1, "Action"}, {2, 3, "GoalIndicator"}, {4, 6, "Color"}};
  PhraseRules::applyDirectionSpans(w, e);
  EXPECT_EQ(e[1], (EntitySpan{2, 3, "GoalIndicator"}));
}

TEST(PhraseRules, SourceSpansAndSourceWords) {
  const auto w = words("take the cup out of the box and the knife away from the edge");
  std::vector<EntitySpan> e{{0, 1, "Action"}, {3, 4, "SpatialIndicator"}, {11, 12, "SpatialIndicator"}};
  PhraseRules::applySourceSpans(w, e);
  EXPECT_EQ(e[1], (EntitySpan{3, 5, "SpatialIndicator"}));
  EXPECT_EQ(e[2], (EntitySpan{10, 12, "SpatialIndicator"}));
  EXPECT_TRUE(PhraseRules::isSourceAt(w, 3));
  EXPECT_TRUE(PhraseRules::isSourceAt(w, 10));
  EXPECT_FALSE(PhraseRules::isSourceAt(w, 2));
  EXPECT_TRUE(PhraseRules::isSourceAt(words("lift it off the shelf"), 2));
}

TEST(PhraseRules, PlacingClauseWithoutAGoalTakesItsBarePhrase) {
  auto w = words("place it directly below , then pick up the cube .");
  std::vector<EntitySpan> e{{0, 1, "Action"}, {6, 7, "Action"}};
  PhraseRules::addPlacingClauseGoals(w, e, lemma);
  EXPECT_EQ(e, (std::vector<EntitySpan>{{0, 1, "Action"}, {3, 4, "GoalIndicator"}, {6, 7, "Action"}}));
  // After a source the next phrase is the goal: "place the ball off the shelf on the floor".
  w = words("place the ball off the shelf on the floor");
  e = {{0, 1, "Action"}, {3, 4, "SpatialIndicator"}};
  PhraseRules::addPlacingClauseGoals(w, e, lemma);
  ASSERT_EQ(e.size(), 3u);
  EXPECT_EQ(e[2], (EntitySpan{6, 7, "GoalIndicator"}));
  // No goal from a relative clause, a measured offset or a pick verb; none before "there".
  for (const std::string text : {"put the cup that is below", "move the cube one square to the left",
                                 "pick up the block below"}) {
    w = words(text);
    e = {{0, 1, "Action"}};
    PhraseRules::addPlacingClauseGoals(w, e, lemma);
    EXPECT_EQ(e.size(), 1u) << text;
  }
  w = words("put the books over there");
  e = {{0, 1, "Action"}, {3, 4, "GoalIndicator"}};
  PhraseRules::addPlacingClauseGoals(w, e, lemma);
  EXPECT_EQ(e, (std::vector<EntitySpan>{{0, 1, "Action"}}));
}

TEST(PhraseRules, OfBeforeARoomLocatesTheNounBeforeIt) {
  const std::set<std::string> rooms{"kitchen", "room"};
  const auto isRoom = [&](const std::string& w) { return rooms.count(w) > 0; };
  const auto isNoun = [](const std::string& w) {
    return std::set<std::string>{"table", "kitchen", "glass", "water", "edge", "dining", "room"}.count(w) > 0;
  };
  auto w = words("put the cup on the table of the kitchen");
  std::vector<EntitySpan> e{{0, 1, "Action"}, {3, 4, "GoalIndicator"}};
  PhraseRules::addRoomOfIndicators(w, e, isNoun, isRoom);
  const std::vector<EntitySpan> expected{{0, 1, "Action"}, {3, 4, "GoalIndicator"}, {5, 6, "Trajector"},
                                         {6, 7, "SpatialIndicator"}};
  EXPECT_EQ(e, expected);
  w = words("put it on the table of the dining room");  // the head of "dining room" is "room"
  e = {{0, 1, "Action"}};
  PhraseRules::addRoomOfIndicators(w, e, isNoun, isRoom);
  EXPECT_EQ(e.size(), 3u);
  for (const std::string text : {"bring me a glass of water", "put it on the edge of the kitchen"}) {
    w = words(text);
    e = {{0, 1, "Action"}};
    PhraseRules::addRoomOfIndicators(w, e, isNoun, isRoom);
    EXPECT_EQ(e.size(), 1u) << text;
  }
}
