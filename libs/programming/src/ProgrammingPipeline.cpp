#include "srp/kb/KnowledgeBase.h"
#include "srp/programming/ProgrammingPipeline.h"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "srp/core/Error.h"
#include "srp/core/Json.h"
#include "srp/core/OutputFile.h"
#include "srp/execution/DemonstrationScene.h"
#include "srp/core/ObjectCatalogue.h"
#include "srp/core/OutputFile.h"
#include "srp/core/SafeText.h"
#include "srp/motion/SkillPlots.h"
#include "srp/perception/DemoPerception.h"
#include "srp/programming/ProgramReport.h"
#include "srp/programming/ProgrammingStages.h"
#include "srp/taskdb/TaskModelStore.h"

namespace srp::programming {

using core::InvalidInputError;

namespace {

class StageClock {
 public:
  explicit StageClock(ProgramResult& r) : result_(r) {}
  void start(std::string stage) {
    stop();
    stage_ = std::move(stage);
    t0_ = std::chrono::steady_clock::now();
  }
  void stop() {
    if (stage_.empty()) return;
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0_).count();
    result_.timings.push_back({stage_, s});
    stage_.clear();
  }

 private:
  ProgramResult& result_;
  std::string stage_;
  std::chrono::steady_clock::time_point t0_;
};

}  // namespace

namespace {
// The database is checked before minutes of perception, but a new file is not
// created before there is a task model to store: an existing file is opened
// (checked, and migrated to this build's schema); for a new one the folder
// must exist and be writable.
void checkDatabase(const std::string& path) {
  namespace fs = std::filesystem;
  if (taskdb::TaskDatabase::isServerUri(path) || fs::exists(path)) {
    taskdb::TaskDatabase::open(path);
    return;
  }
  const fs::path folder = fs::absolute(path).parent_path();
  if (!fs::is_directory(folder))
    throw core::FileError(path, "the task database's folder does not exist; create it or give another --db");
  if (::access(folder.c_str(), W_OK) != 0)
    throw core::FileError(path, "cannot create the task database here (the folder is not writable); give another --db");
}

// A database file this run created and left without any task model (the write
// failed) is removed with its WAL files, so a failed run leaves no empty database.
void removeIfCreatedEmpty(const std::string& path) {
  namespace fs = std::filesystem;
  try {
    auto db = taskdb::TaskDatabase::open(path);
    if (!taskdb::TaskModelStore(db).list().empty()) return;
  } catch (const std::exception&) {
    // unreadable: it is ours and broken
  }
  std::error_code ec;
  for (const char* suffix : {"", "-wal", "-shm", "-journal"}) fs::remove(path + suffix, ec);
}

// The files a report folder holds: an existing report folder (srp program -o) holding anything
// else is not replaced (core::checkFolderHoldsOnly).
const std::vector<std::string> kReportFiles = {"hand_trajectory.png", "summary.md", "contact_sheet.png",
                                               "scene.json", "*_skills.png"};

// The report folder, built aside and renamed into place with the model
// (core::AtomicOutputFolder); its parent is created here, before anything runs.
std::unique_ptr<core::AtomicOutputFolder> startReportFolder(const std::string& dir) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path target = fs::absolute(dir).lexically_normal();
  const fs::path parent = (target.has_filename() ? target : target.parent_path()).parent_path();
  fs::create_directories(parent, ec);
  if (ec || !fs::is_directory(parent))
    throw core::FileError(dir, "cannot create the report folder (" + (ec ? ec.message() : std::string("not a folder")) +
                                   "); nothing was stored. Give a writable folder with --report");
  if (fs::exists(target) && !fs::is_directory(target))
    throw core::FileError(dir, "cannot create the report folder (a file of that name is in the way); nothing was "
                               "stored. Give a writable folder with --report");
  core::checkFolderHoldsOnly(target, kReportFiles, "--out");
  try {
    return std::make_unique<core::AtomicOutputFolder>(target.has_filename() ? target : target.parent_path());
  } catch (const core::FileError& e) {
    throw core::FileError(dir, std::string("cannot create the report folder (") + e.what() +
                                   "); nothing was stored. Give a writable folder with --report");
  }
}

/// What perception found, in the result: frames, the hand, the camera's motion, the discovered classes.
void reportPerception(const perception::PerceptionResult& seen, ProgramResult& result) {
  result.frames = seen.frames;
  result.handDetectedFrames = seen.handDetected;
  result.handDetector = seen.handMethod == perception::PerceptionOptions::HandMethod::MarkerFree ? "marker-free" : "marker";
  result.cameraMoved = seen.cameraMoved;
  result.cameraTravel_m = seen.cameraTravel_m;
  result.cameraTurn_rad = seen.cameraTurn_rad;
  result.observedClasses = seen.observedClasses;
  result.discoveryNotes = seen.discoveryNotes;
}

/// What the segmentation and the learned skills say of each tracked object (ProgramResult::objects).
std::vector<ObjectOutcome> objectOutcomes(const motion::Segmentation& segmentation, const perception::PerceptionResult& seen,
                                          const std::vector<motion::SkillSet>& skills, const core::ObjectCatalogue& runKb) {
  std::vector<ObjectOutcome> outcomes;
  for (const auto& seg : segmentation.objects) {
    ObjectOutcome out;
    out.name = seg.name;
    out.classId = runKb.find(seg.name) ? runKb.find(seg.name)->classId : -1;
    out.moved = seg.moved;
    out.graspFrame = seg.graspFrame;
    out.releaseFrame = seg.releaseFrame;
    out.note = seg.note;
    for (const auto& t : seen.objects)
      if (t.key() == seg.name) {  // seg.name: the perception key (class, or instance id)
        out.detectedFrames = t.detectedFrames();
        out.name = t.className;
        out.instanceId = t.instanceId;
        out.classId = t.classId;
      }
    for (const auto& s : skills)
      if (s.objectName == seg.name) {
        if (s.reach) out.reachLambda = s.reach->lambda();
        if (s.move) out.moveLambda = s.move->lambda();
      }
    outcomes.push_back(out);
  }
  return outcomes;
}

/// The scene file of the demonstration (robot base placed, the perceived scene's objects) for
/// `srp execute --scene`; none without a perceived scene. `robotBase` is told where the base went.
std::optional<core::Scene> sceneFileOf(const taskdb::TaskModel& model, const ProgrammingOptions& o,
                                       const perception::PerceptionResult& seen, std::string& robotBase) {
  if (!model.scene) return std::nullopt;
  const auto placement = execution::RobotPlacement::of(*model.scene, o.X_base_camera, o.extrinsicsSource);
  robotBase = placement.description;
  core::Scene base;
  // The scene file is read back by `srp execute --scene`, which takes only safe names.
  base.name = "demonstration " + o.name;
  if (!core::isSafeName(base.name)) base.name = "demonstration";
  base.intrinsics = seen.intrinsics;
  base.fps = model.info.frameRate_hz;
  return execution::demonstrationScene(*model.scene, placement, base);
}

/// 6. One transaction. The report is written inside it, before COMMIT: a
/// report that cannot be written rolls the model back (all or nothing), and
/// its folder is renamed into place last.
void storeTaskModel(const taskdb::TaskModel& model, const ProgrammingOptions& o, ProgramResult& result, StageClock& clock,
                    core::AtomicOutputFolder* report, const std::optional<core::Scene>& sceneFile,
                    const perception::PerceptionResult& seen, const motion::Segmentation& segmentation,
                    const std::vector<motion::SkillSet>& skills) {
  const bool newDatabase = !taskdb::TaskDatabase::isServerUri(o.dbPath) && !std::filesystem::exists(o.dbPath);
  bool reportCommitted = false;
  try {
    auto db = taskdb::TaskDatabase::open(o.dbPath);
    taskdb::TaskModelStore store(db);
    result.name = o.name;
    result.taskModelId = store.write(
        model, [&](std::size_t done, std::size_t total) {
          if (o.progress) o.progress("store", done, total);
        },
        [&](int id, int version) {
          result.taskModelId = id;
          result.version = version;
          clock.stop();
          if (!report) return;
          const std::string tmp = report->temporaryPath().string();
          std::vector<std::string> files = result.reportFiles;
          if (sceneFile) {
            core::writeJsonFile(tmp + "/scene.json", sceneFile->toJson());
            files.push_back(tmp + "/scene.json");
          }
          ProgramResult shown = result;
          shown.reportFiles = files;
          for (const auto& f : writeProgramReport(tmp, shown, seen, segmentation, skills)) files.push_back(f);
          report->commit();
          reportCommitted = true;
          result.reportFiles.clear();
          for (const auto& f : files)
            result.reportFiles.push_back((report->target() / std::filesystem::path(f).filename()).string());
        });
  } catch (...) {
    std::error_code ec;
    if (reportCommitted) std::filesystem::remove_all(report->target(), ec);  // COMMIT failed after the rename
    if (newDatabase) removeIfCreatedEmpty(o.dbPath);
    throw;
  }
}

double peakResidentMemory_MB() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss / 1024.0;  // Linux reports kilobytes
}
}  // namespace

ProgramResult programTask(const ProgrammingOptions& o) {
  ProgramResult result;
  StageClock clock(result);
  const auto progress = [&](const std::string& stage, std::size_t done, std::size_t total) {
    if (o.progress) o.progress(stage, done, total);
  };
  core::requireSafeName(o.name, "task model name (--name)");
  if (o.demoPath.empty()) throw InvalidInputError("no demonstration given (--demo demo.rawlog)");
  // Check the database and the report folder first: a bad file fails
  // before minutes of perception.
  checkDatabase(o.dbPath);
  std::unique_ptr<core::AtomicOutputFolder> report;
  if (!o.reportDir.empty()) report = startReportFolder(o.reportDir);

  // 1. Language, 2. grounding (once; from here on an object is its class name).
  clock.start("language");
  progress("language", 0, 1);
  const language::TaskPlan plan = parsePlan(o.instruction);
  const core::ObjectCatalogue kb =
      kb::loadCatalogue(o.cataloguePath.empty() ? core::ObjectCatalogue::defaultPath() : o.cataloguePath);
  GroundedPlan grounded = groundPlan(plan, kb);
  // The instances: the scene file's, else those the instruction's colour words name.
  const std::optional<core::Scene> scene =
      o.scenePath.empty() ? instructionInstances(grounded, kb) : std::optional<core::Scene>(core::Scene::load(o.scenePath));
  result.warnings = grounded.plan.warnings;
  result.planLines = planLines(grounded.plan);
  progress("language", 1, 1);

  // 3. Environment.
  clock.start("environment");
  const perception::PerceptionResult seen = perceive(grounded, kb, o, result.warnings, scene);
  // From here on the knowledge base includes what the demonstration showed of the unknown objects.
  const core::ObjectCatalogue runKb = perception::withObservedClasses(kb, seen.observedClasses);
  // 3b. Each phrase -> the perceived instance it means (several of one class).
  grounded = groundInstances(grounded, seen, runKb, scene);
  reportPerception(seen, result);

  // 4. Motion: the perception result handed over in memory, segmented, DMPs learned.
  clock.start("motion");
  progress("motion", 0, 1);
  const motion::DemoTracks tracks = demoTracks(seen, grounded, frameRateOf(seen.hand));
  const motion::LearnedSkills learned = motion::learnSkills(tracks);
  const motion::Segmentation& segmentation = learned.segmentation;
  const std::vector<motion::SkillSet>& skills = learned.skills;
  // 4b. Nothing is stored for a plan the demonstration does not show whole.
  result.problems = stepProblems(grounded, seen, segmentation, result.warnings);
  if (!result.problems.empty() && !o.allowPartial) {
    std::string message;
    for (const auto& p : result.problems) message += (message.empty() ? "" : "; ") + p;
    throw InvalidInputError(message + "; nothing was stored (--allow-partial stores the task model without what is "
                                      "missing)");
  }
  // 5. The rows: instruction tables, perception rows, skills, the perceived scene.
  const taskdb::TaskModel model = buildTaskModel(grounded, o, seen, runKb, tracks, skills, scene);
  result.skillCount = model.skills.size();
  result.sceneStored = model.scene.has_value();
  if (!model.scene)
    result.warnings.push_back("no table plane was found in the demonstration: the task model stores no perceived "
                              "scene ('srp execute' then needs --scene)");
  for (const auto& w : segmentation.warnings) result.warnings.push_back(w);
  result.objects = objectOutcomes(segmentation, seen, skills, runKb);
  const std::optional<core::Scene> sceneFile = sceneFileOf(model, o, seen, result.robotBase);
  progress("motion", 1, 1);
  // What perception saw, drawn on the recording (read again): before the
  // database is locked for writing.
  if (report) {
    clock.start("report");
    result.reportFiles = writeContactSheet(report->temporaryPath().string(), o, seen, runKb, segmentation, model.scene);
  }

  // 6. One transaction (the report written inside it, before COMMIT).
  clock.start("store");
  storeTaskModel(model, o, result, clock, report.get(), sceneFile, seen, segmentation, skills);
  result.peakResidentMemory_MB = peakResidentMemory_MB();
  return result;
}

}  // namespace srp::programming
