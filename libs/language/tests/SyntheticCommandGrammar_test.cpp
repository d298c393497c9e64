#include "srp/language/SyntheticCommandGrammar.h"

#include <gtest/gtest.h>

#include <set>
#include <string>

#include "srp/core/Text.h"

using namespace srp::language;

namespace {
std::string lowerWords(const AnnotatedSentence& s, const EntitySpan& e) {
  std::string t;
  for (int k = e.start; k < e.end; ++k) {
    const std::string w = srp::core::toLowerAscii(s.tokens[k]);
    t += (k > e.start ? " " : "") + w;
  }
  return t;
}
}  // namespace

// Same seed, same commands; another seed, other commands.
TEST(SyntheticCommandGrammar, IsSeeded) {
  const SyntheticCommandGrammar grammar;
  const auto a = grammar.generate(50, 7), b = grammar.generate(50, 7), c = grammar.generate(50, 8);
  ASSERT_EQ(a.size(), 50u);
  int same = 0, sameAsOtherSeed = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    same += a[i].tokens == b[i].tokens && a[i].entities == b[i].entities;
    sameAsOtherSeed += a[i].tokens == c[i].tokens;
  }
  EXPECT_EQ(same, 50);
  EXPECT_LT(sameAsOtherSeed, 10);
}

// Every annotation follows the corpus' schema: spans inside the sentence and
// disjoint, Spatial = Trajector -> SpatialIndicator, Transition = Action ->
// GoalIndicator, a Trajector only with a Spatial relation; and the structures
// the grammar promises occur (a source phrase before a goal in one clause,
// multi-word directions, a goal with no landmark).
TEST(SyntheticCommandGrammar, WritesTheCorpusSchemaWithTheStructures) {
  const auto sentences = SyntheticCommandGrammar().generate(400, 1);
  int sourceThenGoal = 0, multiWordGoal = 0, bareGoal = 0;
  for (const auto& s : sentences) {
    std::vector<int> owner(s.tokens.size(), -1);
    for (size_t e = 0; e < s.entities.size(); ++e) {
      const auto& span = s.entities[e];
      ASSERT_TRUE(span.start >= 0 && span.start < span.end && span.end <= static_cast<int>(s.tokens.size()));
      for (int k = span.start; k < span.end; ++k) {
        EXPECT_EQ(owner[k], -1) << "overlapping entities";
        owner[k] = static_cast<int>(e);
      }
    }
    std::set<int> trajectorsInRelations;
    for (const auto& r : s.relations) {
      const auto& h = s.entities.at(r.head);
      const auto& t = s.entities.at(r.tail);
      if (r.type == "Spatial") {
        EXPECT_EQ(h.type, "Trajector");
        EXPECT_EQ(t.type, "SpatialIndicator");
        trajectorsInRelations.insert(r.head);
      } else {
        EXPECT_EQ(r.type, "Transition");
        EXPECT_EQ(h.type, "Action");
        EXPECT_EQ(t.type, "GoalIndicator");
        if (t.end - t.start >= 3) ++multiWordGoal;
        if (t.end == static_cast<int>(s.tokens.size()) || s.tokens[t.end] == "." || s.tokens[t.end] == "please")
          ++bareGoal;
      }
    }
    for (size_t e = 0; e < s.entities.size(); ++e)
      if (s.entities[e].type == "Trajector") EXPECT_TRUE(trajectorsInRelations.count(static_cast<int>(e)));
    for (size_t a = 0; a < s.entities.size(); ++a)
      for (size_t b = 0; b < s.entities.size(); ++b)
        if (s.entities[a].type == "SpatialIndicator" && s.entities[b].type == "GoalIndicator" &&
            s.entities[a].end <= s.entities[b].start && lowerWords(s, s.entities[a]).rfind("from", 0) == 0)
          ++sourceThenGoal;
  }
  EXPECT_GT(sourceThenGoal, 20);
  EXPECT_GT(multiWordGoal, 20);
  EXPECT_GT(bareGoal, 10);
}
