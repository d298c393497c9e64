#pragma once
/// \file ExecutionReport.h
/// \brief What happened in each step of an execution: done / skipped / refused /
/// failed with the reason, the planned and reached object poses, placement
/// errors, relation checks, timing. Serialised as JSON and as readable text.

#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>
#include <vector>

#include "srp/core/ExitCode.h"
#include "srp/core/Pose.h"

namespace srp::execution {

enum class StepStatus { Done, Skipped, Refused, Failed };
std::string toString(StepStatus s);

/// One target relation verified on the scene after the placement.
struct RelationCheck {
  std::string relation;   ///< as in the plan ("left of", "between", "on top of")
  std::string landmarks;  ///< scene names ("star", "star and octagon")
  bool holds = false;
  std::string quantity;   ///< what was measured ("gap", "height above support", ...)
  double value_m = 0.0;   ///< its value
  std::string detail;     ///< readable summary of the measurement
  /// How far inside the relation's limits the measurement is [m] (the smallest of its
  /// conditions' margins; negative: by how much it is violated). Not serialised.
  double slack_m = 0.0;
};

struct StepReport {
  int index = 0;            ///< 0-based position in the plan
  std::string object;       ///< scene name of the part (or the instruction's name if not found)
  StepStatus status = StepStatus::Skipped;
  std::string reason;       ///< for every status but Done
  std::string relation;     ///< the target relations as text ("next to star, in gray box")
  std::optional<srp::core::Pose3> X_world_start;    ///< where the part was
  std::optional<srp::core::Pose3> X_world_planned;  ///< where it was to go
  std::optional<srp::core::Pose3> X_world_final;    ///< where it came to rest
  double placementError_m = 0.0;  ///< |final - planned| (translation)
  double yawError_rad = 0.0;
  bool insideContainer = false;   ///< final pose inside the target container (when one is named)
  bool neighbourRelationHolds = false;  ///< footprints within the neighbour gap + tolerance
  bool relationsHold = false;     ///< every target relation verified on the final pose
  /// Each target relation checked on the scene after the placement (PlacementPlanner::check).
  std::vector<RelationCheck> relationChecks;
  /// Where the Reach and Move paths came from: "dmp" (the task model's learned
  /// skills), "minimum-jerk" (no learned skill for this part), or
  /// "Reach dmp, Move minimum-jerk" when they differ. Empty when not planned.
  std::string pathSource;
  double planning_s = 0.0;        ///< wall-clock planning time (placement, paths, IK, safety)
  double simulated_s = 0.0;       ///< simulated duration of the step
  double minTableClearance_m = 0.0;  ///< smallest arm-table gap during the step
  double maxJointError_rad = 0.0;    ///< largest joint tracking error during the step
  double slowDown = 1.0;             ///< largest local slow-down of the step's paths: the most a knot interval is stretched in time (1: as planned; PathRetimer)
};

struct ExecutionReport {
  std::string pathGenerator;  ///< "minimum-jerk" or "dmp"
  /// The scene and the robot base when they were not given as a scene file
  /// (the task model's own demonstration; the extrinsics or the default
  /// placement); empty otherwise. Printed first by toText().
  std::string scene;
  std::string robotBase;
  std::vector<StepReport> steps;
  double simulated_s = 0.0;
  double simulationWall_s = 0.0;  ///< wall-clock time spent integrating
  double minTableClearance_m = 0.0;
  int done() const;
  /// True when every step is Done and its relations hold.
  bool allSucceeded() const;
  /// How `srp execute` ends (srp/core/ExitCode.h): Done when allSucceeded(); Error when
  /// a step failed in simulation or its relations do not hold after the placement;
  /// Partial when the others are done but steps were skipped or refused (nothing moved
  /// in those); Error for a report without steps.
  srp::core::ExitCode exitCode() const;
  nlohmann::json toJson() const;
  std::string toText() const;
};

}  // namespace srp::execution
