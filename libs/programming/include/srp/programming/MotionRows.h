#pragma once
/// \file MotionRows.h
/// \brief The mapping between a task model's rows (srp::taskdb) and the motion
/// module's types: hand/object tracks and plan order out of the rows
/// (`srp motion`), Skills rows and ProductPose flags in; and tracks into rows
/// (synthetic demos for examples and tests). PerceptionRows.h is the
/// perception side; motion itself knows no rows.

#include <map>
#include <string>
#include <vector>

#include "srp/core/ObjectCatalogue.h"
#include "srp/motion/LearnSkills.h"
#include "srp/motion/SkillSet.h"
#include "srp/taskdb/TaskDatabase.h"
#include "srp/taskdb/TaskModel.h"

namespace srp::programming {

/// What segmentation needs from a task model. Samples are the union of the
/// TimeIds of HandPositions and of the plan objects' ProductPose rows (frame =
/// TimeId, t = TimeId / frame rate); a TimeId without a row is "not detected".
/// Objects are named by their perception key (perceptionKey: the instance id,
/// else the class name), so two instances of one class are two objects.
/// `objects`: one per plan object with ProductPose rows (its ClassId and
/// InstanceId); `planOrder`: their names, TaskModelTargetObjects order.
struct MotionInputs : motion::DemoTracks {
  /// The rows of one object: (ClassId, InstanceId), InstanceId "" = its class's one instance.
  struct RowKey {
    int classId = 0;
    std::string instanceId;
  };
  std::map<std::string, RowKey> rowKeyByName;  ///< GroundedProducts, by perception key
};

/// The point of an object that motion follows, in its object frame: the
/// origin for a catalogue class; the middle of its height for a class seen
/// in the demonstration without a CAD file (core::ObjectClass::observed),
/// whose origin is the foot of its observed points, far below where the hand
/// holds a tall part (HRT1's toy: 19 cm; the segmenter takes a track point
/// 15 cm from the hand for a false detection). `observed`: the observed
/// classes of the task model (or perception result); `className` may be any.
Eigen::Vector3d p_object_tracked(const std::string& className, const std::vector<core::ObjectClass>& observed);

/// Throws InvalidInputError naming the object when a plan object is not
/// grounded (Products.ClassId missing) or the model has no hand positions.
/// A plan object without ProductPose rows has no track (Segmenter then
/// reports it).
MotionInputs motionInputsFromTaskModel(const taskdb::TaskModel& model);

/// Learns the skills of a task model held in memory (its hand positions and
/// plan objects' ProductPose rows; e.g. taskModelFromTracks) and sets
/// its Skills rows; the ProductPose flags are left as they are. Throws as
/// motionInputsFromTaskModel and learnSkills(DemoTracks) do.
motion::LearnedSkills learnSkills(taskdb::TaskModel& model);

/// Skills rows of the learned skill sets (TimeIds = the demo's frame numbers;
/// ClassId and InstanceId of the skill set's object, MotionInputs::rowKeyByName).
/// Throws InvalidInputError for a skill set of an object `inputs` does not name.
std::vector<taskdb::SkillRow> skillRows(const std::vector<motion::SkillSet>& skills, const MotionInputs& inputs);

/// Sets the Reach/Grasp/Move/Release flags of the ProductPose rows of each
/// skill set's object (its ClassId and InstanceId, MotionInputs::rowKeyByName;
/// Reach: reach start <= TimeId < grasp, Grasp: the grasp frame, Move:
/// between, Release: the release frame; other flags cleared). Rows of other
/// objects are left as they are.
void setSkillFlags(std::vector<taskdb::ProductPoseRow>& rows, const std::vector<motion::SkillSet>& skills,
                   const MotionInputs& inputs);

/// Stores learned skills in one transaction: replaces the task model's Skills
/// rows and sets the flags of the moved objects' ProductPose rows
/// (setSkillFlags). Throws InvalidInputError for an unknown task model; on
/// any error nothing changes.
void storeSkills(taskdb::TaskDatabase& db, int taskModelId, const std::vector<motion::SkillSet>& skills,
                 const MotionInputs& inputs);

/// A task model holding a demo's tracks (e.g. motion::SyntheticPickPlace): one
/// Product and GroundedProduct per track (ObjectId = ClassId = index), the
/// plan order as the plan, the tracks' poses (yaw about the camera z axis) and
/// the hand positions (invalid samples stored with Detected = false), frame
/// rate from the first two hand samples (30 Hz with fewer), no skills.
/// For examples and tests; motionInputsFromTaskModel reads it back.
taskdb::TaskModel taskModelFromTracks(const motion::DemoTracks& tracks, const std::string& name,
                                      const std::string& instruction);

}  // namespace srp::programming
