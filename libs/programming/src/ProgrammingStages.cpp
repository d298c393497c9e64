#include "srp/programming/ProgrammingStages.h"

#include <algorithm>
#include <filesystem>
#include <limits>

#include "srp/core/Error.h"
#include "srp/core/Pose.h"
#include "srp/core/Text.h"
#include "srp/execution/DemonstrationScene.h"
#include "srp/execution/SceneGrounder.h"
#include "srp/language/InstructionParser.h"
#include "srp/language/PlanTables.h"
#include "srp/perception/DemoRawlogReader.h"
#include "srp/programming/MotionRows.h"
#include "srp/programming/PerceptionRows.h"

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
  {
    perception::DemoRawlogReader::Options read;
    read.intrinsics = o.intrinsics;
    perception::DemoRawlogReader reader(o.demoPath, read);
    if (perceiver.wantsPreview())  // the hand learns from (or is chosen in) the whole recording: a first pass
      reader.preview(perceiver, [&](int previewed) {
        if (o.progress) o.progress("environment preview", static_cast<std::size_t>(previewed), 0);
      });
    while (auto f = reader.next()) {
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
  perception::PerceptionResult seen;
  try {
    seen = perception::inFirstCameraFrame(perceiver.finish());
  } catch (const InvalidInputError& e) {
    throw InvalidInputError(std::string("environment: ") + e.what() + "; nothing was stored");
  }
  for (std::size_t i = 0; i < grounded.stepClasses.size(); ++i) {
    const std::string& cls = grounded.stepClasses[i];
    const bool shown = std::any_of(seen.objects.begin(), seen.objects.end(),
                                   [&](const auto& t) { return t.className == cls && t.detectedFrames() > 0; });
    if (!shown)
      throw InvalidInputError("step " + std::to_string(i + 1) + " (" + planLines(grounded.plan)[i] +
                              "): the instruction moves the " + cls + ", but the demonstration '" + o.demoPath +
                              "' never shows it (" + std::to_string(seen.frames) + " frames); nothing was stored");
  }
  return seen;
}

std::optional<taskdb::PerceivedScene> perceivedSceneOf(const perception::PerceptionResult& seen,
                                                       const core::ObjectCatalogue& kb,
                                                       const std::optional<core::Scene>& scene,
                                                       const std::string& cataloguePath) {
  if (!seen.X_camera_table) return std::nullopt;
  const core::Pose3 X_plane_camera = seen.X_camera_table->inverse();
  const std::map<std::string, std::string> colours = instanceColours(scene, kb);
  taskdb::PerceivedScene out;
  out.catalogue = cataloguePath;
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const auto& t : seen.objects) {
    const auto first = std::find_if(t.samples.begin(), t.samples.end(), [](const auto& s) { return s.detected; });
    const core::ObjectClass* cls = kb.find(t.className);
    if (first == t.samples.end() || !cls) continue;
    // Resting on the plane: its yaw about the plane's normal, never below the plane.
    const core::Pose3 X_plane_object = X_plane_camera * first->X_camera_object;
    const double yaw = core::yawOf(X_plane_object.linear());
    taskdb::SceneObjectRow row;
    row.objectId = t.key();
    row.classId = cls->classId;
    row.className = cls->name;
    row.X_table_object.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    row.X_table_object.translation() = X_plane_object.translation();
    row.X_table_object.translation().z() = std::max(0.0, X_plane_object.translation().z());
    const auto word = colours.find(t.instanceId);
    const std::string colour = !t.instanceId.empty() && word != colours.end() ? word->second : classColourWord(*cls);
    if (!colour.empty()) row.colour = colour;
    if (scene && !t.instanceId.empty())
      if (const core::SceneObject* so = scene->findObject(t.instanceId)) row.rgb = so->rgb;
    for (int sx : {-1, 1})
      for (int sy : {-1, 1}) {
        const Eigen::Vector3d corner =
            row.X_table_object * Eigen::Vector3d(sx * cls->dimensions_m.x() / 2, sy * cls->dimensions_m.y() / 2, 0.0);
        lo = lo.cwiseMin(corner.head<2>());
        hi = hi.cwiseMax(corner.head<2>());
      }
    if (cls->observed && std::none_of(out.observedClasses.begin(), out.observedClasses.end(),
                                      [&](const auto& c) { return c.name == cls->name; }))
      out.observedClasses.push_back(*cls);
    out.objects.push_back(row);
  }
  if (out.objects.empty()) return std::nullopt;
  // The table frame: the plane's, moved to the centre of the objects' rectangle.
  const Eigen::Vector2d centre = (lo + hi) / 2;
  out.tableSize_m = (hi - lo).array() + 2 * kPerceivedTableMargin_m;
  core::Pose3 X_table_plane = core::Pose3::Identity();
  X_table_plane.translation() = Eigen::Vector3d(-centre.x(), -centre.y(), 0.0);
  out.X_table_camera = X_table_plane * X_plane_camera;
  for (auto& o : out.objects) o.X_table_object = X_table_plane * o.X_table_object;
  return out;
}

execution::CellDescription perceivedScene(const perception::PerceptionResult& seen, const core::ObjectCatalogue& kb,
                                          const std::optional<core::Scene>& scene) {
  const auto perceived = perceivedSceneOf(seen, kb, scene, "");
  if (!perceived)
    throw InvalidInputError("the demonstration's perception found no table plane (or the camera moves): the "
                            "instruction's objects cannot be grounded among several instances");
  const execution::RobotPlacement placement = execution::RobotPlacement::of(*perceived, std::nullopt);
  return execution::CellDescription::fromScene(execution::demonstrationScene(*perceived, placement), kb);
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
    const Eigen::Vector3d p_object = p_object_tracked(t->className, seen.observedClasses);
    std::map<int, const perception::ObjectPoseSample*> at;
    for (const auto& s : t->samples) at[s.frame] = &s;
    motion::ObjectTrack track;
    track.name = cls;
    track.positions = core::PositionTrajectory(taskdb::TaskModelInfo{}.frame);
    for (int f : frames) {
      const auto it = at.find(f);
      const bool ok = it != at.end() && it->second->detected;
      track.positions.append(
          {f, f / frameRate_hz, ok ? Eigen::Vector3d(it->second->X_camera_object * p_object) : Eigen::Vector3d::Zero(),
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

std::vector<std::string> stepProblems(const GroundedPlan& grounded, const perception::PerceptionResult& seen,
                                      const motion::Segmentation& segmentation, std::vector<std::string>& warnings) {
  std::vector<std::string> problems;
  const std::vector<std::string> lines = planLines(grounded.plan);
  const auto seenObject = [&](const std::string& key) -> const perception::ObjectTrajectory* {
    for (const auto& t : seen.objects)
      if (t.key() == key) return &t;
    return nullptr;
  };
  for (std::size_t i = 0; i < grounded.plan.steps.size() && i < grounded.stepObjects.size(); ++i) {
    const std::string step = "step " + std::to_string(i + 1) + " (" + lines[i] + ")";
    const std::string& key = grounded.stepObjects[i];
    const auto seg = std::find_if(segmentation.objects.begin(), segmentation.objects.end(),
                                  [&](const auto& o) { return o.name == key; });
    const perception::ObjectTrajectory* t = seenObject(key);
    const std::string detected =
        " (detected in " + std::to_string(t ? t->detectedFrames() : 0) + " of " + std::to_string(seen.frames) +
        " frames, hand in " + std::to_string(seen.handDetected) + ")";
    if (seg == segmentation.objects.end())
      problems.push_back(step + ": the demonstration gives no track of the " + key + detected);
    else if (!seg->moved)
      problems.push_back(step + ": the " + key + " never leaves its place in the demonstration, so it has no grasp "
                         "and no release" + detected + (seg->note.empty() ? "" : ": " + seg->note));
    else if (seg->graspFrame < 0 || seg->releaseFrame < 0)
      problems.push_back(step + ": the demonstration shows no " + (seg->graspFrame < 0 ? "grasp" : "release") +
                         " of the " + key + detected + (seg->note.empty() ? "" : ": " + seg->note));
    const auto& plannedStep = grounded.plan.steps[i];
    for (const auto* list : {&plannedStep.source, &plannedStep.target})
      for (const auto& loc : *list) {
        const std::string& landmark = grounded.objectOf(loc.landmark.name, loc.landmark.colour);
        const perception::ObjectTrajectory* lt = seenObject(landmark);
        if ((!lt || lt->detectedFrames() == 0) &&
            std::find_if(warnings.begin(), warnings.end(), [&](const std::string& w) {
              return w.rfind("the " + landmark + " ", 0) == 0;
            }) == warnings.end())
          warnings.push_back("the " + landmark + " ('" + loc.relation + " " + language::describe(loc.landmark) + "', " +
                             step + ") is never seen in the demonstration (" + std::to_string(seen.frames) +
                             " frames): the perceived scene lacks it, so the task cannot run in the scene of its own "
                             "demonstration (give srp execute a --scene)");
      }
  }
  return problems;
}

taskdb::TaskModel buildTaskModel(const GroundedPlan& grounded, const ProgrammingOptions& o,
                                 const perception::PerceptionResult& seen, const core::ObjectCatalogue& kb,
                                 const motion::DemoTracks& tracks, const std::vector<motion::SkillSet>& skills,
                                 const std::optional<core::Scene>& scene) {
  taskdb::TaskModel model = language::planToTaskModel(grounded.plan, o.name, o.instruction);
  model.info.frameRate_hz = frameRateOf(seen.hand);
  model.info.intrinsics = seen.intrinsics;
  model.info.X_base_camera = o.X_base_camera;
  const std::string catalogue = o.cataloguePath.empty() ? core::ObjectCatalogue::defaultPath() : o.cataloguePath;
  model.scene = perceivedSceneOf(seen, kb, scene, std::filesystem::absolute(catalogue).lexically_normal().string());
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

}  // namespace srp::programming
