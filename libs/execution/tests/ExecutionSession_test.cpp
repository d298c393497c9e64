#include "srp/execution/ExecutionSession.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "srp/core/Error.h"
#include "srp/core/Json.h"
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
}  // namespace

TEST(ExecutionSession, RunsTheAppendixCTaskModelEndToEndWithoutChangingTheDatabase) {
  const std::string folder = std::string(SRP_BINARY_DIR) + "/execution_session_test";
  fs::remove_all(folder);
  fs::create_directories(folder);
  const std::string dbPath = folder + "/task.db";
  int id = 0;
  {
    auto db = srp::taskdb::TaskDatabase::open(dbPath);
    srp::taskdb::TaskModelStore store(db);
    const auto j = srp::core::readJsonFile(std::string(SRP_DATASETS_DIR) + "/examples/appendix_c_instruction1.json");
    id = store.write(srp::taskdb::taskModelFromJson(j, "appendix C"));
  }
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
