#pragma once
/// \file ProgrammingStages.h
/// \brief The stages of programTask (ProgrammingPipeline.h), one function
/// each, in the order they run:
///
///   parsePlan (instruction -> plan) -> groundPlan (every object the plan
///   names -> a knowledge-base class, once) -> perceive (demonstration ->
///   hand and object trajectories) -> demoTracks (the in-memory hand-off to
///   motion) -> motion::learnSkills (segmentation + DMPs) -> buildTaskModel
///   (the task-database rows, made here and only here) -> TaskModelStore.
///
/// From the grounding to the rows an object is keyed by its knowledge-base
/// class name (motion's ObjectTrack::name, SkillSet::objectName); class ids
/// and the instruction's ObjectIds appear only in the rows.

#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "srp/core/ObjectCatalogue.h"
#include "srp/language/TaskPlan.h"
#include "srp/motion/LearnSkills.h"
#include "srp/perception/DemoPerception.h"
#include "srp/programming/ProgrammingPipeline.h"
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

  /// The class of an object of the plan. Throws InvalidInputError for an
  /// object the plan does not name.
  const std::string& classOf(const std::string& name, const std::optional<std::string>& colour) const;
};

/// Stage 2: grounds the plan's objects and landmarks, once. Throws
/// InvalidInputError naming the object and the classes the knowledge base
/// knows when one is unknown.
GroundedPlan groundPlan(const language::TaskPlan& plan, const core::ObjectCatalogue& kb);

/// Stage 3: the Environment module on the demonstration, guided by the plan
/// (step objects move, the other landmarks are static). Appends a warning
/// when a damaged rawlog is used with allowTruncated. Throws FileError for
/// an unreadable or empty rawlog, InvalidInputError when a moved object is
/// never detected.
perception::PerceptionResult perceive(const GroundedPlan& grounded, const core::ObjectCatalogue& kb,
                                      const ProgrammingOptions& options, std::vector<std::string>& warnings);

/// Stage 4: the hand-off from perception to motion, in memory. The samples
/// are the frames of the hand and of the moved objects' poses; time =
/// frame / frameRate_hz; an object's yaw is that of its pose's unit
/// quaternion (as the ProductPose row stores it, so `srp motion` re-learning
/// from the database sees the same inputs); a frame without a detection is a
/// sample with valid = false (position zero, the previous yaw). Tracks are
/// keyed and sorted by class name; planOrder = the step classes.
motion::DemoTracks demoTracks(const perception::PerceptionResult& seen, const GroundedPlan& grounded,
                              double frameRate_hz);

/// Stage 5 (rows): the task model to store: the instruction's tables, the
/// perception rows (toTaskDbRows), the plan objects' class ids and
/// locations, the Skills rows and the ProductPose skill flags. Does not
/// touch the database.
taskdb::TaskModel buildTaskModel(const GroundedPlan& grounded, const ProgrammingOptions& options,
                                 const perception::PerceptionResult& seen, const core::ObjectCatalogue& kb,
                                 const motion::DemoTracks& tracks, const std::vector<motion::SkillSet>& skills);

}  // namespace srp::programming
