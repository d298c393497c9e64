#include "srp/programming/ProgrammingStages.h"

#include <algorithm>

#include "srp/core/Error.h"
#include "srp/core/Pose.h"
#include "srp/core/Text.h"
#include "srp/language/InstructionParser.h"
#include "srp/language/PlanTables.h"
#include "srp/programming/MotionRows.h"
#include "srp/programming/PerceptionRows.h"
#include "srp/rawlog/RawlogReader.h"

namespace srp::programming {

using core::InvalidInputError;

namespace {

std::pair<std::string, std::string> wordsOf(const std::string& name, const std::optional<std::string>& colour) {
  return {core::toLowerAscii(name), colour ? core::toLowerAscii(*colour) : std::string()};
}

// Grounds an instruction's object in the knowledge base, or says which names it knows.
const core::ObjectClass& ground(const core::ObjectCatalogue& kb, const language::ObjectRef& o) {
  const auto [noun, colour] = wordsOf(o.name, o.color);
  if (const core::ObjectClass* c = kb.ground(noun, colour)) return *c;
  std::string known;
  for (const auto& c : kb.classes()) known += (known.empty() ? "" : ", ") + c.name;
  throw InvalidInputError("the instruction names '" + language::describe(o) +
                          "', which the knowledge base does not know (it knows: " + known +
                          "); add a mesh and a catalogue entry, or rephrase");
}

// Reach/Grasp/Move/Release flags of the ProductPose rows from the skills.
void setSkillFlags(taskdb::TaskModel& model, const std::vector<motion::SkillSet>& skills,
                   const std::map<std::string, int>& classIdByName) {
  for (const auto& s : skills) {
    const auto it = classIdByName.find(s.objectName);
    if (it == classIdByName.end()) continue;
    for (auto& row : model.productPoses)
      if (row.classId == it->second) programming::setSkillFlags(row, s);
  }
}

}  // namespace

language::TaskPlan parsePlan(const std::string& instruction) {
  const language::InstructionParser parser;
  language::TaskPlan plan = parser.parse(instruction);
  if (plan.steps.empty()) {
    std::string why;
    for (const auto& w : plan.warnings) why += (why.empty() ? "" : "; ") + w;
    throw InvalidInputError("the instruction gives no pick & place step, nothing was stored" +
                            (why.empty() ? std::string() : " (" + why + ")"));
  }
  return plan;
}

std::vector<std::string> planLines(const language::TaskPlan& plan) {
  std::vector<std::string> lines;
  for (const auto& step : plan.steps) {
    std::string line = language::describe(step.object);
    for (const auto& s : step.source) line += ", " + s.relation + " " + language::describe(s.landmark);
    line += " ->";
    for (const auto& t : step.target) line += " " + t.relation + " " + language::describe(t.landmark) + ";";
    lines.push_back(line);
  }
  return lines;
}

const std::string& GroundedPlan::classOf(const std::string& name, const std::optional<std::string>& colour) const {
  const auto it = classByWords.find(wordsOf(name, colour));
  if (it == classByWords.end())
    throw InvalidInputError("'" + name + "' is not an object of the grounded plan; ground the plan it comes from");
  return it->second;
}

GroundedPlan groundPlan(const language::TaskPlan& plan, const core::ObjectCatalogue& kb) {
  GroundedPlan g;
  g.plan = plan;
  const auto add = [&](const language::ObjectRef& o) -> const std::string& {
    const std::string& cls = ground(kb, o).name;
    g.classByWords[wordsOf(o.name, o.color)] = cls;
    return cls;
  };
  for (const auto& step : plan.steps) {
    const std::string& cls = add(step.object);
    g.stepClasses.push_back(cls);
    if (std::find(g.movingClasses.begin(), g.movingClasses.end(), cls) == g.movingClasses.end())
      g.movingClasses.push_back(cls);
    for (const auto* list : {&step.source, &step.target})
      for (const auto& loc : *list) g.landmarkClasses.insert(add(loc.landmark));
  }
  return g;
}

perception::PerceptionResult perceive(const GroundedPlan& grounded, const core::ObjectCatalogue& kb,
                                      const ProgrammingOptions& o, std::vector<std::string>& warnings) {
  perception::PerceptionOptions popt;
  popt.hand = o.markerFreeHand ? perception::PerceptionOptions::HandMethod::MarkerFree
                               : perception::PerceptionOptions::HandMethod::Marker;
  for (const auto& cls : grounded.movingClasses) popt.plan.push_back({cls, false});
  for (const auto& cls : grounded.landmarkClasses)
    if (std::find(grounded.movingClasses.begin(), grounded.movingClasses.end(), cls) == grounded.movingClasses.end())
      popt.plan.push_back({cls, true});

  perception::DemoPerceiver perceiver(kb, popt);
  {
    rawlog::RawlogReader reader(o.demoPath);
    while (auto f = reader.next()) {
      if (o.intrinsics) f->intrinsics = *o.intrinsics;
      perceiver.add(*f);
      if (o.progress) o.progress("environment", static_cast<std::size_t>(perceiver.framesAdded()), 0);
    }
    if (reader.damage() && !o.allowTruncated)
      throw core::FileError(o.demoPath, "unreadable demonstration, " + *reader.damage() +
                                            "; nothing was stored (--allow-truncated uses the frames before the damage)");
    if (reader.damage())
      warnings.push_back("demonstration " + *reader.damage() + "; using the " + std::to_string(reader.framesRead()) +
                         " frames before it (--allow-truncated)");
    if (perceiver.framesAdded() == 0)
      throw core::FileError(o.demoPath, "no RGB-D frames with depth in this rawlog; record one with 'srp record' "
                                        "or make one with 'srp synth-demo'");
  }
  perception::PerceptionResult seen = perceiver.finish();
  for (const auto& cls : grounded.movingClasses) {
    const auto it = std::find_if(seen.objects.begin(), seen.objects.end(),
                                 [&](const auto& t) { return t.className == cls; });
    if (it == seen.objects.end() || it->detectedFrames() == 0)
      throw InvalidInputError("the instruction moves the " + cls + ", but the demonstration '" + o.demoPath +
                              "' never shows it; nothing was stored");
  }
  return seen;
}

motion::DemoTracks demoTracks(const perception::PerceptionResult& seen, const GroundedPlan& grounded,
                              double frameRate_hz) {
  core::require(frameRate_hz > 0, "the demonstration's frame rate must be positive");
  motion::DemoTracks tracks;
  tracks.planOrder = grounded.stepClasses;
  // The moved objects' trajectories by class name (the sorted order motion's
  // inputs have always had); an object never sampled has no track.
  std::map<std::string, const perception::ObjectTrajectory*> moved;
  for (const auto& cls : grounded.movingClasses)
    for (const auto& t : seen.objects)
      if (t.className == cls && !t.samples.empty()) moved[cls] = &t;

  std::set<int> frames;
  for (const auto& s : seen.hand.samples()) frames.insert(s.frame);
  for (const auto& [cls, t] : moved)
    for (const auto& s : t->samples) frames.insert(s.frame);

  std::map<int, const core::PositionSample*> handAt;
  for (const auto& s : seen.hand.samples()) handAt[s.frame] = &s;
  tracks.hand = core::PositionTrajectory(taskdb::TaskModelInfo{}.frame);
  for (int f : frames) {
    const auto it = handAt.find(f);
    const bool ok = it != handAt.end() && it->second->valid;
    tracks.hand.append({f, f / frameRate_hz, ok ? it->second->p_m : Eigen::Vector3d::Zero(), ok});
  }
  for (const auto& [cls, t] : moved) {
    std::map<int, const perception::ObjectPoseSample*> at;
    for (const auto& s : t->samples) at[s.frame] = &s;
    motion::ObjectTrack track;
    track.name = cls;
    track.positions = core::PositionTrajectory(taskdb::TaskModelInfo{}.frame);
    for (int f : frames) {
      const auto it = at.find(f);
      const bool ok = it != at.end() && it->second->detected;
      track.positions.append(
          {f, f / frameRate_hz, ok ? Eigen::Vector3d(it->second->X_camera_object.translation()) : Eigen::Vector3d::Zero(),
           ok});
      if (it != at.end()) {
        // The unit quaternion the ProductPose row stores (normalised again when read back, as yaw_rad() does).
        const Eigen::Quaterniond q = Eigen::Quaterniond(it->second->X_camera_object.linear()).normalized();
        track.yaw_rad.push_back(core::yawOf(q.normalized().toRotationMatrix()));
      } else {
        track.yaw_rad.push_back(track.yaw_rad.empty() ? 0.0 : track.yaw_rad.back());
      }
    }
    tracks.objects.push_back(std::move(track));
  }
  return tracks;
}

taskdb::TaskModel buildTaskModel(const GroundedPlan& grounded, const ProgrammingOptions& o,
                                 const perception::PerceptionResult& seen, const core::ObjectCatalogue& kb,
                                 const motion::DemoTracks& tracks, const std::vector<motion::SkillSet>& skills) {
  taskdb::TaskModel model = language::planToTaskModel(grounded.plan, o.name, o.instruction);
  model.info.frameRate_hz = frameRateOf(seen.hand);
  model.info.intrinsics = seen.intrinsics;
  PerceptionRows rows = toTaskDbRows(seen, kb);
  model.handPositions = std::move(rows.handPositions);
  model.groundedProducts = std::move(rows.groundedProducts);
  model.productPoses = std::move(rows.productPoses);
  // Class names become class ids here, in the rows.
  for (auto& p : model.products) {
    const int classId = kb.at(grounded.classOf(p.objectName, p.color)).classId;
    if (model.findGrounded(classId)) p.classId = classId;
  }
  // A grounded object takes the source/target location of its plan step.
  for (auto& g : model.groundedProducts)
    for (int id : model.targetObjectIds)
      if (const auto* p = model.findProduct(id); p && p->classId == g.classId) {
        if (p->sourceLocationId && !g.sourceLocationId) g.sourceLocationId = p->sourceLocationId;
        if (p->targetLocationId && !g.targetLocationId) g.targetLocationId = p->targetLocationId;
      }
  MotionInputs inputs;
  static_cast<motion::DemoTracks&>(inputs) = tracks;
  for (const auto& g : model.groundedProducts) inputs.classIdByName[g.objectName] = g.classId;
  model.skills = skillRows(skills, inputs);
  setSkillFlags(model, skills, inputs.classIdByName);
  return model;
}

}  // namespace srp::programming
