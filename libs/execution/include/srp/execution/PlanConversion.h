#pragma once
/// \file PlanConversion.h
/// \brief The one place where stored task models become execution plans.
///
/// From a task model (thesis Appendix C): the target objects in the order of
/// TaskModelTargetObjects (repeated mentions of one object merged), each with the
/// relations of its Products rows (SourceLocations / TargetLocations -> landmark
/// Products). "from" / "out of" relations are sources; every other relation is a
/// target (the thesis stores "next to the cuboid" as a source location of the star).
/// A location no product refers to (e.g. "in the gray box" of sentence 1) joins the
/// target object of its landmark's sentence. When the task model holds object poses
/// and X_world_camera is known, the demonstrated final offsets between neighbours
/// (rotated into the world frame) choose the side for "next to".

#include <optional>

#include "srp/core/Pose.h"
#include "srp/execution/ExecutionPlan.h"
#include "srp/taskdb/TaskModel.h"

namespace srp::execution {

/// Throws InvalidInputError when a row references a missing product or location.
ExecutionPlan planFromTaskModel(const srp::taskdb::TaskModel& model,
                                const std::optional<srp::core::Pose3>& X_world_camera = std::nullopt);

}  // namespace srp::execution
