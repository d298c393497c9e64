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
