#pragma once
/// \file TaskModelReport.h
/// \brief Human-readable views of a task model: the plan as a table, and the
/// thesis' Appendix C layout for side-by-side comparison.

#include <ostream>

#include "srp/taskdb/TaskModel.h"

namespace srp::taskdb {

/// One step of the plan as read back from the tables: consecutive
/// TaskModelTargetObjects entries that name the same object (the thesis
/// stores "the cuboid" and "it" as two products) are one step.
struct PlanStepView {
  std::vector<int> objectIds;
  std::string objectName;
  std::optional<std::string> colour;
  std::vector<std::string> sources;  ///< e.g. "from blue box"
  std::vector<std::string> targets;  ///< e.g. "in gray box"
};

std::vector<PlanStepView> planSteps(const TaskModel& model);

/// Header, plan table, grounded objects, skills and row counts.
void printTaskModel(const TaskModel& model, std::ostream& out);

/// Tables C.1-C.7 as tab-separated text, as printed in the thesis' Appendix C
/// (one ProductPose<Name> table per grounded product, Rz = yaw in radians,
/// skill flags as 1 or empty). maxRows > 0 abbreviates the long tables with "...".
void writeAppendixC(const TaskModel& model, std::ostream& out, int maxRows = 0);

}  // namespace srp::taskdb
