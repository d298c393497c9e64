#include "srp/execution/ExecutionReport.h"

#include <iomanip>
#include <nlohmann/json.hpp>
#include <sstream>

#include "srp/core/Json.h"

namespace srp::execution {

std::string toString(StepStatus s) {
  switch (s) {
    case StepStatus::Done: return "done";
    case StepStatus::Skipped: return "skipped";
    case StepStatus::Refused: return "refused";
    case StepStatus::Failed: return "failed";
  }
  return "unknown";
}

int ExecutionReport::done() const {
  int n = 0;
  for (const auto& s : steps) n += s.status == StepStatus::Done;
  return n;
}

bool ExecutionReport::allSucceeded() const {
  for (const auto& s : steps)
    if (s.status != StepStatus::Done || !s.relationsHold) return false;
  return !steps.empty();
}

srp::core::ExitCode ExecutionReport::exitCode() const {
  if (steps.empty()) return srp::core::ExitCode::Error;
  bool partial = false;
  for (const auto& s : steps) {
    if (s.status == StepStatus::Failed || (s.status == StepStatus::Done && !s.relationsHold))
      return srp::core::ExitCode::Error;
    partial = partial || s.status != StepStatus::Done;
  }
  return partial ? srp::core::ExitCode::Partial : srp::core::ExitCode::Done;
}

nlohmann::json ExecutionReport::toJson() const {
  nlohmann::json j;
  j["schema_version"] = 1;
  j["path_generator"] = pathGenerator;
  if (!scene.empty()) j["scene_source"] = scene;
  if (!robotBase.empty()) j["robot_base"] = robotBase;
  j["simulated_s"] = simulated_s;
  j["simulation_wall_s"] = simulationWall_s;
  j["min_table_clearance_m"] = minTableClearance_m;
  j["steps_done"] = done();
  j["all_succeeded"] = allSucceeded();
  j["steps"] = nlohmann::json::array();
  for (const auto& s : steps) {
    nlohmann::json js;
    js["index"] = s.index;
    js["object"] = s.object;
    js["status"] = toString(s.status);
    js["reason"] = s.reason;
    js["relation"] = s.relation;
    if (s.X_world_start) js["X_world_start"] = srp::core::poseToJson(*s.X_world_start);
    if (s.X_world_planned) js["X_world_planned"] = srp::core::poseToJson(*s.X_world_planned);
    if (s.X_world_final) js["X_world_final"] = srp::core::poseToJson(*s.X_world_final);
    if (s.status == StepStatus::Done) {
      js["placement_error_m"] = s.placementError_m;
      js["yaw_error_rad"] = s.yawError_rad;
      js["inside_container"] = s.insideContainer;
      js["neighbour_relation_holds"] = s.neighbourRelationHolds;
      js["relations_hold"] = s.relationsHold;
      js["relation_checks"] = nlohmann::json::array();
      for (const auto& c : s.relationChecks)
        js["relation_checks"].push_back({{"relation", c.relation}, {"landmarks", c.landmarks}, {"holds", c.holds},
                                         {"quantity", c.quantity}, {"value_m", c.value_m}, {"detail", c.detail}});
      js["min_table_clearance_m"] = s.minTableClearance_m;
      js["max_joint_error_rad"] = s.maxJointError_rad;
      js["slow_down"] = s.slowDown;
    }
    if (!s.pathSource.empty()) js["path_source"] = s.pathSource;
    js["planning_s"] = s.planning_s;
    js["simulated_s"] = s.simulated_s;
    j["steps"].push_back(js);
  }
  return j;
}

std::string ExecutionReport::toText() const {
  std::ostringstream o;
  o << std::fixed;
  if (!scene.empty()) o << "scene: " << scene << "\n";
  if (!robotBase.empty()) o << "robot base: " << robotBase << "\n";
  for (const auto& s : steps) {
    o << "step " << s.index + 1 << ": " << s.object << " -> " << s.relation << ": " << toString(s.status);
    if (s.status == StepStatus::Done) {
      o << std::setprecision(2) << " (placed " << s.placementError_m * 1000 << " mm from plan, "
        << (s.relationsHold ? "relations hold" : "RELATION NOT MET") << ", " << s.pathSource << " paths, planning " << std::setprecision(1)
        << s.planning_s * 1000 << " ms, " << std::setprecision(2) << s.simulated_s << " s simulated)";
    } else {
      o << ": " << s.reason;
    }
    o << "\n";
    for (const auto& c : s.relationChecks)
      o << "  " << c.relation << " " << c.landmarks << ": " << (c.holds ? "holds" : "DOES NOT HOLD") << " ("
        << c.detail << ")\n";
  }
  o << std::setprecision(2) << done() << "/" << steps.size() << " steps done, " << simulated_s
    << " s simulated in " << simulationWall_s << " s (" << std::setprecision(1)
    << (simulationWall_s > 0 ? simulated_s / simulationWall_s : 0.0) << "x real time), path generator "
    << pathGenerator << ", closest arm-table approach " << std::setprecision(1) << minTableClearance_m * 1000
    << " mm\n";
  return o.str();
}

}  // namespace srp::execution
