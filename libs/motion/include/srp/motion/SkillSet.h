#pragma once
/// \file SkillSet.h
/// \brief The skills of one pick & place step (thesis table 6.1, ch. 6.4.2):
/// Reach (hand from the previous release to the grasp, a DMP), Grasp (event
/// and poses), Move (grasp to release, a position DMP plus the object's
/// orientation as a quaternion DMP), Release (event and poses).
///
/// Poses are in the demo's frame (`frame`, e.g. "camera"), metres.
/// Pre-grasp = post-grasp = P(t_g) - dp a_g and pre-release = post-release =
/// P(t_r) - dp a_r, with a the unit approach axis (the direction the hand
/// moves in to reach the pose) and dp = 2 cm; orientation Rz(yaw of the object)
/// at the grasp/release (thesis eq. after fig. 6.9).

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "srp/core/Pose.h"
#include "srp/core/SkillType.h"
#include "srp/motion/Dmp.h"
#include "srp/motion/QuaternionDmp.h"

namespace srp::motion {

struct SkillSet {
  std::string objectName;
  std::string frame = "camera";
  int reachStartIndex = 0, graspIndex = 0, releaseIndex = 0;  ///< sample indices of the demo
  int reachStartFrame = 0, graspFrame = 0, releaseFrame = 0;  ///< their frame numbers
  core::Pose3 X_frame_grasp = core::Pose3::Identity();        ///< hand at the grasp, object's orientation
  core::Pose3 X_frame_preGrasp = core::Pose3::Identity();     ///< = post-grasp
  core::Pose3 X_frame_release = core::Pose3::Identity();
  core::Pose3 X_frame_preRelease = core::Pose3::Identity();   ///< = post-release
  Eigen::Vector3d graspApproachAxis = Eigen::Vector3d::UnitZ();    ///< unit, in `frame`
  Eigen::Vector3d releaseApproachAxis = Eigen::Vector3d::UnitZ();
  double approachOffset_m = 0.02;
  std::optional<Dmp> reach;                  ///< hand path reach start -> grasp
  std::optional<Dmp> move;                   ///< hand path grasp -> release
  std::optional<QuaternionDmp> moveOrientation;  ///< object orientation grasp -> release (when yaw is known)
};

/// One row of the task database's Skills table, before object names and
/// sample indices are mapped to its ids.
struct SkillRecord {
  std::string objectName;
  core::SkillType skill = core::SkillType::Reach;
  int startIndex = 0, endIndex = 0;  ///< sample indices (inclusive)
  nlohmann::json parameters;         ///< DMP JSON and poses; see skillRecords()
};

/// Reach, Grasp, Move, Release records of a skill set. Parameters:
/// Reach {"frame", "dmp", "pre_grasp"}; Grasp {"frame", "pose", "pre_grasp",
/// "post_grasp", "approach_axis", "approach_offset_m"}; Move {"frame", "dmp",
/// "orientation_dmp" (or null), "post_grasp", "pre_release"}; Release like Grasp.
std::vector<SkillRecord> skillRecords(const SkillSet& skills);

}  // namespace srp::motion
