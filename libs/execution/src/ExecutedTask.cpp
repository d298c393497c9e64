#include "srp/execution/ExecutedTask.h"

#include "srp/core/Error.h"

namespace srp::execution {

ExecutedTask ExecutedTask::fromSimulation(const RobotModel& model, const SafetyLimits& limits,
                                          const CellSimulator& simulator, ExecutionReport report) {
  ExecutedTask t;
  for (int i = 0; i < 6; ++i) t.jointNames[i] = model.joints()[i].name;
  t.lower_rad = model.lowerLimits_rad();
  t.upper_rad = model.upperLimits_rad();
  t.velocityFraction = limits.velocityFraction;
  t.maxVelocity_radps = model.maxVelocities_radps() * limits.velocityFraction;
  t.maxAcceleration_radps2 = limits.maxAcceleration_radps2;
  t.trajectory = simulator.commandedTrajectory();
  t.gripperEvents = simulator.gripperEvents();
  t.report = std::move(report);
  return t;
}

std::optional<std::string> ExecutedTask::whyNotExportable() const {
  for (const auto& s : report.steps) {
    const std::string step = "step " + std::to_string(s.index + 1) + " (" + s.object + " -> " + s.relation + ")";
    if (s.status == StepStatus::Refused) return step + " was refused before the arm moved: " + s.reason;
    if (s.status == StepStatus::Failed) return step + " failed in simulation: " + s.reason;
  }
  if (report.done() == 0) return std::string("no step was done, there is no motion to export");
  if (trajectory.empty()) return std::string("no commanded trajectory was recorded");
  return std::nullopt;
}

void ExecutedTask::requireExportable(const std::string& what) const {
  if (const auto why = whyNotExportable())
    throw srp::core::InvalidInputError("no " + what + " written: " + *why +
                                       " (fix the task or the scene so that every step passes the checks)");
}

}  // namespace srp::execution
