#pragma once
/// \file ExecutedTask.h
/// \brief What one simulated execution leaves for the exporters (UrScriptExporter,
/// RosTrajectoryExporter): the joint reference the controller was commanded (every
/// Reach/approach/lift/Move/lower/retreat trajectory the SafetyChecker passed, with
/// the holds between them), the grasp and release events on the same clock, the
/// report, and what an exported file's header names (task model, instruction, joint
/// names, the limits the trajectory was checked against).
///
/// Times are simulated seconds from the start of the execution (the arm at rest at
/// its home configuration at t = 0). Joint order and names are the URDF's, base to wrist.

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "srp/execution/CellSimulator.h"
#include "srp/execution/ExecutionReport.h"
#include "srp/execution/JointTrajectory.h"
#include "srp/execution/RobotModel.h"
#include "srp/execution/SafetyChecker.h"

namespace srp::execution {

struct ExecutedTask {
  std::string taskName;      ///< task model name ("thesis"), "" if unknown
  int taskModelId = 0;       ///< id in the task database, 0 if none
  std::string instruction;   ///< the instruction the plan came from
  std::string scene;         ///< scene file the cell came from
  std::array<std::string, 6> jointNames;  ///< URDF joint names, base to wrist
  JointVector lower_rad = JointVector::Zero();
  JointVector upper_rad = JointVector::Zero();
  /// The joint speeds the trajectory was checked against: URDF limit x velocityFraction.
  JointVector maxVelocity_radps = JointVector::Zero();
  double velocityFraction = 1.0;
  /// The joint acceleration the trajectory was checked against (SafetyLimits).
  double maxAcceleration_radps2 = 0.0;
  JointTrajectory trajectory;               ///< CellSimulator::commandedTrajectory()
  std::vector<GripperEvent> gripperEvents;  ///< CellSimulator::gripperEvents()
  ExecutionReport report;

  /// Collects the exporters' input after `report` was produced on `simulator`.
  static ExecutedTask fromSimulation(const RobotModel& model, const SafetyLimits& limits,
                                     const CellSimulator& simulator, ExecutionReport report);

  /// Why this execution must not be exported, or nullopt when it may be: a step
  /// refused (a safety check or the inverse kinematics said no: the arm did not do
  /// that step, and a program without it is not the task), a step failed in
  /// simulation (e.g. the grasp), or nothing was done. Skipped steps (the part was
  /// not in the scene) do not block; the exporters list them in the header.
  std::optional<std::string> whyNotExportable() const;

  /// 16 hex digits identifying the commanded trajectory and the gripper events
  /// (FNV-1a over their bytes): the URScript program and the ROS 2 YAML of one
  /// execution carry the same id in their headers, so a pair left by two different
  /// runs (a kill between the two renames of writeFilesTogether) can be told.
  std::string trajectoryId() const;

  /// Throws InvalidInputError with whyNotExportable() when there is a reason;
  /// `what` names the export in the message ("URScript").
  void requireExportable(const std::string& what) const;
};

}  // namespace srp::execution
