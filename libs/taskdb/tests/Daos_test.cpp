#include <gtest/gtest.h>

#include <limits>

#include "Backends.h"
#include "TestDb.h"
#include "srp/core/Error.h"
#include "srp/taskdb/GroundedProductDao.h"
#include "srp/taskdb/HandPositionDao.h"
#include "srp/taskdb/ProductDao.h"
#include "srp/taskdb/ProductPoseDao.h"
#include "srp/taskdb/SkillDao.h"
#include "srp/taskdb/SourceLocationDao.h"
#include "srp/taskdb/TaskModelDao.h"
#include "srp/taskdb/TaskModelStore.h"

using namespace srp::taskdb;
using srp::taskdb::test::Daos;
using srp::core::InvalidInputError;

TEST_P(Daos, AddGetUpdateRemove) {
  auto db = TaskDatabase::open(newDatabase("crud"));
  TaskModelInfo info;
  info.name = "crud";
  info.intrinsics = srp::core::CameraIntrinsics{607.178, 607.234, 321.391, 241.918, 640, 480};
  info.X_base_camera = srp::core::makePoseYPR({0.1, -0.5, 0.9}, 0.3, 0.0, M_PI);
  const int id = TaskModelDao(db).add(info);
  const auto back = TaskModelDao(db).get(id);
  ASSERT_TRUE(back);
  EXPECT_EQ(*back->intrinsics, *info.intrinsics);
  EXPECT_LT((back->X_base_camera->matrix() - info.X_base_camera->matrix()).norm(), 1e-12);
  EXPECT_FALSE(back->createdUtc.empty());

  ProductDao products(db);
  products.add(id, {0, "cuboid", {}, {}, "red", 4, 0, {}});
  ProductRow p = *products.get(id, 0);
  EXPECT_EQ(p.colour, "red");
  p.colour.reset();
  p.classId = 3;
  // Outside a transaction foreign keys are checked per statement: class 3 must be grounded first.
  EXPECT_THROW(products.update(id, p), std::runtime_error);
  GroundedProductDao(db).add(id, {3, "cuboid", {}, {}, {}});
  products.update(id, p);
  EXPECT_EQ(products.get(id, 0)->classId, 3);
  EXPECT_FALSE(products.get(id, 0)->colour.has_value());
  EXPECT_THROW(products.update(id, {7, "ghost", {}, {}, {}, {}, {}, {}}), InvalidInputError);
  EXPECT_TRUE(products.remove(id, 0));
  EXPECT_FALSE(products.remove(id, 0));
  EXPECT_FALSE(products.get(id, 0).has_value());

  HandPositionDao hands(db);
  hands.add(id, {10, {0.1, 0.2, 0.3}, true});
  hands.update(id, {10, {0.4, 0.5, 0.6}, false});
  EXPECT_EQ(hands.get(id, 10)->p_m.x(), 0.4);
  EXPECT_FALSE(hands.get(id, 10)->detected);
  EXPECT_THROW(hands.add(id, {11, {std::numeric_limits<double>::quiet_NaN(), 0, 0}, true}), InvalidInputError);
}

TEST_P(Daos, SkillParametersRoundTripExactly) {
  auto db = TaskDatabase::open(newDatabase("skills"));
  TaskModel m;
  m.info.name = "skills";
  m.groundedProducts = {{3, "cuboid", {}, {}, {}}};
  nlohmann::json dmp = {{"class", "Dmp"}, {"schema_version", 1}, {"weights", {0.1, 1.0 / 3.0, -2.718281828459045e-7, 343.52}}};
  m.skills = {{3, srp::core::SkillType::Reach, 0, 95, dmp}, {3, srp::core::SkillType::Grasp, 96, 96, {}}};
  TaskModelStore store(db);
  const int id = store.write(m);
  const auto reach = SkillDao(db).get(id, 3, srp::core::SkillType::Reach, "");
  ASSERT_TRUE(reach);
  EXPECT_EQ(reach->parameters, dmp);
  EXPECT_EQ(reach->parameters["weights"][1].get<double>(), 1.0 / 3.0);  // bit-exact
  store.replaceSkills(id, {{3, srp::core::SkillType::Move, 96, 200, {{"class", "Dmp"}}}});
  const auto skills = SkillDao(db).list(id);
  ASSERT_EQ(skills.size(), 1u);
  EXPECT_EQ(skills[0].skill, srp::core::SkillType::Move);
  // A skill for an object that was never grounded violates a foreign key: nothing changes.
  EXPECT_THROW(store.replaceSkills(id, {{9, srp::core::SkillType::Reach, 0, 1, {}}}), InvalidInputError);
  EXPECT_EQ(SkillDao(db).list(id).size(), 1u);

  // Two instances of one class: replacing the skills replaces both instances' rows.
  TaskModel two;
  two.info.name = "two instances";
  two.groundedProducts = {{3, "cuboid", {}, {}, {}, "cuboid_red"}, {3, "cuboid", {}, {}, {}, "cuboid_blue"}};
  two.skills = {{3, srp::core::SkillType::Grasp, 96, 96, {}, "cuboid_red"},
                {3, srp::core::SkillType::Grasp, 40, 40, {}, "cuboid_blue"}};
  const int twoId = store.write(two);
  store.replaceSkills(twoId, {{3, srp::core::SkillType::Grasp, 50, 50, {}, "cuboid_blue"}});
  const auto replaced = SkillDao(db).list(twoId);
  ASSERT_EQ(replaced.size(), 1u);
  EXPECT_EQ(replaced[0].instanceId, "cuboid_blue");
  EXPECT_EQ(replaced[0].startTimeId, 50);
  EXPECT_FALSE(SkillDao(db).get(twoId, 3, srp::core::SkillType::Grasp, "cuboid_red"));
}

TEST_P(Daos, DeletingATaskModelCascadesAndVersionsCount) {
  auto db = TaskDatabase::open(newDatabase("cascade"));
  TaskModelStore store(db);
  const int a = store.write(test::bulkModel("demo", 50, 2));
  const int b = store.write(test::bulkModel("demo", 30, 1));
  EXPECT_EQ(store.read(a).info.version, 1);
  EXPECT_EQ(store.read(b).info.version, 2);
  EXPECT_EQ(TaskModelDao(db).latestByName("demo")->id, b);
  store.remove(a);
  EXPECT_THROW(store.read(a), InvalidInputError);
  EXPECT_TRUE(ProductPoseDao(db).list(a).empty());
  EXPECT_TRUE(HandPositionDao(db).list(a).empty());
  EXPECT_EQ(ProductPoseDao(db).list(b).size(), 30u);
  EXPECT_THROW(store.remove(a), InvalidInputError);
}

TEST_P(Daos, DanglingReferenceRejectsTheWholeModel) {
  auto db = TaskDatabase::open(newDatabase("dangling"));
  TaskModelStore store(db);
  TaskModel m;
  m.info.name = "dangling";
  m.products = {{0, "cuboid", 5, {}, {}, {}, {}, {}}};  // source location 5 does not exist
  EXPECT_THROW(store.write(m), InvalidInputError);
  EXPECT_TRUE(store.list().empty());
}

// Names and texts are bound as parameters, never spliced into SQL: quotes,
// semicolons, dollar quoting, backslashes and SQL fragments come back verbatim.
TEST_P(Daos, HostileNamesAreStoredVerbatim) {
  auto db = TaskDatabase::open(newDatabase("hostile"));
  TaskModelStore store(db);
  const std::vector<std::string> names = {"O'Brien's \"task\"", "a; DROP TABLE TaskModels; --", "$$ $tag$ $$",
                                          "back\\slash ? ?1 $1 %s", "'); DELETE FROM Products; --", "ünïcødé ✓"};
  std::vector<int> ids;
  for (const auto& name : names) {
    TaskModel m = test::bulkModel(name, 3, 1);
    m.info.instruction = name;
    m.groundedProducts[0].objectName = name;
    m.groundedProducts[0].instanceId = name;
    for (auto& pose : m.productPoses) pose.instanceId = name;
    ids.push_back(store.write(m));
  }
  for (std::size_t i = 0; i < names.size(); ++i) {
    const TaskModel back = store.read(ids[i]);
    EXPECT_EQ(back.info.name, names[i]);
    EXPECT_EQ(back.info.instruction, names[i]);
    ASSERT_EQ(back.groundedProducts.size(), 1u);
    EXPECT_EQ(back.groundedProducts[0].objectName, names[i]);
    EXPECT_EQ(back.groundedProducts[0].instanceId, names[i]);
    EXPECT_EQ(back.productPoses.size(), 3u);
    EXPECT_EQ(TaskModelDao(db).latestByName(names[i])->id, ids[i]);
  }
  EXPECT_EQ(store.list().size(), names.size());
}
