#pragma once
/// \file TaskModelMapping.h
/// \brief The mapping between a stored task model (srp::taskdb rows) and the
/// motion module's types: trajectories and plan order in, Skills rows out.

#include <map>
#include <string>
#include <vector>

#include "srp/motion/LearnSkills.h"
#include "srp/motion/Segmenter.h"
#include "srp/motion/SyntheticPickPlace.h"
#include "srp/motion/SkillSet.h"
#include "srp/taskdb/TaskDatabase.h"
#include "srp/taskdb/TaskModel.h"

namespace srp::motion {

/// What segmentation needs from a task model. Samples are the union of the
/// TimeIds of HandPositions and of the plan objects' ProductPose rows (frame =
/// TimeId, t = TimeId / frame rate); a TimeId without a row is "not detected".
/// `objects`: one per plan object with ProductPose rows; `planOrder`: grounded
/// object names, TaskModelTargetObjects order.
struct MotionInputs : DemoTracks {
  std::map<std::string, int> classIdByName;  ///< GroundedProducts
};

/// Throws InvalidInputError naming the object when a plan object is not
/// grounded (Products.ClassId missing) or the model has no hand positions.
/// A plan object without ProductPose rows has no track (Segmenter then
/// reports it).
MotionInputs motionInputsFromTaskModel(const taskdb::TaskModel& model);

/// Learns the skills of a task model held in memory (its hand positions and
/// plan objects' ProductPose rows; e.g. taskModelFromSyntheticDemo) and sets
/// its Skills rows; the ProductPose flags are left as they are. Throws as
/// motionInputsFromTaskModel and learnSkills(DemoTracks) do.
LearnedSkills learnSkills(taskdb::TaskModel& model);

/// Skills rows of the learned skill sets (TimeIds = the demo's frame numbers).
std::vector<taskdb::SkillRow> skillRows(const std::vector<SkillSet>& skills, const MotionInputs& inputs);

/// Sets the Reach/Grasp/Move/Release flags of one ProductPose row of the
/// skill set's object (Reach: reach start <= TimeId < grasp, Grasp: the grasp
/// frame, Move: between, Release: the release frame; other flags cleared).
/// Returns true when a flag changed.
bool setSkillFlags(taskdb::ProductPoseRow& row, const SkillSet& skills);

/// Stores learned skills in one transaction: replaces the task model's Skills
/// rows and sets the Reach/Grasp/Move/Release flags of the moved objects'
/// ProductPose rows (Reach: reach start <= TimeId < grasp, Grasp: the grasp
/// frame, Move: between, Release: the release frame; other flags cleared).
/// Throws InvalidInputError for an unknown task model; on any error nothing changes.
void storeSkills(taskdb::TaskDatabase& db, int taskModelId, const std::vector<SkillSet>& skills,
                 const MotionInputs& inputs);

/// A task model holding a synthetic demo (SyntheticPickPlaceGenerator): one
/// Product and GroundedProduct per object (ObjectId = ClassId = index), the
/// moved objects as the plan, their poses and the hand positions (undetected
/// samples stored with Detected = false), no skills. For examples and tests.
taskdb::TaskModel taskModelFromSyntheticDemo(const SyntheticPickPlace& demo, const std::string& name);

}  // namespace srp::motion
