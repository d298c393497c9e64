#include <gtest/gtest.h>

#include <limits>

#include "srp/core/Error.h"
#include "srp/core/PositionTrajectory.h"
#include "srp/core/SkillType.h"

using namespace srp::core;

TEST(PositionTrajectory, AppendsInOrderAndCountsValid) {
  PositionTrajectory hand("camera");
  hand.append({0, 0.0, {0.1, 0.2, 0.3}, true});
  hand.append({1, 1.0 / 30, {0, 0, 0}, false});
  hand.append({2, 2.0 / 30, {0.2, 0.2, 0.3}, true});
  EXPECT_EQ(hand.size(), 3u);
  EXPECT_EQ(hand.validCount(), 2u);
  EXPECT_DOUBLE_EQ(hand.positions()(0, 2), 0.2);
  EXPECT_DOUBLE_EQ(hand.times()(1), 1.0 / 30);
  EXPECT_THROW(hand.append({3, 0.01, {0, 0, 0}, true}), InvalidInputError);
  EXPECT_THROW(hand.append({3, 1.0, {std::numeric_limits<double>::quiet_NaN(), 0, 0}, true}),
               InvalidInputError);
  hand.append({3, 1.0, {std::numeric_limits<double>::quiet_NaN(), 0, 0}, false});
}

TEST(SkillType, StringRoundTrip) {
  for (SkillType s : kAllSkillTypes) EXPECT_EQ(skillTypeFromString(toString(s)), s);
  EXPECT_THROW(skillTypeFromString("reach"), InvalidInputError);
}
