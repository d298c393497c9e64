#include "srp/language/Tokenizer.h"

#include <gtest/gtest.h>

using srp::language::tokenizeSentences;

TEST(Tokenizer, SplitsSentencesAndKeepsOffsets) {
  const std::string text = "Pick up the cuboid, then place it at Location 2.5. Next, move item A!";
  const auto s = tokenizeSentences(text);
  ASSERT_EQ(s.size(), 2u);
  std::vector<std::string> words;
  for (const auto& t : s[0]) words.push_back(t.text);
  EXPECT_EQ(words, (std::vector<std::string>{"Pick", "up", "the", "cuboid", ",", "then", "place", "it", "at", "Location",
                                             "2.5", "."}));
  for (const auto& sentence : s)
    for (const auto& t : sentence) EXPECT_EQ(text.substr(t.charBegin, t.charEnd - t.charBegin), t.text);
  EXPECT_EQ(s[1].back().text, "!");
}

TEST(Tokenizer, EmptyAndBlankTextGiveNoSentences) {
  EXPECT_TRUE(tokenizeSentences("").empty());
  EXPECT_TRUE(tokenizeSentences("   \n\n  ").empty());
}

TEST(Tokenizer, BlankLineEndsASentence) {
  const auto s = tokenizeSentences("pick the star\n\nplace the cube");
  ASSERT_EQ(s.size(), 2u);
  EXPECT_EQ(s[1][0].text, "place");
}
