// Schema 1 -> 2 (instance ids, issue 19): a database file written by srp before
// the change (tests/data/schema_v1.db, see tests/data/README.md) still opens,
// keeps every row, and then stores two instances of one class.
#include <gtest/gtest.h>

#include <SQLiteCpp/SQLiteCpp.h>

#include <filesystem>

#include "MigrationFixture.h"
#include "TestDb.h"
#include "srp/core/Error.h"
#include "srp/core/Json.h"
#include "srp/taskdb/GroundedProductDao.h"
#include "srp/taskdb/ProductPoseDao.h"
#include "srp/taskdb/SkillDao.h"
#include "srp/taskdb/TaskModelStore.h"

using namespace srp::taskdb;

namespace {
using test::kFixture;
using test::expectEveryRowOfTheFixture;

int userVersion(const std::string& path) {
  SQLite::Database raw(path, SQLite::OPEN_READONLY);
  return raw.execAndGet("PRAGMA user_version").getInt();
}
}  // namespace

TEST(Migration, SchemaOneFileOpensWithEveryRowAndGainsInstanceIds) {
  ASSERT_TRUE(std::filesystem::exists(kFixture)) << kFixture;
  ASSERT_EQ(userVersion(kFixture), 1) << "the fixture must stay a schema-1 file";
  test::TempDbPath path("migrate_v1");
  std::filesystem::copy_file(kFixture, path.str());

  // Read-only cannot migrate: it says how to.
  try {
    TaskDatabase::open(path.str(), TaskDatabase::Mode::ReadOnly);
    ADD_FAILURE() << "a schema-1 file opened read-only without migration";
  } catch (const srp::core::FileError& e) {
    EXPECT_NE(std::string(e.what()).find("read-write to migrate"), std::string::npos) << e.what();
  }

  auto db = TaskDatabase::open(path.str());
  EXPECT_EQ(db.schemaVersion(), kSchemaVersion);
  const TaskModel read = TaskModelStore(db).read(1);
  expectEveryRowOfTheFixture(read);
  for (const auto& g : read.groundedProducts) EXPECT_EQ(g.instanceId, "");

  // The migrated file now holds two instances of one class, with their own poses and skills.
  const TaskModel two = test::twoCuboidsModel();
  const ProductPoseRow blue = two.productPoses[1];
  const int id = TaskModelStore(db).write(two);
  const TaskModel back = TaskModelStore(db).read(id);
  EXPECT_EQ(back.groundedProducts.size(), 2u);
  EXPECT_EQ(back.productPoses.size(), 2u);
  EXPECT_EQ(back.products, two.products);
  const auto bluePose = ProductPoseDao(db).get(id, 3, 1, "cuboid_blue");
  ASSERT_TRUE(bluePose.has_value());
  EXPECT_EQ(bluePose->p_m, blue.p_m);
  EXPECT_TRUE(GroundedProductDao(db).get(id, 3, "cuboid_red").has_value());
  EXPECT_FALSE(GroundedProductDao(db).get(id, 3).has_value());  // no instance-less row in this model
  EXPECT_TRUE(SkillDao(db).get(id, 3, srp::core::SkillType::Grasp, "cuboid_blue").has_value());
  // A product grounded to an instance that has no GroundedProducts row is refused.
  TaskModel dangling = two;
  dangling.info.name = "dangling";
  dangling.products[0].instanceId = "cuboid_green";
  EXPECT_THROW(TaskModelStore(db).write(dangling), srp::core::Error);
}

TEST(Migration, ReopeningAMigratedFileKeepsItAsItIs) {
  test::TempDbPath path("migrate_twice");
  std::filesystem::copy_file(kFixture, path.str());
  { TaskDatabase::open(path.str()); }
  { auto db = TaskDatabase::open(path.str()); EXPECT_EQ(TaskModelStore(db).list().size(), 1u); }
  auto ro = TaskDatabase::open(path.str(), TaskDatabase::Mode::ReadOnly);
  EXPECT_EQ(ro.schemaVersion(), kSchemaVersion);
  EXPECT_EQ(TaskModelStore(ro).read(1).productPoses.size(), 9u);
}

// Schema 2 -> 3 (the perceived scene): a file written by srp before the change
// (tests/data/schema_v2.db) opens with every row, its task model has no scene,
// and the migrated file then stores a model with one.
TEST(Migration, SchemaTwoFileOpensWithEveryRowAndThenStoresAPerceivedScene) {
  const std::string& fixture = test::kFixtureV2;
  ASSERT_EQ(userVersion(fixture), 2) << "the fixture must stay a schema-2 file";
  test::TempDbPath path("migrate_v2");
  std::filesystem::copy_file(fixture, path.str());
  auto db = TaskDatabase::open(path.str());
  EXPECT_EQ(db.schemaVersion(), kSchemaVersion);
  const TaskModel read = TaskModelStore(db).read(1);
  expectEveryRowOfTheFixture(read);
  EXPECT_FALSE(read.scene.has_value()) << "programmed before schema 3: no perceived scene";
  TaskModel withScene;
  withScene.info.name = "with a scene";
  withScene.scene = PerceivedScene{};
  withScene.scene->catalogue = "catalogue.json";
  withScene.scene->objects.push_back({"cuboid", 3, "cuboid", srp::core::Pose3::Identity(), std::nullopt, std::nullopt});
  const int id = TaskModelStore(db).write(withScene);
  const TaskModel back = TaskModelStore(db).read(id);
  ASSERT_TRUE(back.scene.has_value());
  EXPECT_EQ(back.scene->objects.size(), 1u);
}
