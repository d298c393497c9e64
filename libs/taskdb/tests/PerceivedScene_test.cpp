// The perceived scene of a task model (schema 3): stored and read back with the
// model, every number checked on the way in and on the way out.
#include <gtest/gtest.h>

#include <SQLiteCpp/SQLiteCpp.h>

#include <limits>

#include "Backends.h"
#include "SqlUtil.h"
#include "TestDb.h"
#include "srp/core/Error.h"
#include "srp/core/ObjectClassJson.h"
#include "srp/taskdb/PerceivedSceneDao.h"
#include "srp/taskdb/TaskModelStore.h"

using namespace srp::taskdb;
using srp::taskdb::test::PerceivedSceneStore;

namespace {
constexpr double kPoseTol_m = 1e-12;       // stored as REAL: doubles exactly, rotations through a quaternion
constexpr double kRotationTol = 1e-12;

PerceivedScene toyScene() {
  PerceivedScene s;
  s.catalogue = "/srp/datasets/kb/catalogue.json";
  s.tableSize_m = {0.9, 0.7};
  s.X_table_camera = srp::core::makePoseYPR({0.05, 0.4, 0.8}, 0.1, 0.6, 3.0);
  SceneObjectRow bin;
  bin.objectId = "bin";
  bin.classId = 101;
  bin.className = "bin";
  bin.X_table_object.translation() = Eigen::Vector3d(0.2, -0.1, 0.0);
  SceneObjectRow toy;
  toy.objectId = "toy";
  toy.classId = 100;
  toy.className = "toy";
  toy.X_table_object = srp::core::makePoseYPR({-0.2, 0.05, 0.0}, 0.7, 0.0, 0.0);
  toy.colour = "blue";
  toy.rgb = Eigen::Vector3d(0.1, 0.2, 0.7);
  s.objects = {bin, toy};
  srp::core::ObjectClass toyClass;
  toyClass.name = "toy";
  toyClass.noun = "toy";  // the JSON form requires a usable noun
  toyClass.classId = 100;
  toyClass.shape = "hull";
  toyClass.dimensions_m = {0.12, 0.08, 0.06};
  toyClass.mass_kg = 0.05;
  toyClass.footprint_object = {{-0.06, -0.04}, {0.06, -0.04}, {0.0, 0.04}};
  toyClass.observed = true;
  srp::core::ObjectClass binClass;
  binClass.name = "bin";
  binClass.noun = "bin";
  binClass.classId = 101;
  binClass.kind = srp::core::ObjectKind::Container;
  binClass.shape = "open_box";
  binClass.dimensions_m = {0.3, 0.2, 0.15};
  binClass.wallThickness_m = 0.005;
  binClass.mass_kg = 0.4;
  binClass.observed = true;
  s.observedClasses = {toyClass, binClass};
  return s;
}

TaskModel modelWith(const PerceivedScene& s) {
  TaskModel m;
  m.info.name = "toy in bin";
  m.scene = s;
  return m;
}
}  // namespace

TEST_P(PerceivedSceneStore, StoredWithTheTaskModelAndReadBack) {
  auto db = TaskDatabase::open(newDatabase("perceived_scene"));
  const PerceivedScene s = toyScene();
  const int id = TaskModelStore(db).write(modelWith(s));
  const TaskModel back = TaskModelStore(db).read(id);
  ASSERT_TRUE(back.scene.has_value());
  EXPECT_EQ(back.scene->catalogue, s.catalogue);
  EXPECT_EQ(back.scene->tableSize_m, s.tableSize_m);
  EXPECT_LT((back.scene->X_table_camera.translation() - s.X_table_camera.translation()).norm(), kPoseTol_m);
  EXPECT_LT((back.scene->X_table_camera.linear() - s.X_table_camera.linear()).norm(), kRotationTol);
  ASSERT_EQ(back.scene->objects.size(), 2u);
  EXPECT_EQ(back.scene->objects[1].objectId, "toy");
  EXPECT_EQ(back.scene->objects[1].colour, std::optional<std::string>("blue"));
  EXPECT_EQ(back.scene->objects[1].rgb, s.objects[1].rgb);
  EXPECT_FALSE(back.scene->objects[0].colour.has_value());
  EXPECT_LT((back.scene->objects[1].X_table_object.matrix() - s.objects[1].X_table_object.matrix()).norm(), kRotationTol);
  ASSERT_EQ(back.scene->observedClasses.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i)
    EXPECT_EQ(srp::core::objectClassToJson(back.scene->observedClasses[i]),
              srp::core::objectClassToJson(s.observedClasses[i]));
  // JSON form (db show --json, db import) round-trips too (poses through their quaternion).
  const TaskModel again = taskModelFromJson(toJson(back), "json");
  ASSERT_TRUE(again.scene.has_value());
  EXPECT_LT((again.scene->X_table_camera.matrix() - back.scene->X_table_camera.matrix()).norm(), kRotationTol);
  ASSERT_EQ(again.scene->objects.size(), back.scene->objects.size());
  for (std::size_t i = 0; i < back.scene->objects.size(); ++i)
    EXPECT_LT((again.scene->objects[i].X_table_object.matrix() - back.scene->objects[i].X_table_object.matrix()).norm(),
              kRotationTol);
  EXPECT_EQ(toJson(again)["perceived_scene"]["observed_classes"], toJson(back)["perceived_scene"]["observed_classes"]);
  // Deleting the task model deletes its scene.
  TaskModelStore(db).remove(id);
  EXPECT_FALSE(PerceivedSceneDao(db).get(id).has_value());
  detail::Statement left(db, "SELECT (SELECT COUNT(*) FROM SceneObjects) + (SELECT COUNT(*) FROM ObservedClasses)");
  ASSERT_TRUE(left.executeStep());
  EXPECT_EQ(left.getColumn(0).getInt(), 0);
}

TEST_P(PerceivedSceneStore, ANonFiniteNumberIsRefusedAndNothingIsWritten) {
  auto db = TaskDatabase::open(newDatabase("perceived_scene_bad"));
  PerceivedScene s = toyScene();
  s.objects[1].X_table_object.translation().x() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(TaskModelStore(db).write(modelWith(s)), srp::core::Error);
  s = toyScene();
  s.tableSize_m.y() = std::numeric_limits<double>::infinity();
  EXPECT_THROW(TaskModelStore(db).write(modelWith(s)), srp::core::Error);
  s = toyScene();
  s.observedClasses[0].dimensions_m.z() = -0.01;
  EXPECT_THROW(TaskModelStore(db).write(modelWith(s)), srp::core::Error);
  EXPECT_TRUE(TaskModelStore(db).list().empty());
}

TEST(PerceivedScene, ADamagedRowIsRefusedNamingTableRowAndColumn) {
  test::TempDbPath path("perceived_scene_damaged");
  int id = 0;
  {
    auto db = TaskDatabase::open(path.str());
    id = TaskModelStore(db).write(modelWith(toyScene()));
  }
  const auto run = [&](const std::string& sql) {
    SQLite::Database raw(path.str(), SQLite::OPEN_READWRITE);
    raw.exec(sql);
  };
  const auto refusal = [&](const std::string& sql) -> std::string {
    run(sql);
    auto db = TaskDatabase::open(path.str(), TaskDatabase::Mode::ReadOnly);
    try {
      TaskModelStore(db).read(id);
    } catch (const srp::core::FileError& e) {
      return e.what();
    }
    ADD_FAILURE() << "read back after: " << sql;
    return "";
  };
  std::string what = refusal("UPDATE SceneObjects SET QZ = 9e999 WHERE ObjectId = 'toy'");  // +inf
  EXPECT_NE(what.find("table SceneObjects, row 'toy'"), std::string::npos) << what;
  EXPECT_NE(what.find("column QZ"), std::string::npos) << what;
  run("UPDATE SceneObjects SET QZ = 0 WHERE ObjectId = 'toy'");
  what = refusal("UPDATE SceneObjects SET QW = 0, QX = 0, QY = 0, QZ = 0 WHERE ObjectId = 'toy'");
  EXPECT_NE(what.find("quaternion of norm 0"), std::string::npos) << what;
  run("UPDATE SceneObjects SET QW = 1 WHERE ObjectId = 'toy'");
  what = refusal("UPDATE PerceivedScenes SET CameraY = -9e999");
  EXPECT_NE(what.find("table PerceivedScenes"), std::string::npos) << what;
  EXPECT_NE(what.find("column CameraY"), std::string::npos) << what;
  run("UPDATE PerceivedScenes SET CameraY = 0.4");
  what = refusal("UPDATE ObservedClasses SET Definition = json_set(Definition, '$.mass_kg', -1) WHERE Name = 'toy'");
  EXPECT_NE(what.find("table ObservedClasses, row 'toy'"), std::string::npos) << what;
  EXPECT_NE(what.find("mass_kg"), std::string::npos) << what;
}
