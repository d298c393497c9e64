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

}  // namespace srp::taskdb::test
