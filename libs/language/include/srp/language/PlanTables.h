#pragma once
/// \file PlanTables.h
/// \brief TaskPlan <-> the instruction tables of the task database (thesis
/// Appendix C): Products, SourceLocations, TargetLocations, TaskModelTargetObjects.
///
/// Mapping: each step's object is a Product (TokenId/SentenceId of its first
/// mention) listed in TaskModelTargetObjects in step order; each landmark is a
/// Product of its own. The first source location is the object's
/// SourceLocation (TrajectorObjectId = the landmark, as the thesis names that
/// column), the first target location its TargetLocation (IndicatorObjectId =
/// the landmark). Further locations of a list qualify the previous landmark
/// ("next to the cuboid in the gray box": the cuboid is *in* the gray box) and
/// are stored as that landmark's SourceLocation, so the chain reads back in order.

#include <string>

#include "srp/language/TaskPlan.h"
#include "srp/taskdb/TaskModel.h"

namespace srp::language {

/// The rows of `plan` as a task model named `name` (info.instruction = `instruction`;
/// other tables empty, ids 0-based). Throws InvalidInputError for a plan with no steps.
taskdb::TaskModel planToTaskModel(const TaskPlan& plan, const std::string& name, const std::string& instruction);

/// The steps stored in a task model's instruction tables (inverse of
/// planToTaskModel for steps; anchors and sentences are not restored).
/// Throws InvalidInputError naming the dangling id when rows do not link up.
std::vector<PlanStep> planStepsFromTaskModel(const taskdb::TaskModel& model);

/// Writes the plan to the database at `dbPath` in one transaction and returns
/// the new TaskModelId. A plan with zero steps is not written: InvalidInputError
/// carrying the plan's warnings.
int storePlan(const TaskPlan& plan, const std::string& dbPath, const std::string& name, const std::string& instruction);

}  // namespace srp::language
