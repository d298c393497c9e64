#include "srp/programming/ProgrammingPipeline.h"

#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>

#include "srp/core/Error.h"
#include "srp/core/ObjectCatalogue.h"
#include "srp/language/InstructionParser.h"
#include "srp/language/PlanTables.h"
#include "srp/motion/Segmenter.h"
#include "srp/motion/SkillLearner.h"
#include "srp/motion/SkillPlots.h"
#include "srp/motion/TaskModelMapping.h"
#include "srp/perception/DemoPerception.h"
#include "srp/perception/TaskDbMapping.h"
#include "srp/programming/ProgramReport.h"
#include "srp/rawlog/RawlogReader.h"
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

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

// Grounds an instruction's object in the knowledge base, or says which names it knows.
const core::ObjectClass& ground(const core::ObjectCatalogue& kb, const language::ObjectRef& o) {
  if (const core::ObjectClass* c = kb.ground(lower(o.name), o.color ? lower(*o.color) : "")) return *c;
  std::string known;
  for (const auto& c : kb.classes()) known += (known.empty() ? "" : ", ") + c.name;
  throw InvalidInputError("the instruction names '" + language::describe(o) +
                          "', which the knowledge base does not know (it knows: " + known +
                          "); add a mesh and a catalogue entry, or rephrase");
}

// Reach/Grasp/Move/Release flags of the ProductPose rows from the segmentation.
void setSkillFlags(taskdb::TaskModel& model, const std::vector<motion::SkillSet>& skills,
                   const std::map<std::string, int>& classIdByName) {
  for (const auto& s : skills) {
    const auto it = classIdByName.find(s.objectName);
    if (it == classIdByName.end()) continue;
    for (auto& row : model.productPoses)
      if (row.classId == it->second) motion::setSkillFlags(row, s);
  }
}

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
// Creates the report folder and writes (and removes) a probe file in it, so
// an unusable folder fails the run before anything is computed or stored.
void checkReportFolder(const std::string& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec || !std::filesystem::is_directory(dir))
    throw core::FileError(dir, "cannot create the report folder (" + (ec ? ec.message() : std::string("not a folder")) +
                                   "); nothing was stored. Give a writable folder with --report");
  const std::string probe = dir + "/.srp_write_probe";
  {
    std::ofstream out(probe);
    if (!(out << "probe") || !out.flush())
      throw core::FileError(dir, "cannot write in the report folder (permissions? disk full?); nothing was stored");
  }
  std::filesystem::remove(probe, ec);
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
  if (o.name.empty()) throw InvalidInputError("a task model needs a name (--name)");
  if (o.demoPath.empty()) throw InvalidInputError("no demonstration given (--demo demo.rawlog)");
  // Open the database and check the report folder first: a bad file fails
  // before minutes of perception.
  { auto db = taskdb::TaskDatabase::open(o.dbPath); }
  if (!o.reportDir.empty()) checkReportFolder(o.reportDir);

  // 1. Language.
  clock.start("language");
  progress("language", 0, 1);
  const language::InstructionParser parser;
  const language::TaskPlan plan = parser.parse(o.instruction);
  if (plan.steps.empty()) {
    std::string why;
    for (const auto& w : plan.warnings) why += (why.empty() ? "" : "; ") + w;
    throw InvalidInputError("the instruction gives no pick & place step, nothing was stored" +
                            (why.empty() ? std::string() : " (" + why + ")"));
  }
  result.warnings = plan.warnings;
  for (const auto& step : plan.steps) {
    std::string line = language::describe(step.object);
    for (const auto& s : step.source) line += ", " + s.relation + " " + language::describe(s.landmark);
    line += " ->";
    for (const auto& t : step.target) line += " " + t.relation + " " + language::describe(t.landmark) + ";";
    result.planLines.push_back(line);
  }
  progress("language", 1, 1);

  // 2. Grounding: step objects move, landmarks stay where they are.
  const core::ObjectCatalogue kb =
      core::ObjectCatalogue::load(o.cataloguePath.empty() ? core::ObjectCatalogue::defaultPath() : o.cataloguePath);
  std::vector<std::string> movingOrder;
  std::set<std::string> moving, landmarks;
  for (const auto& step : plan.steps) {
    const std::string& cls = ground(kb, step.object).name;
    if (moving.insert(cls).second) movingOrder.push_back(cls);
    for (const auto* list : {&step.source, &step.target})
      for (const auto& loc : *list) landmarks.insert(ground(kb, loc.landmark).name);
  }
  perception::PerceptionOptions popt;
  popt.hand = o.markerFreeHand ? perception::PerceptionOptions::HandMethod::MarkerFree
                               : perception::PerceptionOptions::HandMethod::Marker;
  for (const auto& cls : movingOrder) popt.plan.push_back({cls, false});
  for (const auto& cls : landmarks)
    if (!moving.count(cls)) popt.plan.push_back({cls, true});

  // 3. Environment.
  clock.start("environment");
  perception::DemoPerceiver perceiver(kb, popt);
  {
    rawlog::RawlogReader reader(o.demoPath);
    while (auto f = reader.next()) {
      if (o.intrinsics) f->intrinsics = *o.intrinsics;
      perceiver.add(*f);
      progress("environment", static_cast<std::size_t>(perceiver.framesAdded()), 0);
    }
    if (reader.damage() && !o.allowTruncated)
      throw core::FileError(o.demoPath, "unreadable demonstration, " + *reader.damage() +
                                            "; nothing was stored (--allow-truncated uses the frames before the damage)");
    if (reader.damage())
      result.warnings.push_back("demonstration " + *reader.damage() + "; using the " +
                                std::to_string(reader.framesRead()) + " frames before it (--allow-truncated)");
    if (perceiver.framesAdded() == 0)
      throw core::FileError(o.demoPath, "no RGB-D frames with depth in this rawlog; record one with 'srp record' "
                                        "or make one with 'srp synth-demo'");
  }
  const perception::PerceptionResult seen = perceiver.finish();
  result.frames = seen.frames;
  result.handDetectedFrames = seen.handDetected;
  for (const auto& cls : movingOrder) {
    const auto it = std::find_if(seen.objects.begin(), seen.objects.end(),
                                 [&](const auto& t) { return t.className == cls; });
    if (it == seen.objects.end() || it->detectedFrames() == 0)
      throw InvalidInputError("the instruction moves the " + cls + ", but the demonstration '" + o.demoPath +
                              "' never shows it; nothing was stored");
  }

  // 4. The task model: instruction tables + perception rows, ids linked.
  clock.start("motion");
  taskdb::TaskModel model = language::planToTaskModel(plan, o.name, o.instruction);
  model.info.frameRate_hz = frameRateOf(seen.hand);
  model.info.intrinsics = seen.intrinsics;
  const perception::PerceptionRows rows = perception::toTaskDbRows(seen, kb);
  model.handPositions = rows.handPositions;
  model.groundedProducts = rows.groundedProducts;
  model.productPoses = rows.productPoses;
  for (auto& p : model.products) {
    const language::ObjectRef ref{p.objectName, p.color};
    const core::ObjectClass& cls = ground(kb, ref);
    if (model.findGrounded(cls.classId)) p.classId = cls.classId;
  }
  // A grounded object takes the source/target location of its plan step.
  for (auto& g : model.groundedProducts)
    for (int id : model.targetObjectIds)
      if (const auto* p = model.findProduct(id); p && p->classId == g.classId) {
        if (p->sourceLocationId && !g.sourceLocationId) g.sourceLocationId = p->sourceLocationId;
        if (p->targetLocationId && !g.targetLocationId) g.targetLocationId = p->targetLocationId;
      }

  // 5. Motion: segmentation, skills, DMPs.
  progress("motion", 0, 1);
  const motion::MotionInputs inputs = motion::motionInputsFromTaskModel(model);
  const motion::Segmentation segmentation = motion::Segmenter().segment(inputs.hand, inputs.objects, inputs.planOrder);
  const std::vector<motion::SkillSet> skills = motion::SkillLearner().learn(segmentation, inputs.objects);
  model.skills = motion::skillRows(skills, inputs);
  setSkillFlags(model, skills, inputs.classIdByName);
  result.skillCount = model.skills.size();
  for (const auto& w : segmentation.warnings) result.warnings.push_back(w);
  for (const auto& seg : segmentation.objects) {
    ObjectOutcome out;
    out.name = seg.name;
    out.classId = inputs.classIdByName.count(seg.name) ? inputs.classIdByName.at(seg.name) : -1;
    out.moved = seg.moved;
    out.graspFrame = seg.graspFrame;
    out.releaseFrame = seg.releaseFrame;
    out.note = seg.note;
    for (const auto& t : seen.objects)
      if (t.className == seg.name) out.detectedFrames = t.detectedFrames();
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
          if (!o.reportDir.empty())
            result.reportFiles = writeProgramReport(o.reportDir, result, seen, segmentation, skills);
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
    j["objects"].push_back({{"name", o.name}, {"class_id", o.classId}, {"moved", o.moved},
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
