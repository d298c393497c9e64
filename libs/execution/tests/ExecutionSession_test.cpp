#include "srp/execution/ExecutionSession.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "srp/core/Error.h"
#include "srp/core/Json.h"
#include "srp/execution/PlacementPlanner.h"
#include "srp/taskdb/TaskModelStore.h"

using namespace srp::execution;
namespace fs = std::filesystem;

namespace {
std::string fileBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// A new database at `dbPath` holding the Appendix C task model; returns its id.
int importAppendixC(const std::string& dbPath) {
  auto db = srp::taskdb::TaskDatabase::open(dbPath);
  srp::taskdb::TaskModelStore store(db);
  const auto j = srp::core::readJsonFile(std::string(SRP_DATASETS_DIR) + "/examples/appendix_c_instruction1.json");
  return store.write(srp::taskdb::taskModelFromJson(j, "appendix C"));
}
}  // namespace

TEST(ExecutionSession, RunsTheAppendixCTaskModelEndToEndWithoutChangingTheDatabase) {
  const std::string folder = std::string(SRP_BINARY_DIR) + "/execution_session_test";
  fs::remove_all(folder);
  fs::create_directories(folder);
  const std::string dbPath = folder + "/task.db";
  const int id = importAppendixC(dbPath);
  const std::string before = fileBytes(dbPath);

  ExecuteRequest request;
  request.databasePath = dbPath;
  request.taskModelId = id;
  request.outputFolder = folder + "/out";
  request.framePeriod = 100;  // a few frames: every 2 s
  const ExecuteResult result = executeTask(request);
  EXPECT_EQ(result.plan.steps.size(), 4u);
  EXPECT_TRUE(result.report.allSucceeded()) << result.report.toText();
  for (const char* f : {"/out/report.json", "/out/report.txt", "/out/joints.csv", "/out/frames/frame_00001.png"})
    EXPECT_TRUE(fs::exists(folder + f)) << f;
  const auto report = srp::core::readJsonFile(folder + "/out/report.json");
  EXPECT_EQ(report["steps"].size(), 4u);
  EXPECT_EQ(report["task_model_id"], id);

  request.taskModelId = id + 41;
  EXPECT_THROW(executeTask(request), srp::core::Error);
  request.databasePath = folder + "/missing.db";
  EXPECT_THROW(executeTask(request), srp::core::FileError);
  EXPECT_EQ(fileBytes(dbPath), before) << "executing must not change the task database";
}

TEST(ExecutionSession, FinalSceneLetsAReversalRunFromWhereThePreviousRunLeft) {
  const std::string folder = std::string(SRP_BINARY_DIR) + "/execution_final_scene_test";
  fs::remove_all(folder);
  fs::create_directories(folder);
  const std::string dbPath = folder + "/task.db";
  const int id = importAppendixC(dbPath);
  ExecuteRequest first;
  first.databasePath = dbPath;
  first.taskModelId = id;
  first.outputFolder = folder + "/first";
  first.framePeriod = 0;
  first.instruction = "Pick up the cuboid from the blue box and place it in the gray box.";
  const ExecuteResult a = executeTask(first);
  ASSERT_TRUE(a.report.allSucceeded()) << a.report.toText();
  EXPECT_EQ(a.report.steps[0].pathSource, "minimum-jerk") << "Appendix C has no learned skills";
  const std::string finalScene = folder + "/first/final_scene.json";
  ASSERT_TRUE(fs::exists(finalScene));
  const CellDescription after = CellDescription::loadScene(finalScene);
  ASSERT_NE(after.find("cuboid"), nullptr);
  EXPECT_TRUE(isInside(*after.find("cuboid"), *after.find("gray box")));
  EXPECT_LT((after.find("cuboid")->X_world_object.translation() - a.report.steps[0].X_world_final->translation()).norm(),
            1e-9);

  ExecuteRequest back = first;
  back.scenePath = finalScene;
  back.outputFolder = folder + "/back";
  back.instruction = "Move the cuboid from the gray box back to the blue box.";
  const ExecuteResult b = executeTask(back);
  ASSERT_EQ(b.report.steps.size(), 1u);
  EXPECT_TRUE(b.report.allSucceeded()) << b.report.toText();
  const CellDescription restored = CellDescription::loadScene(back.outputFolder + "/final_scene.json");
  EXPECT_TRUE(isInside(*restored.find("cuboid"), *restored.find("blue box")));
}

// `srp execute` loads the scene's catalogue through kb::loadCatalogue, so a part given by its
// CAD file alone (no shape, size or mass in the catalogue) is measured from its mesh and handled
// like the shipped classes: here the cuboid, described only by the shipped cuboid.stl.
TEST(ExecutionSession, HandlesAPartGivenByItsMeshAlone) {
  constexpr double kSizeTol_m = 1e-4;  // the mesh's bounding box against the catalogue's size
  const std::string folder = std::string(SRP_BINARY_DIR) + "/execution_mesh_only_test";
  fs::remove_all(folder);
  fs::create_directories(folder);
  auto catalogue = srp::core::readJsonFile(std::string(SRP_DATASETS_DIR) + "/kb/catalogue.json");
  Eigen::Vector3d shippedSize_m = Eigen::Vector3d::Zero();
  for (auto& c : catalogue["classes"]) {
    c["mesh"] = std::string(SRP_DATASETS_DIR) + "/kb/" + c["mesh"].get<std::string>();
    if (c["name"] != "cuboid") continue;
    for (int i = 0; i < 3; ++i) shippedSize_m[i] = c["dimensions_m"][i].get<double>();
    c.erase("shape");
    c.erase("dimensions_m");
    c.erase("mass_kg");
  }
  ASSERT_GT(shippedSize_m.minCoeff(), 0.0);
  std::ofstream(folder + "/catalogue.json") << catalogue.dump(1);
  auto scene = srp::core::readJsonFile(std::string(SRP_SOURCE_DIR) + "/sim/scenes/default.json");
  scene["catalogue"] = folder + "/catalogue.json";
  std::ofstream(folder + "/scene.json") << scene.dump(1);

  ExecuteRequest request;
  request.databasePath = folder + "/task.db";
  request.taskModelId = importAppendixC(request.databasePath);
  request.scenePath = folder + "/scene.json";
  request.outputFolder = folder + "/out";
  request.framePeriod = 0;
  request.instruction = "Pick up the cuboid from the blue box and place it in the gray box.";
  const ExecuteResult result = executeTask(request);
  ASSERT_EQ(result.report.steps.size(), 1u);
  EXPECT_TRUE(result.report.allSucceeded()) << result.report.toText();
  const CellDescription after = CellDescription::loadScene(folder + "/out/final_scene.json");
  ASSERT_NE(after.find("cuboid"), nullptr);
  EXPECT_TRUE(isInside(*after.find("cuboid"), *after.find("gray box")));
  const Eigen::Vector3d measured_m = after.find("cuboid")->size_m;
  EXPECT_LT((measured_m - shippedSize_m).cwiseAbs().maxCoeff(), kSizeTol_m)
      << "measured " << measured_m.transpose() << ", shipped " << shippedSize_m.transpose();
}
