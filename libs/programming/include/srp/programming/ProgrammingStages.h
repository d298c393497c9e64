#pragma once
/// \file ProgrammingStages.h
/// \brief The stages of programTask (ProgrammingPipeline.h), one function
/// each, in the order they run:
///
///   parsePlan (instruction -> plan) -> groundPlan (every object the plan
///   names -> a knowledge-base class, once) -> perceive (demonstration ->
///   hand and object trajectories, per instance when a scene holds a class
///   several times) -> groundInstances (every phrase -> the perceived
///   instance it means) -> demoTracks (the in-memory hand-off to motion) ->
///   motion::learnSkills (segmentation + DMPs) -> buildTaskModel (the
///   task-database rows, made here and only here) -> TaskModelStore.
///
/// From the grounding to the rows an object is keyed by its perception key
/// (perception::PlanObject::key: the instance id when its class is tracked
/// per instance, else the knowledge-base class name; motion's
/// ObjectTrack::name, SkillSet::objectName); class ids, instance ids and the
/// instruction's ObjectIds appear only in the rows.

#include <map>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "srp/core/ObjectCatalogue.h"
#include "srp/core/PositionTrajectory.h"
#include "srp/core/Scene.h"
#include "srp/execution/CellDescription.h"
#include "srp/language/TaskPlan.h"
#include "srp/motion/LearnSkills.h"
#include "srp/perception/DemoPerception.h"
#include "srp/programming/ProgrammingOptions.h"
#include "srp/taskdb/TaskModel.h"

namespace srp::programming {

/// Stage 1: the instruction's pick & place plan. Throws InvalidInputError
/// when it gives no step (the message carries the parser's warnings).
language::TaskPlan parsePlan(const std::string& instruction);

/// One readable line per plan step ("cuboid, from blue box -> in gray box;").
std::vector<std::string> planLines(const language::TaskPlan& plan);

/// The plan with every object it names grounded in the knowledge base.
struct GroundedPlan {
  language::TaskPlan plan;
  std::vector<std::string> stepClasses;    ///< the class each step moves, step order (repeats kept)
  std::vector<std::string> movingClasses;  ///< stepClasses without repeats, first-mention order
  std::set<std::string> landmarkClasses;   ///< classes of every source/target landmark
  /// The class of each object as the instruction words it: (lower-case
  /// name, lower-case colour or "") -> class name.
  std::map<std::pair<std::string, std::string>, std::string> classByWords;
  /// The perceived object (perception key) each step moves, step order;
  /// without repeats; per wording. groundPlan sets them to the classes
  /// (one instance per class), groundInstances to the instances.
  std::vector<std::string> stepObjects;
  std::vector<std::string> movingObjects;
  std::map<std::pair<std::string, std::string>, std::string> objectByWords;
  /// Objects the knowledge base does not know (or knows without a mesh or a
  /// shape), by class name: perceive looks for them in the demonstration
  /// (perception::ObjectDiscovery). Their class names are in stepClasses,
  /// landmarkClasses and classByWords like the others'.
  std::map<std::string, perception::UnknownObject> unknown;

  /// The perceived object (key) of a phrase of the plan. Throws
  /// InvalidInputError for an object the plan does not name.
  const std::string& objectOf(const std::string& name, const std::optional<std::string>& colour) const;

  /// The class of an object of the plan. Throws InvalidInputError for an
  /// object the plan does not name.
  const std::string& classOf(const std::string& name, const std::optional<std::string>& colour) const;
};

/// Stage 2: grounds the plan's objects and landmarks, once. An object the
/// knowledge base does not know, or knows without a mesh or a shape, becomes
/// an unknown object (GroundedPlan::unknown) to be found in the
/// demonstration: a step's object is the part the hand moves, a landmark the
/// place where it was let go (target) or picked up (source); its class name
/// is the noun (the catalogue entry's name when there is one).
GroundedPlan groundPlan(const language::TaskPlan& plan, const core::ObjectCatalogue& kb);

/// Without a scene file: the instances the instruction's own colour words
/// name, as a scene of ids "<class>_<colour>" (no poses; colour = the word,
/// its rgb core::rgbOfColourName) for each part class named in two or more
/// basic colours ("the red cuboid ... the blue cuboid"); nullopt when there
/// is none. perceive and groundInstances then use it as the scene.
std::optional<core::Scene> instructionInstances(const GroundedPlan& grounded, const core::ObjectCatalogue& kb);

/// Stage 3: the Environment module on the demonstration, guided by the plan
/// (step objects move, the other landmarks are static). With a `scene` (the
/// demo's scene file, ProgrammingOptions::scenePath), a plan class the scene
/// holds several times is tracked per instance, with the instance's colour
/// (perception::withSceneInstances). Without a scene file
/// (ProgrammingOptions::scenePath empty), a part class the instruction names
/// in exactly one basic colour other than its class's is looked for in that
/// colour (its one instance, InstanceId ""). Appends a warning when a damaged rawlog
/// is used with allowTruncated. The plan's unknown objects are looked for in
/// the demonstration (their classes in PerceptionResult::observedClasses).
/// With a moving camera the result is in the first frame's camera
/// (perception::inFirstCameraFrame). Throws FileError for an unreadable or
/// empty rawlog, InvalidInputError when no instance of a moved class is ever
/// detected or an unknown object is not found (naming what was seen).
perception::PerceptionResult perceive(const GroundedPlan& grounded, const core::ObjectCatalogue& kb,
                                      const ProgrammingOptions& options, std::vector<std::string>& warnings,
                                      const std::optional<core::Scene>& scene = std::nullopt);

/// Distance [m] the perceived table reaches beyond the objects' footprints on
/// every side (perceivedSceneOf): with execution's default robot placement
/// (0.1 m inside the table edge, execution::kDefaultBaseInset_m) the robot then
/// stands 0.3 m from the nearest object, as in the thesis cell.
inline constexpr double kPerceivedTableMargin_m = 0.4;

/// The scene the demonstration showed, as stored with the task model
/// (taskdb::PerceivedScene): one object per perceived trajectory with a
/// detection (id = its key, class from the knowledge base, colour word = the
/// scene instance's, else its class's, else the basic colour nearest its rgb),
/// where it was first detected, resting on the support plane (its yaw about
/// the plane's normal; never below the plane); the table frame is the support
/// plane's (PerceptionResult::X_camera_table) moved to the centre of the
/// rectangle holding every object's footprint plus kPerceivedTableMargin_m; the
/// knowledge base's observed classes (ObjectClass::observed) the scene uses;
/// `cataloguePath` as given. nullopt when the result has no support plane.
std::optional<taskdb::PerceivedScene> perceivedSceneOf(const perception::PerceptionResult& seen,
                                                       const core::ObjectCatalogue& kb,
                                                       const std::optional<core::Scene>& scene,
                                                       const std::string& cataloguePath);

/// The perceived demo scene at the demo's start, for grounding: the cell of
/// perceivedSceneOf (CellDescription::fromScene of its scene). Throws
/// InvalidInputError when the result has no table frame.
execution::CellDescription perceivedScene(const perception::PerceptionResult& seen, const core::ObjectCatalogue& kb,
                                          const std::optional<core::Scene>& scene);

/// Stage 3b: every object phrase of the plan -> the perceived object it
/// means. A phrase of a class tracked as one instance is that instance (no
/// grounding needed, as before instances); a phrase of a class tracked per
/// instance is grounded by execution::SceneGrounder (colour, ordinal,
/// superlative, relation to a landmark; the step's source locations) in the
/// perceivedScene. Sets stepObjects, movingObjects, objectByWords. Throws
/// execution::GroundingError naming the candidates when a phrase fits none or
/// several instances ("two cuboids match 'the cuboid' ...; say which"), and
/// InvalidInputError when a moved instance is never detected.
GroundedPlan groundInstances(const GroundedPlan& grounded, const perception::PerceptionResult& seen,
                             const core::ObjectCatalogue& kb, const std::optional<core::Scene>& scene);

/// Stage 4: the hand-off from perception to motion, in memory. The samples
/// are the frames of the hand and of the moved objects' poses; time =
/// frame / frameRate_hz; an object's yaw is that of its pose's unit
/// quaternion (as the ProductPose row stores it, so `srp motion` re-learning
/// from the database sees the same inputs); a frame without a detection is a
/// sample with valid = false (position zero, the previous yaw). Tracks are
/// keyed and sorted by perception key (class name, or instance id); planOrder
/// = the step objects. An object's position is its pose applied to
/// p_object_tracked (MotionRows.h: the origin of a catalogue class, the
/// middle of the height of a class found in the demonstration).
motion::DemoTracks demoTracks(const perception::PerceptionResult& seen, const GroundedPlan& grounded,
                              double frameRate_hz);

/// Stage 4b, the honest check: what the demonstration lacks for the plan, one
/// line per step, naming the step: a step whose object never leaves its place
/// or has no grasp or no release (motion's segmentation, its note). Empty when
/// every step can be learned. A landmark of a step that is never seen (the
/// steps can still be learned, but the perceived scene lacks it) is appended
/// to `warnings`, once per landmark.
std::vector<std::string> stepProblems(const GroundedPlan& grounded, const perception::PerceptionResult& seen,
                                      const motion::Segmentation& segmentation, std::vector<std::string>& warnings);

/// Stage 5 (rows): the task model to store: the instruction's tables, the
/// perception rows (toTaskDbRows), the plan objects' class ids, instance ids
/// (Products.InstanceId: the instance each phrase was grounded to, "" for a
/// class's one instance) and locations, the Skills rows and the ProductPose
/// skill flags, the perceived scene (perceivedSceneOf, knowledge base
/// ProgrammingOptions::cataloguePath, else the bundled one) and the camera's
/// extrinsics (ProgrammingOptions::X_base_camera). Does not touch the database.
taskdb::TaskModel buildTaskModel(const GroundedPlan& grounded, const ProgrammingOptions& options,
                                 const perception::PerceptionResult& seen, const core::ObjectCatalogue& kb,
                                 const motion::DemoTracks& tracks, const std::vector<motion::SkillSet>& skills,
                                 const std::optional<core::Scene>& scene = std::nullopt);

/// Frame rate [Hz] of a recording from its timestamps (median frame period; 30 when unknown).
double frameRateOf(const core::PositionTrajectory& samples);

}  // namespace srp::programming
