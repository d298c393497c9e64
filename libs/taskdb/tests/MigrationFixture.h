#pragma once
// The task databases written by older builds of srp (tests/data/README.md) and
// the rows a migrated copy must hold; for the SQLite and the server migration tests.
#include <gtest/gtest.h>

#include <string>

#include "srp/core/Json.h"
#include "srp/taskdb/TaskModel.h"

namespace srp::taskdb::test {

/// Schema 1 and 2 files; both hold kFixtureSource's task model as id 1.
inline const std::string kFixture = std::string(SRP_SOURCE_DIR) + "/libs/taskdb/tests/data/schema_v1.db";
inline const std::string kFixtureV2 = std::string(SRP_SOURCE_DIR) + "/libs/taskdb/tests/data/schema_v2.db";
inline const std::string kFixtureSource = std::string(SRP_SOURCE_DIR) + "/libs/taskdb/tests/data/schema_v1_source.json";

/// Every row of the fixture's source task model is read back from a migrated database.
inline void expectEveryRowOfTheFixture(const TaskModel& read) {
  const TaskModel expected = taskModelFromJson(srp::core::readJsonFile(kFixtureSource), kFixtureSource);
  EXPECT_EQ(read.products, expected.products);
  EXPECT_EQ(read.sourceLocations, expected.sourceLocations);
  EXPECT_EQ(read.targetLocations, expected.targetLocations);
  EXPECT_EQ(read.targetObjectIds, expected.targetObjectIds);
  EXPECT_EQ(read.groundedProducts, expected.groundedProducts);
  EXPECT_EQ(read.productPoses, expected.productPoses);
  EXPECT_EQ(read.handPositions, expected.handPositions);
  ASSERT_EQ(read.skills.size(), 1u);
  EXPECT_EQ(read.skills, expected.skills);
}

/// A model a migrated database must take: two instances of class 3 (red and
/// blue cuboid), each with its pose at TimeId 1 and a Grasp; a product grounded
/// to the red one, the plan's one step.
inline TaskModel twoCuboidsModel() {
  TaskModel two;
  two.info.name = "two cuboids";
  two.groundedProducts = {{3, "cuboid", {}, {}, std::string("red"), "cuboid_red"},
                          {3, "cuboid", {}, {}, std::string("blue"), "cuboid_blue"}};
  ProductPoseRow red, blue;
  red.classId = blue.classId = 3;
  red.timeId = blue.timeId = 1;
  red.instanceId = "cuboid_red";
  blue.instanceId = "cuboid_blue";
  red.p_m = {0.1, 0.0, 0.5};
  blue.p_m = {-0.1, 0.0, 0.5};
  two.productPoses = {red, blue};
  two.skills = {{3, srp::core::SkillType::Grasp, 1, 1, nlohmann::json::object(), "cuboid_red"},
                {3, srp::core::SkillType::Grasp, 1, 1, nlohmann::json::object(), "cuboid_blue"}};
  two.products = {{0, "cuboid", {}, {}, std::string("red"), {}, {}, 3, "cuboid_red"}};
  two.targetObjectIds = {0};
  return two;
}

}  // namespace srp::taskdb::test
