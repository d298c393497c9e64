// End to end on a small synthetic demonstration: instruction + demo -> one
// task model; bad input and kills write nothing.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>
#include <fstream>
#include <iostream>

#include "srp/core/Error.h"
#include "srp/core/OutputFile.h"
#include "srp/execution/DemonstrationScene.h"
#include "srp/execution/ExecutionSession.h"
#include "srp/core/Scene.h"
#include "srp/kb/KnowledgeBase.h"
#include "srp/programming/ProgrammingPipeline.h"
#include "srp/synth/DemoGenerator.h"
#include "SmallDemoOptions.h"
#include "srp/synth/PickPlacePlan.h"
#include "srp/taskdb/TaskModelStore.h"

using namespace srp;

namespace {
constexpr int kEventTol_frames = 3;  // issue 8: grasp/release within +-3 frames of the truth
const std::string kSubset = "Pick up the cuboid from the blue box and place it in the gray box.";

std::filesystem::path workDir() {
  static const auto dir = std::filesystem::temp_directory_path() / ("srp_programming_test_" + std::to_string(getpid()));
  std::filesystem::create_directories(dir);
  return dir;
}

using programming::test::smallDemoOptions;

// One small demo (the cuboid step of instruction 1) shared by the tests; the
// octagon is taken out of the scene so an instruction can name a part it never shows.
const std::string& demoPath() {
  static const std::string path = [] {
    core::Scene scene = core::Scene::load(std::string(SRP_SIM_DIR) + "/scenes/default.json");
    scene.objects.erase(std::remove_if(scene.objects.begin(), scene.objects.end(),
                                       [](const auto& o) { return o.className == "octagon"; }),
                        scene.objects.end());
    const auto kb = kb::loadCatalogue(scene.cataloguePath);
    const synth::SynthDemoOptions opt = smallDemoOptions(7);
    const nlohmann::json plan = {{"steps",
                                  {{{"object", {{"name", "cuboid"}, {"color", nullptr}}},
                                    {"source", {{{"relation", "from"}, {"landmark", {{"name", "box"}, {"color", "blue"}}}}}},
                                    {"target", {{{"relation", "in"}, {"landmark", {{"name", "box"}, {"color", "gray"}}}}}}}}}};
    const std::string rawlog = (workDir() / "cuboid.rawlog").string();
    synth::generateSyntheticDemo(scene, kb, plan, opt, rawlog);
    return rawlog;
  }();
  return path;
}

// The same step at 640x480 (the boxes' thin walls are found at this resolution,
// not at 320x240): for the tests of the perceived scene, which holds them.
const std::string& fullSizeDemoPath() {
  static const std::string path = [] {
    const core::Scene scene = core::Scene::load(std::string(SRP_SIM_DIR) + "/scenes/default.json");
    const auto kb = kb::loadCatalogue(scene.cataloguePath);
    synth::SynthDemoOptions opt = smallDemoOptions(7);
    opt.width_px = 640;
    opt.height_px = 480;
    nlohmann::json plan = synth::defaultPlanJson();
    plan["steps"] = nlohmann::json::array({plan.at("steps").at(0)});
    const std::string rawlog = (workDir() / "cuboid_640.rawlog").string();
    synth::generateSyntheticDemo(scene, kb, plan, opt, rawlog);
    return rawlog;
  }();
  return path;
}

programming::ProgrammingOptions options(const std::string& db, const std::string& instruction = kSubset) {
  programming::ProgrammingOptions o;
  o.instruction = instruction;
  o.demoPath = demoPath();
  o.dbPath = db;
  o.name = "cuboid";
  return o;
}

std::size_t modelCount(const std::string& db) {
  auto d = taskdb::TaskDatabase::open(db);
  return taskdb::TaskModelStore(d).list().size();
}

std::string freshDb(const std::string& name) {
  const std::string p = (workDir() / (name + ".db")).string();
  for (const char* s : {"", "-wal", "-shm"}) std::filesystem::remove(p + s);
  return p;
}
}  // namespace

TEST(ProgrammingPipeline, LearnsTheCuboidStepFromTheDemo) {
  const std::string db = freshDb("ok");
  auto o = options(db);
  o.reportDir = (workDir() / "report").string();
  const programming::ProgramResult r = programming::programTask(o);
  ASSERT_EQ(r.objects.size(), 1u);
  EXPECT_EQ(r.objects[0].name, "cuboid");
  EXPECT_TRUE(r.objects[0].moved);

  const auto gt = synth::DemoGroundTruth::load(synth::groundTruthPathFor(demoPath()));
  const auto* event = gt.eventFor("cuboid");
  ASSERT_NE(event, nullptr);
  EXPECT_NEAR(r.objects[0].graspFrame, event->graspFrame, kEventTol_frames);
  EXPECT_NEAR(r.objects[0].releaseFrame, event->releaseFrame, kEventTol_frames);

  auto d = taskdb::TaskDatabase::open(db);
  const taskdb::TaskModel m = taskdb::TaskModelStore(d).read(r.taskModelId);
  EXPECT_EQ(m.info.instruction, kSubset);
  EXPECT_EQ(m.handPositions.size(), static_cast<std::size_t>(r.frames));
  EXPECT_EQ(m.skills.size(), 4u);  // Reach, Grasp, Move, Release of the cuboid
  int graspRows = 0;
  for (const auto& p : m.productPoses) graspRows += p.grasp;
  EXPECT_EQ(graspRows, 1);
  for (const auto& f : r.reportFiles) EXPECT_TRUE(std::filesystem::exists(f)) << f;
}

// Issue 8 / issue 6 on a realistic synthetic demo (default sensor noise, glove
// tag, marker hand detector): grasp and release of every object within +-3
// frames of srp::synth's ground truth. Two steps (the second object placed
// next to the first), so the second object's search starts at a release.
TEST(ProgrammingPipeline, GraspAndReleaseOfEveryObjectMatchTheGroundTruth) {
  const core::Scene scene = core::Scene::load(std::string(SRP_SIM_DIR) + "/scenes/default.json");
  const auto kb = kb::loadCatalogue(scene.cataloguePath);
  synth::SynthDemoOptions opt = smallDemoOptions(11);
  opt.demo.idleStart_s = opt.demo.idleEnd_s = 0.5;
  nlohmann::json plan = synth::defaultPlanJson();
  plan["steps"].erase(plan["steps"].begin() + 2, plan["steps"].end());  // cuboid, then the star next to it
  const std::string rawlog = (workDir() / "two_steps.rawlog").string();
  synth::generateSyntheticDemo(scene, kb, plan, opt, rawlog);
  const auto gt = synth::DemoGroundTruth::load(synth::groundTruthPathFor(rawlog));

  programming::ProgrammingOptions o;
  o.instruction = "Begin by picking up the cuboid from the blue box and placing it in the gray box. Next, carefully "
                  "lift the star and position it next to the cuboid in the gray box.";
  o.demoPath = rawlog;
  o.dbPath = freshDb("two_steps");
  o.name = "two_steps";
  const programming::ProgramResult r = programming::programTask(o);
  ASSERT_EQ(r.objects.size(), 2u);
  for (const auto& obj : r.objects) {
    const auto* event = gt.eventFor(obj.name);
    ASSERT_NE(event, nullptr) << obj.name;
    EXPECT_TRUE(obj.moved) << obj.name;
    std::cout << obj.name << ": grasp " << obj.graspFrame << " (truth " << event->graspFrame << "), release "
              << obj.releaseFrame << " (truth " << event->releaseFrame << ")\n";
    EXPECT_NEAR(obj.graspFrame, event->graspFrame, kEventTol_frames) << obj.name;
    EXPECT_NEAR(obj.releaseFrame, event->releaseFrame, kEventTol_frames) << obj.name;
  }
}

TEST(ProgrammingPipeline, BadInputWritesNothing) {
  const std::string db = freshDb("bad");
  { taskdb::TaskDatabase::open(db); }
  // No steps.
  EXPECT_THROW(programming::programTask(options(db, "The weather is nice today.")), core::InvalidInputError);
  // A part the demo never shows.
  try {
    programming::programTask(options(db, "Pick up the octagon from the blue box and place it in the gray box."));
    ADD_FAILURE() << "unseen octagon accepted";
  } catch (const core::InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("never shows"), std::string::npos) << e.what();
  }
  // A part the knowledge base does not know.
  EXPECT_THROW(programming::programTask(options(db, "Pick up the cylinder and place it in the gray box.")),
               core::InvalidInputError);
  // A bad rawlog.
  auto o = options(db);
  o.demoPath = (workDir() / "junk.rawlog").string();
  std::ofstream(o.demoPath) << "not a rawlog";
  EXPECT_THROW(programming::programTask(o), core::FileError);
  EXPECT_EQ(modelCount(db), 0u);
}

TEST(ProgrammingPipeline, KilledAtAnyStageLeavesTheDatabaseAsBefore) {
  const std::string db = freshDb("killed");
  {  // one model already there
    auto d = taskdb::TaskDatabase::open(db);
    taskdb::TaskModel m;
    m.info.name = "previous";
    taskdb::TaskModelStore(d).write(m);
  }
  for (const std::string stage : {"environment", "store"}) {
    int fd[2];
    ASSERT_EQ(pipe(fd), 0);
    const pid_t child = fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
      close(fd[0]);
      auto o = options(db);
      o.progress = [&](const std::string& s, std::size_t done, std::size_t) {
        if (s == stage && done > 0) {
          const char c = 'k';
          if (write(fd[1], &c, 1) != 1) _exit(3);
          pause();
        }
      };
      programming::programTask(o);
      _exit(2);
    }
    close(fd[1]);
    char c = 0;
    ASSERT_EQ(read(fd[0], &c, 1), 1) << "child never reached stage " << stage;
    kill(child, SIGKILL);
    int status = 0;
    waitpid(child, &status, 0);
    close(fd[0]);
    EXPECT_TRUE(WIFSIGNALED(status));
    EXPECT_EQ(modelCount(db), 1u) << "killed in stage " << stage;
  }
}

// Issue 21: a run whose report cannot be written stores nothing, whether the
// folder is unusable from the start or the report fails after the model is in.
TEST(ProgrammingPipeline, UnwritableReportStoresNothing) {
  const std::string db = freshDb("report");
  {
    auto d = taskdb::TaskDatabase::open(db);
    taskdb::TaskModel m;
    m.info.name = "previous";
    taskdb::TaskModelStore(d).write(m);
  }
  // A folder under a regular file cannot be created, even by root.
  const auto file = workDir() / "a_regular_file";
  std::ofstream(file) << "x";
  auto o = options(db);
  o.reportDir = (file / "report").string();
  bool perceptionStarted = false;
  o.progress = [&](const std::string& stage, std::size_t, std::size_t) {
    if (stage == "environment") perceptionStarted = true;
  };
  try {
    programming::programTask(o);
    ADD_FAILURE() << "a report folder under a regular file was accepted";
  } catch (const core::FileError& e) {
    EXPECT_NE(std::string(e.what()).find("report folder"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(perceptionStarted) << "the report folder must be checked before the demonstration is read";
  EXPECT_EQ(modelCount(db), 1u);

  // The folder is fine but writing the report fails (as on a full disk) once
  // every row is written: the model is rolled back and no report folder is left.
  const auto dir = workDir() / "report_failed";
  std::filesystem::remove_all(dir);
  o = options(db);
  o.reportDir = dir.string();
  o.progress = [](const std::string& stage, std::size_t, std::size_t) {
    if (stage == "store") core::injectOutputWriteFailureAfter(0);
  };
  EXPECT_THROW(programming::programTask(o), core::FileError);
  core::injectOutputWriteFailureAfter(-1);
  EXPECT_EQ(modelCount(db), 1u);
  EXPECT_FALSE(std::filesystem::exists(dir)) << "a failed run leaves no report folder";

  // And with a usable folder the same run stores exactly one model.
  o.progress = nullptr;
  o.reportDir = (workDir() / "report_ok").string();
  const auto r = programming::programTask(o);
  EXPECT_EQ(modelCount(db), 2u);
  EXPECT_EQ(r.version, 1);
  EXPECT_TRUE(std::filesystem::exists(workDir() / "report_ok" / "summary.md"));
}

// Issue 21: a damaged demonstration fails the run (nothing stored) unless the
// caller allows the frames before the damage.
TEST(ProgrammingPipeline, DamagedDemonstrationStoresNothingUnlessAllowed) {
  const std::string db = freshDb("damaged");
  const std::string cut = (workDir() / "cut.rawlog").string();
  std::filesystem::copy_file(demoPath(), cut, std::filesystem::copy_options::overwrite_existing);
  std::filesystem::resize_file(cut, std::filesystem::file_size(cut) * 97 / 100);
  auto o = options(db);
  o.demoPath = cut;
  try {
    programming::programTask(o);
    ADD_FAILURE() << "a truncated demonstration was programmed";
  } catch (const core::FileError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("damaged after frame"), std::string::npos) << what;
    EXPECT_NE(what.find("nothing was stored"), std::string::npos) << what;
  }
  EXPECT_EQ(modelCount(db), 0u);
  o.allowTruncated = true;
  const auto r = programming::programTask(o);
  EXPECT_EQ(modelCount(db), 1u);
  EXPECT_TRUE(std::any_of(r.warnings.begin(), r.warnings.end(),
                          [](const std::string& w) { return w.find("--allow-truncated") != std::string::npos; }))
      << "no warning names the truncation";
}

// The scene the demonstration showed is stored with the task model: every
// object where the demonstration began, the table plane and the camera, as the
// synthetic demo's ground truth has them (compared in the camera frame, which
// both share).
TEST(ProgrammingPipeline, StoresThePerceivedSceneOfTheDemonstration) {
  constexpr double kPosTol_m = 5e-3;     // detections on a 320x240 demo with sensor noise
  constexpr double kYawTol_rad = 3.0 * M_PI / 180.0;
  constexpr double kNormalTol_rad = 1.0 * M_PI / 180.0;
  constexpr double kHeightTol_m = 5e-3;
  const std::string db = freshDb("scene");
  auto o = options(db);
  o.demoPath = fullSizeDemoPath();
  o.reportDir = (workDir() / "report_scene").string();
  const programming::ProgramResult r = programming::programTask(o);
  EXPECT_TRUE(r.sceneStored);
  auto d = taskdb::TaskDatabase::open(db);
  const taskdb::TaskModel m = taskdb::TaskModelStore(d).read(r.taskModelId);
  ASSERT_TRUE(m.scene.has_value());
  const auto gt = synth::DemoGroundTruth::load(synth::groundTruthPathFor(fullSizeDemoPath()));
  const core::Pose3 X_camera_table = m.scene->X_table_camera.inverse();
  const core::Pose3 X_camera_world = gt.X_world_camera.inverse();
  // The table plane: its normal and the camera's height above it.
  const double normalAngle = std::acos(std::clamp(X_camera_table.linear().col(2).dot(X_camera_world.linear().col(2)), -1.0, 1.0));
  const double heightError_m = m.scene->X_table_camera.translation().z() - gt.X_world_camera.translation().z();
  std::cout << "table normal " << normalAngle * 180 / M_PI << " deg off, camera height " << 1e3 * heightError_m
            << " mm off\n";
  EXPECT_LT(normalAngle, kNormalTol_rad);
  EXPECT_LT(std::abs(heightError_m), kHeightTol_m);
  std::set<std::string> seen;
  for (const auto& obj : m.scene->objects) {
    const auto truth = std::find_if(gt.objects.begin(), gt.objects.end(), [&](const auto& t) { return t.className == obj.className; });
    ASSERT_NE(truth, gt.objects.end()) << obj.objectId;
    const core::Pose3 perceived = X_camera_table * obj.X_table_object;
    const core::Pose3 expected = X_camera_world * truth->X_world_object_initial;
    const double dp = (perceived.translation() - expected.translation()).norm();
    // Yaw about the table normal, modulo the half turn every shape here repeats under.
    const Eigen::Vector3d a = perceived.linear().col(0), b = expected.linear().col(0);
    const double yaw = std::acos(std::clamp(std::abs(a.dot(b)), 0.0, 1.0));
    std::cout << obj.objectId << ": " << 1e3 * dp << " mm, " << yaw * 180 / M_PI << " deg\n";
    EXPECT_LT(dp, kPosTol_m) << obj.objectId;
    EXPECT_LT(yaw, kYawTol_rad) << obj.objectId;
    EXPECT_GE(obj.X_table_object.translation().z(), 0.0) << obj.objectId;
    seen.insert(obj.className);
  }
  EXPECT_EQ(seen, (std::set<std::string>{"cuboid", "blue box", "gray box"}));
  // The report holds the scene as a scene file and the contact sheet.
  const auto kb = kb::loadCatalogue(core::ObjectCatalogue::defaultPath());
  const core::Scene file = core::Scene::load(o.reportDir + "/scene.json");
  file.validate(kb);
  EXPECT_EQ(file.objects.size(), m.scene->objects.size());
  EXPECT_TRUE(std::filesystem::exists(o.reportDir + "/contact_sheet.png"));
}

// `srp execute --db F --task N` without a scene runs the task in the scene of
// its own demonstration: the default robot placement, or the extrinsics.
TEST(ProgrammingPipeline, TheTaskRunsInTheSceneOfItsOwnDemonstration) {
  constexpr double kBaseOnTableTol_m = 5e-3;  // the calibrated base stands on the perceived table top
  const auto gt = synth::DemoGroundTruth::load(synth::groundTruthPathFor(fullSizeDemoPath()));
  for (const bool calibrated : {false, true}) {
    const std::string db = freshDb(calibrated ? "own_scene_calibrated" : "own_scene");
    auto o = options(db);
    o.demoPath = fullSizeDemoPath();
    if (calibrated) o.X_base_camera = gt.X_base_camera();
    const programming::ProgramResult r = programming::programTask(o);
    execution::ExecuteRequest request;
    request.databasePath = db;
    request.taskModelId = r.taskModelId;
    request.framePeriod = 0;
    const execution::ExecuteResult done = execution::executeTask(request);
    EXPECT_TRUE(done.report.allSucceeded()) << done.report.toText();
    EXPECT_NE(done.report.robotBase.find(calibrated ? "calibration" : "default placement"), std::string::npos)
        << done.report.robotBase;
    if (calibrated) {
      auto d = taskdb::TaskDatabase::open(db);
      const taskdb::TaskModel m = taskdb::TaskModelStore(d).read(r.taskModelId);
      const auto placement = execution::RobotPlacement::of(*m.scene, m.info.X_base_camera);
      EXPECT_NEAR(placement.X_world_base.translation().z(), gt.X_world_base.translation().z(), kBaseOnTableTol_m);
    }
  }
}

// Honest results: a step the demonstration does not show (the parallelogram never moves
// in the cuboid's demo) stores nothing, names the step, and creates neither a
// database nor a report folder; --allow-partial stores it and says what is missing.
TEST(ProgrammingPipeline, AStepWithoutGraspOrReleaseStoresNothingUnlessPartialIsAllowed) {
  const std::string db = freshDb("no_grasp");
  const auto report = workDir() / "report_no_grasp";
  std::filesystem::remove_all(report);
  auto o = options(db, "Pick up the parallelogram and place it in the gray box.");
  o.reportDir = report.string();
  try {
    programming::programTask(o);
    ADD_FAILURE() << "a step without a grasp was stored";
  } catch (const core::InvalidInputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("step 1 (parallelogram"), std::string::npos) << what;
    EXPECT_NE(what.find("never leaves its place"), std::string::npos) << what;
    EXPECT_NE(what.find("nothing was stored"), std::string::npos) << what;
  }
  EXPECT_FALSE(std::filesystem::exists(db)) << "no empty database left behind";
  EXPECT_FALSE(std::filesystem::exists(report)) << "no report folder left behind";
  o.allowPartial = true;
  const programming::ProgramResult r = programming::programTask(o);
  ASSERT_EQ(r.problems.size(), 1u);
  EXPECT_NE(r.problems[0].find("step 1"), std::string::npos);
  EXPECT_EQ(modelCount(db), 1u);
  EXPECT_TRUE(std::filesystem::exists(report / "summary.md"));
}
