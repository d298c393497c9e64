#include "srp/motion/SkillSet.h"

#include "srp/core/Json.h"

namespace srp::motion {

std::vector<SkillRecord> skillRecords(const SkillSet& s) {
  using core::poseToJson;
  const auto axis = [](const Eigen::Vector3d& a) { return nlohmann::json{a.x(), a.y(), a.z()}; };
  std::vector<SkillRecord> out;
  out.push_back({s.objectName, core::SkillType::Reach, s.reachStartIndex, s.graspIndex,
                 {{"frame", s.frame},
                  {"dmp", s.reach ? s.reach->toJson() : nlohmann::json(nullptr)},
                  {"pre_grasp", poseToJson(s.X_frame_preGrasp)}}});
  out.push_back({s.objectName, core::SkillType::Grasp, s.graspIndex, s.graspIndex,
                 {{"frame", s.frame},
                  {"pose", poseToJson(s.X_frame_grasp)},
                  {"pre_grasp", poseToJson(s.X_frame_preGrasp)},
                  {"post_grasp", poseToJson(s.X_frame_preGrasp)},
                  {"approach_axis", axis(s.graspApproachAxis)},
                  {"approach_offset_m", s.approachOffset_m}}});
  out.push_back({s.objectName, core::SkillType::Move, s.graspIndex, s.releaseIndex,
                 {{"frame", s.frame},
                  {"dmp", s.move ? s.move->toJson() : nlohmann::json(nullptr)},
                  {"orientation_dmp", s.moveOrientation ? s.moveOrientation->toJson() : nlohmann::json(nullptr)},
                  {"post_grasp", poseToJson(s.X_frame_preGrasp)},
                  {"pre_release", poseToJson(s.X_frame_preRelease)}}});
  out.push_back({s.objectName, core::SkillType::Release, s.releaseIndex, s.releaseIndex,
                 {{"frame", s.frame},
                  {"pose", poseToJson(s.X_frame_release)},
                  {"pre_release", poseToJson(s.X_frame_preRelease)},
                  {"post_release", poseToJson(s.X_frame_preRelease)},
                  {"approach_axis", axis(s.releaseApproachAxis)},
                  {"approach_offset_m", s.approachOffset_m}}});
  return out;
}

}  // namespace srp::motion
