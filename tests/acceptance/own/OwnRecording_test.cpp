// A user's own recording, end to end on real data the project did not make:
// HRT1 task2 and task3 (datasets/real/hrt1-pick-place, MIT, credits in its
// README; task 1 is held out for review) imported as `srp import DIR x.rawlog
// --fps 10` does and programmed as `srp program -i ... --demo x.rawlog --db
// t.db` does (programTask with the command's defaults: hand auto, the default
// catalogue, which knows neither a toy nor a bin). The toy and the bin are
// found in the demonstration; the stored task model is scored against our
// event labels (event_labels.json, labelled by looking at the frames) and
// against where the toy ends: inside the bin's footprint; the stored task is then
// executed as `srp execute --db t.db --task 1` does (no --scene: the perceived scene),
// the step done and "in bin" holding. The real hand-held
// cube recording (datasets/real/visp-rbt-cube) with default flags: the camera
// motion is noticed and the cube detected in every frame. Slow label: five
// recordings perceived (~5-10 s each).
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <string>

#include "srp/calib/RgbdImporter.h"
#include "srp/core/ExitCode.h"
#include "srp/core/Json.h"
#include "srp/execution/ExecutionSession.h"
#include "srp/kb/KnowledgeBase.h"
#include "srp/perception/RawlogPerception.h"
#include "srp/programming/ProgrammingPipeline.h"
#include "srp/taskdb/TaskDatabase.h"
#include "srp/taskdb/TaskModelStore.h"

namespace srp {
namespace {

// Issue 30: grasp and release within 2 frames of the labels at 10 Hz.
constexpr int kEventTol_frames = 2;
constexpr double kInsideMargin_m = 0.0;  // the toy's centre strictly inside the bin's footprint
// srp execute: the toy within 1 cm of its planned pose in the bin (the executor's own
// "placed as planned" tolerance, TaskExecutor::Options::placementTolerance_m).
constexpr double kExecutedPlacementTol_m = 0.01;

std::string hrt1Root() { return std::string(SRP_DATASETS_DIR) + "/real/hrt1-pick-place"; }

std::filesystem::path workDir() {
  const auto dir = std::filesystem::path(SRP_BINARY_DIR) / "acceptance_own_recording";
  std::filesystem::create_directories(dir);
  return dir;
}

std::string importTask(const std::string& task) {
  const std::string rawlog = (workDir() / (task + ".rawlog")).string();
  if (!std::filesystem::exists(rawlog)) {
    calib::ImportOptions io;
    io.fps = 10.0;
    calib::importImageFolder(hrt1Root() + "/" + task, rawlog, io);
  }
  return rawlog;
}

void programAndScore(const std::string& task, const std::string& instruction, const std::string& tag) {
  programming::ProgrammingOptions o;
  o.instruction = instruction;
  o.demoPath = importTask(task);
  o.dbPath = (workDir() / (task + "_" + tag + ".db")).string();
  std::filesystem::remove(o.dbPath);
  const programming::ProgramResult r = programming::programTask(o);

  ASSERT_EQ(r.planLines.size(), 1u) << task << ": one step (toy -> bin)";
  ASSERT_EQ(r.objects.size(), 1u);
  const auto& toy = r.objects.front();
  EXPECT_EQ(toy.name, "toy");
  ASSERT_TRUE(toy.moved) << toy.note;
  const auto labels = core::readJsonFile(hrt1Root() + "/event_labels.json").at("tasks").at(task);
  const int graspLabel = labels.at("grasp_frame"), releaseLabel = labels.at("release_frame");
  std::printf("[ figures  ] HRT1 %s, '%s': grasp %d (label %d), release %d (label %d), camera %s\n", task.c_str(),
              instruction.c_str(), toy.graspFrame, graspLabel, toy.releaseFrame, releaseLabel,
              r.cameraMoved ? "moved" : "fixed");
  EXPECT_LE(std::abs(toy.graspFrame - graspLabel), kEventTol_frames) << task;
  EXPECT_LE(std::abs(toy.releaseFrame - releaseLabel), kEventTol_frames) << task;

  // The stored model: the toy's last pose inside the bin's footprint (both in the model's frame).
  ASSERT_EQ(r.observedClasses.size(), 2u);
  const core::ObjectClass* bin = nullptr;
  for (const auto& c : r.observedClasses)
    if (c.name == "bin") bin = &c;
  ASSERT_NE(bin, nullptr);
  EXPECT_EQ(bin->kind, core::ObjectKind::Container);
  auto db = taskdb::TaskDatabase::open(o.dbPath, taskdb::TaskDatabase::Mode::ReadOnly);
  const taskdb::TaskModel model = taskdb::TaskModelStore(db).read(r.taskModelId);
  const taskdb::ProductPoseRow *toyLast = nullptr, *binRow = nullptr;
  for (const auto& p : model.productPoses) {
    if (p.classId == toy.classId && p.detected && (!toyLast || p.timeId > toyLast->timeId)) toyLast = &p;
    if (p.classId == bin->classId && p.detected && !binRow) binRow = &p;
  }
  ASSERT_NE(toyLast, nullptr);
  ASSERT_NE(binRow, nullptr);
  const core::Pose3 X_frame_bin = core::makePose(binRow->p_m, binRow->q);
  const Eigen::Vector3d p_bin_toy = X_frame_bin.inverse() * toyLast->p_m;
  std::printf("[ figures  ] HRT1 %s: toy's last pose in the bin's frame (%.3f, %.3f) m, bin %.3f x %.3f m\n",
              task.c_str(), p_bin_toy.x(), p_bin_toy.y(), bin->dimensions_m.x(), bin->dimensions_m.y());
  EXPECT_LT(std::abs(p_bin_toy.x()), bin->dimensions_m.x() / 2 - kInsideMargin_m) << task;
  EXPECT_LT(std::abs(p_bin_toy.y()), bin->dimensions_m.y() / 2 - kInsideMargin_m) << task;

  // srp execute --db t.db --task 1, no --scene: the perceived scene, the robot at its default placement.
  execution::ExecuteRequest request;
  request.databasePath = o.dbPath;
  request.taskModelId = r.taskModelId;
  request.framePeriod = 0;
  const execution::ExecuteResult executed = execution::executeTask(request);
  ASSERT_EQ(executed.report.steps.size(), 1u);
  const auto& step = executed.report.steps.front();
  std::printf("[ figures  ] HRT1 %s, '%s': srp execute %s, %.2f mm from plan, relations %s (%s)\n", task.c_str(),
              instruction.c_str(), execution::toString(step.status).c_str(), 1000 * step.placementError_m,
              step.relationsHold ? "hold" : "NOT MET", step.reason.c_str());
  EXPECT_EQ(executed.report.exitCode(), core::ExitCode::Done) << task << ": " << step.reason;
  EXPECT_TRUE(step.relationsHold) << task << ": " << step.reason;
  EXPECT_LE(step.placementError_m, kExecutedPlacementTol_m) << task;
}

TEST(OwnRecording, Hrt1ToyIntoBinFoundAndProgrammed) {
  for (const std::string task : {"task2", "task3"}) {
    programAndScore(task, "Pick up the toy and put it in the bin.", "toy_bin");
    programAndScore(task, "Put the blue toy in the grey bin.", "blue_toy_grey_bin");
  }
}

TEST(OwnRecording, Hrt1ToyOfAnotherColourIsRefusedAndNothingStored) {
  programming::ProgrammingOptions o;
  o.instruction = "Put the red toy in the bin.";
  o.demoPath = importTask("task2");
  o.dbPath = (workDir() / "task2_red.db").string();
  std::filesystem::remove(o.dbPath);
  try {
    programming::programTask(o);
    FAIL() << "a red toy was found in a recording whose only moved part is blue";
  } catch (const std::exception& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("red"), std::string::npos) << what;
    EXPECT_NE(what.find("blue"), std::string::npos) << what << ": the message names what was moved";
  }
  if (std::filesystem::exists(o.dbPath)) {
    auto db = taskdb::TaskDatabase::open(o.dbPath, taskdb::TaskDatabase::Mode::ReadOnly);
    EXPECT_TRUE(taskdb::TaskModelStore(db).list().empty()) << "a refused run stored a task model";
  }
}

TEST(OwnRecording, HandHeldCubeCameraMotionNoticedWithDefaultFlags) {
  const std::string rawlog = (workDir() / "cube.rawlog").string();
  if (!std::filesystem::exists(rawlog))
    calib::importImageFolder(std::string(SRP_DATASETS_DIR) + "/real/visp-rbt-cube", rawlog, calib::ImportOptions{});
  const auto catalogue = kb::loadCatalogue(std::string(SRP_DATASETS_DIR) + "/real/visp-rbt-cube/catalogue.json");
  perception::PerceptionOptions options;  // srp perceive's defaults but for --hand none --objects cube
  options.hand = perception::PerceptionOptions::HandMethod::None;
  options.plan.push_back({"cube", false, "", std::nullopt});
  const perception::PerceptionResult r = perception::perceiveRawlog(rawlog, catalogue, options);
  ASSERT_EQ(r.objects.size(), 1u);
  std::printf("[ figures  ] visp-rbt-cube, default flags: cube detected in %d/%d frames, camera moved %d (from "
              "frame %d, %.1f cm, %.1f deg)\n",
              r.objects[0].detectedFrames(), r.frames, r.cameraMoved, r.cameraMovedAtFrame, 100 * r.cameraTravel_m,
              r.cameraTurn_rad * 180 / M_PI);
  EXPECT_TRUE(r.cameraMoved);
  EXPECT_EQ(r.objects[0].detectedFrames(), r.frames);
  EXPECT_EQ(r.frames, 50);
}

}  // namespace
}  // namespace srp
