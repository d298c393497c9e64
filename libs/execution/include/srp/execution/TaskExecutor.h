#pragma once
/// \file TaskExecutor.h
/// \brief The task planner of thesis fig. 7.11 running on the simulated cell.
///
/// Before anything moves, the placements of all steps are planned together
/// (JointPlacementPlanner): a step no joint plan can satisfy is skipped with the reason,
/// the others keep room for each other. Then for each target object in plan order:
/// perceive the current scene (the cell's ground truth), find the object and its source
/// location; take its planned target pose (planned again, for the remaining steps
/// together, if the scene no longer allows it); if any is missing the step is skipped
/// with the reason. Otherwise plan, then execute:
///   Reach (path generator, current tcp pose -> pre-grasp = grasp + approach offset
///   along world z), approach down, Grasp (weld), lift to post-grasp, Move (path
///   generator, post-grasp -> pre-release), lower, Release, retreat up.
/// The whole step is planned (IK, nearest branch) and checked by the SafetyChecker
/// before the arm moves; a violation refuses the step and the arm stays put.

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "srp/execution/CartesianPathGenerator.h"
#include "srp/execution/CellSimulator.h"
#include "srp/execution/ExecutionPlan.h"
#include "srp/execution/ExecutionReport.h"
#include "srp/execution/JointPlacementPlanner.h"
#include "srp/execution/PlacementPlanner.h"
#include "srp/execution/SafetyChecker.h"
#include "srp/execution/UrInverseKinematics.h"

namespace srp::execution {

class TaskExecutor {
 public:
  struct Options {
    double approachOffset_m = 0.02;  ///< pre-/post-grasp and -release offset (thesis: 2 cm)
    double releaseHeight_m = 0.003;  ///< part bottom above its support when released
    double retreat_m = 0.06;         ///< tool lift after release
    double sampleTime_s = 0.01;      ///< Cartesian path and joint trajectory sampling
    double settle_s = 0.15;          ///< hold time after each segment
    /// A path whose joint speeds or accelerations exceed the limits (a learned DMP is as
    /// fast as the demonstrator, which near a wrist singularity can be too fast for the
    /// arm) is followed more slowly where it is too fast (PathRetimer: the same knots,
    /// later, only along the stretches where a limit binds), if slowing the whole segment
    /// by one factor k = max(speed ratio / velocityMargin, sqrt(acceleration ratio /
    /// accelerationMargin)) would need at most this k; beyond it (an IK branch jump, a
    /// singularity) the step is refused.
    double maxSlowDown = 4.0;
    double velocityMargin = 0.95;         ///< a slowed path peaks at this fraction of the speed limit
    double accelerationMargin = 0.95;     ///< and at this fraction of the acceleration limit
    double placementTolerance_m = 0.01;   ///< "within 1 cm of the planned pose"
    double neighbourTolerance_m = 0.015;  ///< extra gap allowed for "next to"
    SafetyLimits safety;
    PlacementContext::Options placement;
    JointPlacementPlanner::Options jointPlacement;  ///< the search over all steps' placements
    CellSimulator::Options simulation;
  };

  /// The arm starts at rest at q_home. `generator` provides the Reach/Move paths.
  TaskExecutor(const RobotModel& model, const CellDescription& scene, const JointVector& q_home,
               std::shared_ptr<const CartesianPathGenerator> generator, Options options);
  TaskExecutor(const RobotModel& model, const CellDescription& scene, const JointVector& q_home,
               std::shared_ptr<const CartesianPathGenerator> generator)
      : TaskExecutor(model, scene, q_home, std::move(generator), Options{}) {}
  ~TaskExecutor();

  /// Plans every step's placement together, then runs the plan step by step; never
  /// throws for expected outcomes (a missing part, an unreachable pose, no room): those
  /// are reported per step. `onStep` (may be empty) is called after each step. A step's
  /// planning_s includes its share of the joint placement planning.
  ExecutionReport run(const ExecutionPlan& plan, const std::function<void(const StepReport&)>& onStep = {});

  /// The scene as perceived now: parts at their simulated poses.
  CellDescription perceive() const;

  const CellSimulator& simulator() const { return *sim_; }
  CellSimulator& simulator() { return *sim_; }
  /// Writes the simulated joint log (every CellSimulator::Options::logPeriod_s): time,
  /// measured and reference joint positions. Throws FileError.
  void writeJointLogCsv(const std::string& path) const;

  /// A comfortable start configuration above the table for a base at X_world_base
  /// (tool pointing down, 0.35 m in front of the base).
  static JointVector defaultHome(const RobotModel& model, const srp::core::Pose3& X_world_base,
                                 const srp::core::Pose3& X_world_target);

 private:
  struct Segment;
  /// One step of fig. 7.11: perceive, find, place (`planned[index]`, planned again with
  /// the remaining steps when the scene no longer allows it), plan, execute, check.
  StepReport runStep(std::size_t index, const ExecutionPlan& plan, std::vector<PlannedPlacement>& planned);
  /// Plans the six segments (Reach, approach, lift, Move, lower, retreat) for both
  /// suction turns and keeps the better; the reason when neither is feasible.
  std::optional<std::string> planMotion(const CellDescription& scene, const CellObject& part,
                                        const srp::core::Pose3& X_world_target, std::vector<Segment>& segments) const;
  std::optional<std::string> planVariant(const CellDescription& scene, const CellObject& part,
                                         const srp::core::Pose3& X_world_target, double turn_rad,
                                         std::vector<Segment>& segments) const;
  /// Tracks the segments on the simulator with grasp and release; the reason of a failed grasp.
  std::optional<std::string> executeSegments(const std::string& part, const std::vector<Segment>& segments,
                                             StepReport& r);
  /// Fills the final pose and relation checks of `r`; "" when the relations hold, else
  /// which check failed and by how much.
  std::string checkOutcome(const CellDescription& scene, const CellObject& part, const ExecutionStep& step,
                    const Placement& placement,
                    StepReport& r) const;
  RobotModel model_;
  UrInverseKinematics ik_;
  CellDescription scene_;
  std::shared_ptr<const CartesianPathGenerator> generator_;
  Options options_;
  SafetyChecker safety_;
  PlacementPlanner placement_;
  JointPlacementPlanner jointPlacement_;
  std::unique_ptr<CellSimulator> sim_;
};

}  // namespace srp::execution
