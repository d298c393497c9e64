#include "srp/execution/RosTrajectoryExporter.h"

#include <cmath>
#include <fstream>
#include <iomanip>
#include <sstream>

#include "srp/core/Error.h"

namespace srp::execution {
namespace {

std::string list(const JointVector& v) {
  std::ostringstream o;
  o << std::fixed << std::setprecision(9) << "[";
  for (int i = 0; i < 6; ++i) o << (i ? ", " : "") << v[i];
  o << "]";
  return o.str();
}

/// builtin_interfaces/Duration of t >= 0: whole seconds and nanoseconds in [0, 1e9).
std::pair<long long, long long> duration(double t_s) {
  long long ns = std::llround(t_s * 1e9);
  return {ns / 1000000000LL, ns % 1000000000LL};
}

std::string quoted(const std::string& s) {  // YAML single-quoted scalar
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("''") : std::string(1, c);
  return q + "'";
}

}  // namespace

RosTrajectoryExporter::RosTrajectoryExporter(RosTrajectoryOptions options) : options_(std::move(options)) {
  if (!(options_.pointPeriod_s >= 0.0))
    throw srp::core::InvalidInputError("RosTrajectoryExporter: point period " + std::to_string(options_.pointPeriod_s) +
                                       " s must be >= 0 (0 = every knot)");
}

std::string RosTrajectoryExporter::toYaml(const ExecutedTask& task) const {
  task.requireExportable("ROS trajectory");
  const auto& samples = task.trajectory.samples();
  std::vector<std::size_t> kept;
  for (std::size_t i = 0; i < samples.size(); ++i)
    if (kept.empty() || i + 1 == samples.size() ||
        samples[i].t_s >= samples[kept.back()].t_s + options_.pointPeriod_s - 1e-9)
      kept.push_back(i);

  std::ostringstream s;
  s << std::fixed << std::setprecision(3);
  s << "# trajectory_msgs/msg/JointTrajectory written by srp execute: the simulated, safety-checked joint\n"
    << "# trajectory of task model " << task.taskModelId << " '" << task.taskName << "', " << kept.size()
    << " points, " << task.trajectory.duration_s() << " s.\n";
  if (!task.instruction.empty()) {
    std::string ins = task.instruction;
    for (char& c : ins)
      if (c == '\n') c = ' ';
    s << "# instruction: " << ins << "\n";
  }
  s << "# Move the arm to the first point first; then, e.g.:\n"
    << "#   ros2 topic pub --once --yaml-file <this file> " << options_.topic << " trajectory_msgs/msg/JointTrajectory\n"
    << "# Gripper (not in this message; e.g. ur_msgs/srv/SetIO on the tool output), simulated times:\n";
  for (const auto& e : task.gripperEvents)
    s << "#   t = " << e.t_s << " s: " << (e.kind == GripperEvent::Kind::Grasp ? "grasp" : "release") << " the "
      << e.part << "\n";
  s << "header:\n  stamp: {sec: 0, nanosec: 0}\n  frame_id: " << quoted(options_.frameId) << "\n";
  s << "joint_names: [";
  for (int j = 0; j < 6; ++j) s << (j ? ", " : "") << task.jointNames[j];
  s << "]\npoints:\n";
  for (std::size_t i : kept) {
    const auto& p = samples[i];
    const auto [sec, nsec] = duration(p.t_s);
    s << "- positions: " << list(p.q_rad) << "\n"
      << "  velocities: " << list(p.qd_radps) << "\n"
      << "  accelerations: []\n  effort: []\n"
      << "  time_from_start: {sec: " << sec << ", nanosec: " << nsec << "}\n";
  }
  return s.str();
}

void RosTrajectoryExporter::write(const ExecutedTask& task, const std::string& path) const {
  const std::string text = toYaml(task);
  std::ofstream out(path);
  if (!out) throw srp::core::FileError(path, "cannot write the ROS trajectory YAML");
  out << text;
  if (!out) throw srp::core::FileError(path, "writing the ROS trajectory YAML failed");
}

}  // namespace srp::execution
