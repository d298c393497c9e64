#pragma once
/// \file ExecutionSession.h
/// \brief One `srp execute` run as a library call: stored task model + current
/// scene -> plan -> simulated UR5 execution -> report, joint log and frames.
///
/// The database is opened read-only: executing never changes a task model.

#include <functional>
#include <optional>
#include <string>

#include "srp/core/Scene.h"
#include "srp/execution/ExecutionPlan.h"
#include "srp/execution/ExecutedTask.h"
#include "srp/execution/ExecutionReport.h"
#include "srp/execution/TaskExecutor.h"

namespace srp::execution {

struct ExecuteRequest {
  std::string databasePath;
  int taskModelId = 0;
  /// Scene JSON; "" = the scene of the task model's own demonstration (its
  /// perceived scene, DemonstrationScene.h), or sim/scenes/default.json for a
  /// task model that stores none (programmed by an older srp).
  std::string scenePath;
  /// Camera-to-robot extrinsics, the demonstration camera's pose in the robot
  /// base (`srp calibrate extrinsics` / `hand-eye`, read by `srp execute
  /// --extrinsics`); nullopt = the task model's X_base_camera, else (own scene)
  /// the default robot placement or (scene file) the scene's camera.
  std::optional<srp::core::Pose3> X_base_camera;
  std::string extrinsicsSource;  ///< names X_base_camera in the report (its file)
  /// Knowledge base of the own scene's catalogue classes; "" = the one the task
  /// model was programmed with (PerceivedScene::catalogue).
  std::string cataloguePath;
  std::string outputFolder;  ///< "" = write nothing
  int framePeriod = 10;      ///< render every n-th logged snapshot (0 = no frames)
  bool drawSafetySpheres = false;  ///< frames: overlay the safety checker's arm spheres
  /// A new instruction: parsed by the Language Module (with the stored plan as the
  /// known steps, for "back to" and "only the star"), it replaces the stored plan.
  std::string instruction;
  /// Replaces the stored plan directly (tests, tools).
  std::optional<ExecutionPlan> planOverride;
  TaskExecutor::Options options;
  std::function<void(const std::string&)> progress;  ///< one line per step, may be empty
};

struct ExecuteResult {
  ExecutionPlan plan;
  ExecutionReport report;
  /// The commanded trajectory, gripper events and report for the exporters
  /// (UrScriptExporter, RosTrajectoryExporter).
  ExecutedTask executed;
  std::vector<std::string> writtenFiles;
};

/// Throws FileError / InvalidInputError for a missing database, an unknown task id,
/// a bad scene; expected outcomes (missing part, unreachable pose) are in the report.
ExecuteResult executeTask(const ExecuteRequest& request);

/// `before` with every object at its pose in `perceived` (the simulated cell after
/// execution): what `srp execute --out DIR` writes as DIR/final_scene.json, so the
/// next run (e.g. a reversal) starts from the scene this one left.
srp::core::Scene sceneAfter(const srp::core::Scene& before, const CellDescription& perceived);

/// The tcp pose the arm starts from: 0.3 m above the middle of the containers
/// (the table centre when there are none), tool pointing down.
srp::core::Pose3 defaultHomeTcp(const CellDescription& cell);

}  // namespace srp::execution
