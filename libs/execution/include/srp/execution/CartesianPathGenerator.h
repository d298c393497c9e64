#pragma once
/// \file CartesianPathGenerator.h
/// \brief Interface of the planner's Cartesian path source for the Reach and Move
/// skills: the Motion Module's DMPs plug in here (DmpPathGenerator), and a
/// minimum-jerk generator serves when no demonstration is stored.
///
/// Poses are of the tool centre point in the world (table) frame; time in seconds
/// from the start of the path; the path starts and ends at rest.

#include <memory>
#include <vector>

#include "srp/core/Pose.h"
#include "srp/core/SkillType.h"

namespace srp::execution {

struct CartesianPathSample {
  double t_s = 0.0;
  srp::core::Pose3 X_world_tcp = srp::core::Pose3::Identity();
};

using CartesianPath = std::vector<CartesianPathSample>;

class CartesianPathGenerator {
 public:
  virtual ~CartesianPathGenerator() = default;

  /// Path of the tcp for `skill` (Reach or Move) of target object number `stepIndex`
  /// from X_world_start to X_world_goal, sampled every dt_s (first sample = start,
  /// last = goal exactly). Throws InvalidInputError for other skills.
  virtual CartesianPath generate(srp::core::SkillType skill, int stepIndex, const srp::core::Pose3& X_world_start,
                                 const srp::core::Pose3& X_world_goal, double dt_s) const = 0;

  /// Short name for reports ("minimum-jerk", "dmp").
  virtual std::string name() const = 0;
};

}  // namespace srp::execution
