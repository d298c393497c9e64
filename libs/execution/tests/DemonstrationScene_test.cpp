// A task runs in the scene of its own demonstration: the robot base from the
// extrinsics or the default placement, parts seen without a CAD file simulated
// as their hull / box.
#include "srp/execution/DemonstrationScene.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "srp/core/DefaultScene.h"
#include "srp/core/Json.h"
#include "srp/execution/ExecutionSession.h"
#include "srp/kb/KnowledgeBase.h"
#include "srp/taskdb/TaskModelStore.h"

using namespace srp::execution;
namespace fs = std::filesystem;

namespace {
constexpr double kPoseTol_m = 1e-9;
constexpr double kRotationTol = 1e-9;

srp::taskdb::PerceivedScene perceivedFrom(const srp::core::Scene& scene) {
  srp::taskdb::PerceivedScene p;
  p.catalogue = scene.cataloguePath;
  p.tableSize_m = scene.tableSize_m;
  p.X_table_camera = scene.X_world_camera;
  return p;
}

srp::core::ObjectClass observed(const std::string& name, int id, srp::core::ObjectKind kind) {
  srp::core::ObjectClass c;
  c.name = c.noun = name;
  c.classId = id;
  c.kind = kind;
  c.observed = true;
  if (kind == srp::core::ObjectKind::Part) {
    c.shape = "hull";
    c.dimensions_m = {0.05, 0.04, 0.035};
    c.footprint_object = {{-0.025, -0.02}, {0.025, -0.015}, {0.02, 0.02}, {-0.025, 0.02}};
    c.mass_kg = 0.04;
    c.rgb = {0.1, 0.2, 0.75};
  } else {
    c.shape = "open_box";
    c.dimensions_m = {0.26, 0.2, 0.08};
    c.wallThickness_m = 0.006;
    c.mass_kg = 0.4;
    c.rgb = {0.5, 0.5, 0.5};
  }
  return c;
}
}  // namespace

TEST(DemonstrationScene, DefaultPlacementOnTheThesisSceneIsItsRobotBase) {
  const srp::core::Scene scene = srp::core::Scene::load(srp::core::defaultScenePath());
  const RobotPlacement placement = RobotPlacement::of(perceivedFrom(scene), std::nullopt);
  EXPECT_TRUE(placement.isDefault);
  EXPECT_LT((placement.X_world_base.translation() - scene.X_world_base.translation()).norm(), kPoseTol_m)
      << placement.X_world_base.translation().transpose();
  EXPECT_LT((placement.X_world_base.linear() - scene.X_world_base.linear()).norm(), kRotationTol);
  EXPECT_NE(placement.description.find("table edge opposite the camera"), std::string::npos);
}

TEST(DemonstrationScene, ExtrinsicsPlaceTheBaseWhereTheCalibrationSays) {
  const srp::core::Scene scene = srp::core::Scene::load(srp::core::defaultScenePath());
  const RobotPlacement placement =
      RobotPlacement::of(perceivedFrom(scene), scene.X_base_camera(), "calib/extrinsics.json");
  EXPECT_FALSE(placement.isDefault);
  EXPECT_LT((placement.X_world_base.matrix() - scene.X_world_base.matrix()).norm(), kPoseTol_m);
  EXPECT_NE(placement.description.find("calib/extrinsics.json"), std::string::npos);
  // A camera to one side: the default base stands at the far edge, facing the table centre.
  srp::taskdb::PerceivedScene side = perceivedFrom(scene);
  side.X_table_camera.translation() = Eigen::Vector3d(0.9, 0.0, 0.6);
  const srp::core::Pose3 base = defaultRobotBase(side);
  EXPECT_NEAR(base.translation().x(), -(side.tableSize_m.x() / 2 - kDefaultBaseInset_m), kPoseTol_m);
  EXPECT_NEAR(base.translation().y(), 0.0, kPoseTol_m);
  EXPECT_NEAR((base.linear().col(0) - Eigen::Vector3d::UnitX()).norm(), 0.0, kRotationTol);
}

// A task model whose demonstration showed a part and a bin that no catalogue
// knows: executed without a scene file, in its own scene.
TEST(DemonstrationScene, TaskRunsInItsOwnSceneWithObservedParts) {
  const std::string folder = std::string(SRP_BINARY_DIR) + "/demonstration_scene_test";
  fs::remove_all(folder);
  fs::create_directories(folder);
  const srp::core::Scene thesis = srp::core::Scene::load(srp::core::defaultScenePath());
  srp::taskdb::TaskModel m;
  m.info.name = "toy in bin";
  m.info.intrinsics = thesis.intrinsics;
  m.products = {{0, "toy", {}, 0, {}, 0, 0, 100, ""}, {1, "bin", {}, {}, {}, 5, 0, 101, ""}};
  m.targetLocations = {{0, 1, "in"}};
  m.targetObjectIds = {0};
  m.groundedProducts = {{100, "toy", {}, 0, {}, ""}, {101, "bin", {}, {}, {}, ""}};
  srp::taskdb::PerceivedScene scene;
  scene.catalogue = thesis.cataloguePath;
  scene.tableSize_m = {0.9, 0.6};
  scene.X_table_camera = thesis.X_world_camera;
  scene.X_table_camera.translation() = Eigen::Vector3d(0.0, 0.35, 0.75);
  srp::taskdb::SceneObjectRow toy{"toy", 100, "toy", srp::core::Pose3::Identity(), std::string("blue"), std::nullopt};
  toy.X_table_object.translation() = Eigen::Vector3d(-0.15, 0.05, 0.0);
  srp::taskdb::SceneObjectRow bin{"bin", 101, "bin", srp::core::Pose3::Identity(), std::string("gray"), std::nullopt};
  bin.X_table_object.translation() = Eigen::Vector3d(0.15, 0.0, 0.0);
  scene.objects = {toy, bin};
  scene.observedClasses = {observed("toy", 100, srp::core::ObjectKind::Part),
                           observed("bin", 101, srp::core::ObjectKind::Container)};
  m.scene = scene;
  const std::string dbPath = folder + "/task.db";
  int id = 0;
  {
    auto db = srp::taskdb::TaskDatabase::open(dbPath);
    id = srp::taskdb::TaskModelStore(db).write(m);
  }
  ExecuteRequest request;
  request.databasePath = dbPath;
  request.taskModelId = id;
  request.outputFolder = folder + "/out";
  request.framePeriod = 200;  // a frame now and then: the renderer draws the hull
  const ExecuteResult result = executeTask(request);
  EXPECT_TRUE(result.report.allSucceeded()) << result.report.toText();
  EXPECT_NE(result.report.scene.find("own demonstration"), std::string::npos) << result.report.scene;
  EXPECT_NE(result.report.robotBase.find("default placement"), std::string::npos) << result.report.robotBase;
  ASSERT_EQ(result.report.steps.size(), 1u);
  EXPECT_TRUE(result.report.steps[0].insideContainer);
  EXPECT_TRUE(fs::exists(folder + "/out/frames/frame_00001.png"));
  // The scene it left carries the observed classes: the next run can start from it.
  const srp::core::Scene after = srp::core::Scene::load(folder + "/out/final_scene.json");
  EXPECT_EQ(after.observedClasses.size(), 2u);
  after.validate(srp::kb::loadCatalogue(after.cataloguePath));
}

// calib/extrinsics.json is the synthetic camera's pose in the robot base of the
// default scene (as calib/camera.xml is its intrinsics): `make demo` executes a
// task in its own perceived scene with it.
TEST(DemonstrationScene, TheSyntheticCamerasExtrinsicsFileMatchesTheDefaultScene) {
  const srp::core::Scene scene = srp::core::Scene::load(srp::core::defaultScenePath());
  const auto j = srp::core::readJsonFile(std::string(SRP_SOURCE_DIR) + "/calib/extrinsics.json");
  const srp::core::Pose3 X_base_camera = srp::core::poseFromJson(j.at("X_base_camera"), "calib/extrinsics.json");
  EXPECT_LT((X_base_camera.matrix() - scene.X_base_camera().matrix()).norm(), kPoseTol_m);
}
