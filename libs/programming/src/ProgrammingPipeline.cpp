#include "srp/kb/KnowledgeBase.h"
#include "srp/programming/ProgrammingPipeline.h"

#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "srp/core/Error.h"
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

double frameRateOf(const core::PositionTrajectory& samples) {
  std::vector<double> dt;
  for (std::size_t i = 1; i < samples.size(); ++i)
    if (samples[i].frame > samples[i - 1].frame)
      dt.push_back((samples[i].t_s - samples[i - 1].t_s) / (samples[i].frame - samples[i - 1].frame));
  if (dt.empty()) return 30.0;
  std::nth_element(dt.begin(), dt.begin() + static_cast<std::ptrdiff_t>(dt.size() / 2), dt.end());
  const double median = dt[dt.size() / 2];
  return median > 0.0 ? 1.0 / median : 30.0;
}

namespace {
// The report folder's parent is created and checked now, so an unusable folder
// fails the run before anything is computed or stored; the report itself is
// built beside it and renamed into place (core::AtomicOutputFolder).
const std::vector<std::string> kReportFiles = {"hand_trajectory.png", "summary.md", "*_skills.png"};

void checkReportFolder(const std::string& dir) {
  const std::filesystem::path folder = std::filesystem::path(dir).lexically_normal();
  std::error_code ec;
  if (folder.has_parent_path()) std::filesystem::create_directories(folder.parent_path(), ec);
  core::checkFolderHoldsOnly(folder, kReportFiles, "--report");
  if (ec || std::filesystem::exists(folder, ec) != std::filesystem::is_directory(folder, ec))
    throw core::FileError(dir, "cannot create the report folder here (" +
                                   (ec ? ec.message() : std::string("a file of that name exists")) +
                                   "); nothing was stored. Give a writable folder with --report");
  const core::AtomicOutputFolder probe(folder);  // creates and removes a folder beside it: the parent is writable
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
  // Open the database and check the report folder first: a bad file fails
  // before minutes of perception.
  { auto db = taskdb::TaskDatabase::open(o.dbPath); }
  if (!o.reportDir.empty()) checkReportFolder(o.reportDir);

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
  // 3b. Each phrase -> the perceived instance it means (several of one class).
  grounded = groundInstances(grounded, seen, kb, scene);
  result.frames = seen.frames;
  result.handDetectedFrames = seen.handDetected;

  // 4. Motion: the perception result handed over in memory, segmented, DMPs learned.
  clock.start("motion");
  progress("motion", 0, 1);
  const motion::DemoTracks tracks = demoTracks(seen, grounded, frameRateOf(seen.hand));
  const motion::LearnedSkills learned = motion::learnSkills(tracks);
  const motion::Segmentation& segmentation = learned.segmentation;
  const std::vector<motion::SkillSet>& skills = learned.skills;
  // 5. The rows: instruction tables, perception rows, skills.
  const taskdb::TaskModel model = buildTaskModel(grounded, o, seen, kb, tracks, skills, scene);
  result.skillCount = model.skills.size();
  for (const auto& w : segmentation.warnings) result.warnings.push_back(w);
  for (const auto& seg : segmentation.objects) {
    ObjectOutcome out;
    out.name = seg.name;
    out.classId = kb.find(seg.name) ? kb.find(seg.name)->classId : -1;
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
    result.objects.push_back(out);
  }
  progress("motion", 1, 1);

  // 6. One transaction. The report is written inside it, before COMMIT: a
  // report that cannot be written rolls the model back (all or nothing).
  clock.start("store");
  {
    auto db = taskdb::TaskDatabase::open(o.dbPath);
    taskdb::TaskModelStore store(db);
    result.name = o.name;
    result.taskModelId = store.write(
        model, [&](std::size_t done, std::size_t total) { progress("store", done, total); },
        [&](int id, int version) {
          result.taskModelId = id;
          result.version = version;
          clock.stop();
          if (!o.reportDir.empty()) {
            core::AtomicOutputFolder report(std::filesystem::path(o.reportDir).lexically_normal());
            const std::string staged = report.temporaryPath().string();
            result.reportFiles = writeProgramReport(staged, result, seen, segmentation, skills);
            report.commit();
            for (auto& f : result.reportFiles) f = o.reportDir + f.substr(staged.size());
          }
        });
  }
  result.peakResidentMemory_MB = peakResidentMemory_MB();
  return result;
}

std::string toJsonText(const ProgramResult& r) {
  nlohmann::json j;
  j["task_model_id"] = r.taskModelId;
  j["name"] = r.name;
  j["version"] = r.version;
  j["plan"] = r.planLines;
  j["frames"] = r.frames;
  j["hand_detected_frames"] = r.handDetectedFrames;
  j["skills"] = r.skillCount;
  j["objects"] = nlohmann::json::array();
  for (const auto& o : r.objects)
    j["objects"].push_back({{"name", o.name}, {"instance", o.instanceId}, {"class_id", o.classId}, {"moved", o.moved},
                            {"grasp_frame", o.graspFrame}, {"release_frame", o.releaseFrame},
                            {"detected_frames", o.detectedFrames}, {"reach_lambda", o.reachLambda},
                            {"move_lambda", o.moveLambda}, {"note", o.note}});
  j["timings_s"] = nlohmann::json::object();
  for (const auto& t : r.timings) j["timings_s"][t.stage] = t.wall_s;
  j["peak_memory_MB"] = r.peakResidentMemory_MB;
  j["warnings"] = r.warnings;
  j["report_files"] = r.reportFiles;
  return j.dump(2);
}

}  // namespace srp::programming
