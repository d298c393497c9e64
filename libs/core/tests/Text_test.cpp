#include "srp/core/Text.h"

#include <gtest/gtest.h>

using srp::core::normaliseName;
using srp::core::toLowerAscii;

TEST(Text, LowerCasesAsciiLettersOnly) {
  EXPECT_EQ(toLowerAscii("Put The BLUE_Box"), "put the blue_box");
  EXPECT_EQ(toLowerAscii("Gr\xC3\x9C\x6E 42"), "gr\xC3\x9C\x6E 42");  // UTF-8 bytes unchanged
}

TEST(Text, NormalisedNamesCompareAcrossSpellings) {
  EXPECT_EQ(normaliseName("Blue_Box "), "blue box");
  EXPECT_EQ(normaliseName("  to-the-left of"), "to the left of");
  EXPECT_EQ(normaliseName("cuboid_red"), normaliseName("CUBOID RED"));
  EXPECT_EQ(normaliseName(" _- "), "");
}
