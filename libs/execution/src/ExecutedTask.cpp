#include "srp/execution/ExecutedTask.h"

#include <cstdint>
#include <cstdio>

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

std::string ExecutedTask::trajectoryId() const {
  std::uint64_t h = 1469598103934665603ull;  // FNV-1a, 64 bit
  const auto mix = [&h](const void* data, std::size_t n) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < n; ++i) h = (h ^ p[i]) * 1099511628211ull;
  };
  for (const auto& s : trajectory.samples()) {
    mix(&s.t_s, sizeof(s.t_s));
    mix(s.q_rad.data(), sizeof(double) * 6);
    mix(s.qd_radps.data(), sizeof(double) * 6);
  }
  for (const auto& e : gripperEvents) {
    const int kind = e.kind == GripperEvent::Kind::Grasp ? 1 : 2;
    mix(&kind, sizeof(kind));
    mix(&e.t_s, sizeof(e.t_s));
  }
  char text[17];
  std::snprintf(text, sizeof(text), "%016llx", static_cast<unsigned long long>(h));
  return text;
}

void ExecutedTask::requireExportable(const std::string& what) const {
  if (const auto why = whyNotExportable())
    throw srp::core::InvalidInputError("no " + what + " written: " + *why +
                                       " (fix the task or the scene so that every step passes the checks)");
}

}  // namespace srp::execution
