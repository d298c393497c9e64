#include "srp/core/SpatialRelations.h"

#include <gtest/gtest.h>

using namespace srp::core;

// Every neighbour wording of the thesis' Appendix A instructions.
TEST(SpatialRelations, AppendixANeighbourWordsAreNeighbourRelations) {
  for (const char* w : {"next to", "beside", "adjacent to", "near", "alongside"}) EXPECT_TRUE(isNeighbourRelation(w)) << w;
  for (const char* w : {"in", "into", "from", "out of", "back to"}) EXPECT_FALSE(isNeighbourRelation(w)) << w;
}

TEST(SpatialRelations, ContainmentWords) {
  for (const char* w : {"in", "into", "inside", "on", "back to"}) EXPECT_TRUE(isContainmentRelation(w)) << w;
  for (const char* w : {"from", "next to", "out of", ""}) EXPECT_FALSE(isContainmentRelation(w)) << w;
}
