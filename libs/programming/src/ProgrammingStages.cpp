#include "srp/programming/ProgrammingStages.h"

#include <algorithm>

#include "srp/core/Error.h"
#include "srp/core/Pose.h"
#include "srp/core/Text.h"
#include "srp/execution/SceneGrounder.h"
#include "srp/language/InstructionParser.h"
#include "srp/language/PlanTables.h"
#include "srp/perception/PreviewRawlog.h"
#include "srp/programming/MotionRows.h"
#include "srp/programming/PerceptionRows.h"
#include "srp/rawlog/RawlogReader.h"

namespace srp::programming {

using core::InvalidInputError;

namespace {

std::pair<std::string, std::string> wordsOf(const std::string& name, const std::optional<std::string>& colour) {
  return {core::toLowerAscii(name), colour ? core::toLowerAscii(*colour) : std::string()};
}

// Grounds an instruction's object in the knowledge base; nullptr when it does not know it.
const core::ObjectClass* ground(const core::ObjectCatalogue& kb, const language::ObjectRef& o) {
  const auto [noun, colour] = wordsOf(o.name, o.colour);
  return kb.ground(noun, colour);
}

// A class the knowledge base names but cannot model: no mesh file and no generator shape.
bool withoutModel(const core::ObjectClass& c) { return c.shape.empty() && c.meshPath.empty(); }

// The colour word a class answers to: its own, else the basic colour nearest its rgb.
std::string classColourWord(const core::ObjectClass& c) {
  return !c.colourName.empty() ? c.colourName : core::nearestColourName(c.rgb);
}

// Per part class of the plan: the basic colour words its phrases use.
std::map<std::string, std::set<std::string>> partColourWords(const GroundedPlan& g, const core::ObjectCatalogue& kb) {
  std::map<std::string, std::set<std::string>> out;
  for (const auto& [words, cls] : g.classByWords) {
    const core::ObjectClass* c = kb.find(cls);
    if (!c || c->kind != core::ObjectKind::Part || words.second.empty() || !core::rgbOfColourName(words.second)) continue;
    out[cls].insert(words.second);
  }
  return out;
}

// The colour word of each scene instance (core::instanceColour), for the rows and the grounding.
std::map<std::string, std::string> instanceColours(const std::optional<core::Scene>& scene,
                                                   const core::ObjectCatalogue& kb) {
  std::map<std::string, std::string> out;
  if (!scene) return out;
  for (const auto& o : scene->objects)
    if (const auto* cls = kb.find(o.className)) out[o.id] = core::instanceColour(o, *cls);
  return out;
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

std::optional<core::Scene> instructionInstances(const GroundedPlan& grounded, const core::ObjectCatalogue& kb) {
  core::Scene scene;
  scene.name = "instruction";
  for (const auto& [cls, colours] : partColourWords(grounded, kb)) {
    if (colours.size() < 2) continue;
    for (const auto& colour : colours) {
      core::SceneObject o;
      o.id = cls + "_" + colour;
      std::replace(o.id.begin(), o.id.end(), ' ', '_');
      o.className = cls;
      o.colour = colour;
      scene.objects.push_back(o);
    }
  }
  if (scene.objects.empty()) return std::nullopt;
  return scene;
}

const std::string& GroundedPlan::objectOf(const std::string& name, const std::optional<std::string>& colour) const {
  const auto it = objectByWords.find(wordsOf(name, colour));
  if (it == objectByWords.end())
    throw InvalidInputError("'" + name + "' is not an object of the grounded plan; ground the plan it comes from");
  return it->second;
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
  using Role = perception::UnknownObject::Role;
  // An object the knowledge base cannot model is found in the demonstration:
  // a step's object as the part moved, a landmark as the place of `of`.
  const auto add = [&](const language::ObjectRef& o, Role role, const std::string& of) -> std::string {
    const core::ObjectClass* c = ground(kb, o);
    std::string cls;
    if (c && !withoutModel(*c)) {
      cls = c->name;
    } else {
      perception::UnknownObject u;
      u.name = c ? c->name : core::toLowerAscii(o.name);
      u.noun = c && !c->noun.empty() ? c->noun : core::toLowerAscii(o.name);
      if (o.colour) u.colour = core::toLowerAscii(*o.colour);
      if (c) u.classId = c->classId;
      u.role = role;
      u.of = of;
      cls = u.name;
      const auto it = g.unknown.find(cls);
      if (it == g.unknown.end()) g.unknown.emplace(cls, u);
      else if (it->second.role != Role::Moved && role == Role::Moved) it->second = u;  // a part moved is a part
    }
    g.classByWords[wordsOf(o.name, o.colour)] = cls;
    return cls;
  };
  for (const auto& step : plan.steps) {
    const std::string cls = add(step.object, Role::Moved, "");
    g.stepClasses.push_back(cls);
    if (std::find(g.movingClasses.begin(), g.movingClasses.end(), cls) == g.movingClasses.end())
      g.movingClasses.push_back(cls);
    for (const auto& loc : step.source) g.landmarkClasses.insert(add(loc.landmark, Role::PickPlace, cls));
    for (const auto& loc : step.target) g.landmarkClasses.insert(add(loc.landmark, Role::ReleasePlace, cls));
  }
  // One instance per class until groundInstances says otherwise.
  g.stepObjects = g.stepClasses;
  g.movingObjects = g.movingClasses;
  g.objectByWords = g.classByWords;
  return g;
}

perception::PerceptionResult perceive(const GroundedPlan& grounded, const core::ObjectCatalogue& kb,
                                      const ProgrammingOptions& o, std::vector<std::string>& warnings,
                                      const std::optional<core::Scene>& scene) {
  perception::PerceptionOptions popt;
  using Hand = ProgrammingOptions::Hand;
  popt.hand = o.hand == Hand::MarkerFree ? perception::PerceptionOptions::HandMethod::MarkerFree
              : o.hand == Hand::Marker   ? perception::PerceptionOptions::HandMethod::Marker
                                         : perception::PerceptionOptions::HandMethod::Auto;
  const auto known = [&](const std::string& cls) { return grounded.unknown.count(cls) == 0; };
  for (const auto& cls : grounded.movingClasses)
    if (known(cls)) popt.plan.push_back({cls, false, "", std::nullopt});
  for (const auto& cls : grounded.landmarkClasses)
    if (known(cls) &&
        std::find(grounded.movingClasses.begin(), grounded.movingClasses.end(), cls) == grounded.movingClasses.end())
      popt.plan.push_back({cls, true, "", std::nullopt});
  // The unknown objects: the moved parts first (the places refer to them).
  for (const auto& [cls, u] : grounded.unknown)
    if (u.role == perception::UnknownObject::Role::Moved) popt.unknownObjects.push_back(u);
  for (const auto& [cls, u] : grounded.unknown)
    if (u.role != perception::UnknownObject::Role::Moved) popt.unknownObjects.push_back(u);
  if (scene) popt.plan = perception::withSceneInstances(popt.plan, *scene, kb);
  if (o.scenePath.empty()) {
    // No scene file: a part the instruction names in one colour that is not
    // its class's ("the blue cuboid", the catalogue's cuboid being red) is
    // looked for in that colour.
    const auto words = partColourWords(grounded, kb);
    for (auto& p : popt.plan) {
      const auto w = words.find(p.className);
      if (!p.instanceId.empty() || w == words.end() || w->second.size() != 1) continue;
      const std::string& colour = *w->second.begin();
      if (colour != classColourWord(kb.at(p.className))) p.rgb = core::rgbOfColourName(colour);
    }
  }

  perception::DemoPerceiver perceiver(kb, popt);
  if (perceiver.wantsPreview())  // the hand learns from (or is chosen in) the whole recording: a first read
    perception::previewRawlog(perceiver, o.demoPath, o.intrinsics, [&](int previewed) {
      if (o.progress) o.progress("environment preview", static_cast<std::size_t>(previewed), 0);
    });
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
  perception::PerceptionResult seen = perception::inFirstCameraFrame(perceiver.finish());
  for (const auto& cls : grounded.movingClasses) {
    const bool shown = std::any_of(seen.objects.begin(), seen.objects.end(),
                                   [&](const auto& t) { return t.className == cls && t.detectedFrames() > 0; });
    if (!shown)
      throw InvalidInputError("the instruction moves the " + cls + ", but the demonstration '" + o.demoPath +
                              "' never shows it; nothing was stored");
  }
  return seen;
}

execution::CellDescription perceivedScene(const perception::PerceptionResult& seen, const core::ObjectCatalogue& kb,
                                          const std::optional<core::Scene>& scene) {
  if (!seen.X_camera_table)
    throw InvalidInputError("the demonstration's perception found no table plane (or the camera moves): the "
                            "instruction's objects cannot be grounded among several instances");
  const core::Pose3 X_table_camera = seen.X_camera_table->inverse();
  const std::map<std::string, std::string> colours = instanceColours(scene, kb);
  execution::CellDescription cell;
  cell.X_world_camera = X_table_camera;  // world = the table frame
  for (const auto& t : seen.objects) {
    const auto first = std::find_if(t.samples.begin(), t.samples.end(), [](const auto& s) { return s.detected; });
    const core::ObjectClass* cls = kb.find(t.className);
    if (first == t.samples.end() || !cls) continue;
    execution::CellObject c;
    c.name = t.key();
    c.className = t.className;
    c.noun = cls->noun.empty() ? cls->name : cls->noun;
    c.classId = cls->classId;
    c.kind = cls->kind == core::ObjectKind::Container ? execution::CellObjectKind::Container : execution::CellObjectKind::Part;
    c.size_m = cls->dimensions_m;
    c.X_world_object = X_table_camera * first->X_camera_object;
    c.rgb = cls->rgb;
    const auto word = colours.find(t.instanceId);
    c.colour = !t.instanceId.empty() && word != colours.end() ? word->second : classColourWord(*cls);
    cell.objects.push_back(c);
  }
  return cell;
}

GroundedPlan groundInstances(const GroundedPlan& grounded, const perception::PerceptionResult& seen,
                             const core::ObjectCatalogue& kb, const std::optional<core::Scene>& scene) {
  GroundedPlan g = grounded;
  const auto perInstance = [&](const std::string& cls) {
    return std::any_of(seen.objects.begin(), seen.objects.end(),
                       [&](const auto& t) { return t.className == cls && !t.instanceId.empty(); });
  };
  if (std::none_of(g.classByWords.begin(), g.classByWords.end(), [&](const auto& kv) { return perInstance(kv.second); }))
    return g;  // one instance per class: the classes are the objects
  const execution::CellDescription cell = perceivedScene(seen, kb, scene);
  const execution::SceneGrounder grounder(cell);
  const auto objectOf = [&](const language::ObjectRef& ref, const std::vector<language::LocationRef>& where) {
    const std::string& cls = g.classOf(ref.name, ref.colour);
    if (!perInstance(cls)) return cls;
    return grounder.ground(ref, where).name;
  };
  g.stepObjects.clear();
  g.movingObjects.clear();
  for (const auto& step : g.plan.steps) {
    const std::string key = objectOf(step.object, step.source);
    g.objectByWords[wordsOf(step.object.name, step.object.colour)] = key;
    g.stepObjects.push_back(key);
    if (std::find(g.movingObjects.begin(), g.movingObjects.end(), key) == g.movingObjects.end())
      g.movingObjects.push_back(key);
    for (const auto* list : {&step.source, &step.target})
      for (const auto& loc : *list) g.objectByWords[wordsOf(loc.landmark.name, loc.landmark.colour)] = objectOf(loc.landmark, {});
  }
  for (const auto& key : g.movingObjects) {
    const bool shown = std::any_of(seen.objects.begin(), seen.objects.end(),
                                   [&](const auto& t) { return t.key() == key && t.detectedFrames() > 0; });
    if (!shown)
      throw InvalidInputError("the instruction moves the " + key + ", but the demonstration never shows it; nothing was stored");
  }
  return g;
}

motion::DemoTracks demoTracks(const perception::PerceptionResult& seen, const GroundedPlan& grounded,
                              double frameRate_hz) {
  core::require(frameRate_hz > 0, "the demonstration's frame rate must be positive");
  motion::DemoTracks tracks;
  tracks.planOrder = grounded.stepObjects;
  // The moved objects' trajectories by key (the sorted order motion's
  // inputs have always had); an object never sampled has no track.
  std::map<std::string, const perception::ObjectTrajectory*> moved;
  for (const auto& key : grounded.movingObjects)
    for (const auto& t : seen.objects)
      if (t.key() == key && !t.samples.empty()) moved[key] = &t;

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
    // A part found in the demonstration is followed at its middle: its
    // origin is the foot of its observed points, a hand's span below a tall
    // part's top where the hand holds it (HRT1's toy: 19 cm), which the
    // segmenter would take for a detection away from the hand.
    const auto observed = std::find_if(seen.observedClasses.begin(), seen.observedClasses.end(),
                                       [&](const core::ObjectClass& c) { return c.name == t->className; });
    const Eigen::Vector3d p_object_tracked = observed == seen.observedClasses.end()
                                                 ? Eigen::Vector3d::Zero()
                                                 : Eigen::Vector3d(0, 0, 0.5 * observed->dimensions_m.z());
    std::map<int, const perception::ObjectPoseSample*> at;
    for (const auto& s : t->samples) at[s.frame] = &s;
    motion::ObjectTrack track;
    track.name = cls;
    track.positions = core::PositionTrajectory(taskdb::TaskModelInfo{}.frame);
    for (int f : frames) {
      const auto it = at.find(f);
      const bool ok = it != at.end() && it->second->detected;
      track.positions.append(
          {f, f / frameRate_hz, ok ? Eigen::Vector3d(it->second->X_camera_object * p_object_tracked) : Eigen::Vector3d::Zero(),
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
                                 const motion::DemoTracks& tracks, const std::vector<motion::SkillSet>& skills,
                                 const std::optional<core::Scene>& scene) {
  taskdb::TaskModel model = language::planToTaskModel(grounded.plan, o.name, o.instruction);
  model.info.frameRate_hz = frameRateOf(seen.hand);
  model.info.intrinsics = seen.intrinsics;
  PerceptionRows rows = toTaskDbRows(seen, kb, instanceColours(scene, kb));
  model.handPositions = std::move(rows.handPositions);
  model.groundedProducts = std::move(rows.groundedProducts);
  model.productPoses = std::move(rows.productPoses);
  // Class names become class ids here, in the rows; a phrase grounded to an
  // instance names it (Products.InstanceId).
  for (auto& p : model.products) {
    const int classId = kb.at(grounded.classOf(p.objectName, p.colour)).classId;
    if (!model.findGrounded(classId)) continue;
    p.classId = classId;
    const std::string& key = grounded.objectOf(p.objectName, p.colour);
    for (const auto& g : model.groundedProducts)
      if (g.classId == classId && !g.instanceId.empty() && g.instanceId == key) p.instanceId = key;
  }
  // A grounded object takes the source/target location of its plan step.
  for (auto& g : model.groundedProducts)
    for (int id : model.targetObjectIds)
      if (const auto* p = model.findProduct(id); p && p->classId == g.classId && p->instanceId == g.instanceId) {
        if (p->sourceLocationId && !g.sourceLocationId) g.sourceLocationId = p->sourceLocationId;
        if (p->targetLocationId && !g.targetLocationId) g.targetLocationId = p->targetLocationId;
      }
  MotionInputs inputs;
  static_cast<motion::DemoTracks&>(inputs) = tracks;
  for (const auto& g : model.groundedProducts) inputs.rowKeyByName[perceptionKey(g)] = {g.classId, g.instanceId};
  model.skills = skillRows(skills, inputs);
  setSkillFlags(model.productPoses, skills, inputs);
  return model;
}

}  // namespace srp::programming
