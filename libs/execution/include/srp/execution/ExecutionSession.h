#pragma once
/// \file ExecutionSession.h
/// \brief One `srp execute` run as a library call: stored task model + current
/// scene -> plan -> simulated UR5 execution -> report, joint log and frames.
///
/// The database is opened read-only: executing never changes a task model.

#include <functional>
#include <optional>
#include <string>

#include "srp/execution/ExecutionPlan.h"
#include "srp/execution/ExecutionReport.h"
#include "srp/execution/TaskExecutor.h"

namespace srp::execution {

struct ExecuteRequest {
  std::string databasePath;
  int taskModelId = 0;
  std::string scenePath;     ///< scene JSON; "" = sim/scenes/default.json
  std::string outputFolder;  ///< "" = write nothing
  int framePeriod = 10;      ///< render every n-th logged snapshot (0 = no frames)
  /// Replaces the stored plan (e.g. a new instruction parsed by the Language Module).
  std::optional<ExecutionPlan> planOverride;
  ExecutionOptions options;
  std::function<void(const std::string&)> progress;  ///< one line per step, may be empty
};

struct ExecuteResult {
  ExecutionPlan plan;
  ExecutionReport report;
  std::vector<std::string> writtenFiles;
};

/// Throws FileError / InvalidInputError for a missing database, an unknown task id,
/// a bad scene; expected outcomes (missing part, unreachable pose) are in the report.
ExecuteResult executeTask(const ExecuteRequest& request);

/// The tcp pose the arm starts from: 0.3 m above the middle of the containers
/// (the table centre when there are none), tool pointing down.
srp::core::Pose3 defaultHomeTcp(const CellDescription& cell);

}  // namespace srp::execution
