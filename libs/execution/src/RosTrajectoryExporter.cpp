#include "srp/execution/RosTrajectoryExporter.h"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <cstdio>
#include <iomanip>
#include <sstream>

#include "srp/core/Error.h"
#include "srp/core/OutputFile.h"
#include "srp/core/SafeText.h"
#include "srp/execution/SafetyChecker.h"

namespace srp::execution {
namespace {

/// A number as the YAML scalar `-0.123456789` (fixed, 9 decimals: a float64 to the
/// reader, never an integer, never an exponent).
std::string fixed9(double v) {
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), "%.9f", v);
  return buffer;
}

void emitJoints(YAML::Emitter& out, const JointVector& v) {
  out << YAML::Flow << YAML::BeginSeq;
  for (int i = 0; i < 6; ++i) out << fixed9(v[i]);
  out << YAML::EndSeq;
}

/// A text value: yaml-cpp picks the style for printable ASCII, but writes a CR
/// unquoted in a flow sequence; anything else goes double-quoted, where every
/// control and non-ASCII character is an escape.
void emitText(YAML::Emitter& out, const std::string& text, YAML::EMITTER_MANIP style) {
  bool printable = true;
  for (char c : text) printable = printable && c >= 0x20 && c <= 0x7E;
  if (!printable) style = YAML::DoubleQuoted;
  if (style != YAML::Auto) out << style;
  out << text;
}

/// builtin_interfaces/Duration of t >= 0: whole seconds and nanoseconds in [0, 1e9).
std::pair<long long, long long> duration(double t_s) {
  long long ns = std::llround(t_s * 1e9);
  return {ns / 1000000000LL, ns % 1000000000LL};
}

std::string fmt3(double v) {
  std::ostringstream o;
  o << std::fixed << std::setprecision(3) << v;
  return o.str();
}

}  // namespace

RosTrajectoryExporter::RosTrajectoryExporter(Options options) : options_(std::move(options)) {
  if (!(options_.pointPeriod_s >= 0.0) || !std::isfinite(options_.pointPeriod_s))
    throw srp::core::InvalidInputError("RosTrajectoryExporter: point period " + std::to_string(options_.pointPeriod_s) +
                                       " s must be a finite number >= 0 (0 = every knot)");
  if (!(options_.maxThinningDeviation_rad > 0.0))
    throw srp::core::InvalidInputError("RosTrajectoryExporter: the thinning deviation bound " +
                                       std::to_string(options_.maxThinningDeviation_rad) + " rad must be > 0");
}

JointTrajectory RosTrajectoryExporter::exportedTrajectory(const ExecutedTask& task) const {
  const auto& samples = task.trajectory.samples();
  if (options_.pointPeriod_s <= 0.0 || samples.size() < 3) return task.trajectory;
  // Would the controller's cubic between knots i and j keep the checks? Positions and
  // speeds at every checked knot and half-way between them, within the deviation
  // bound of the checked trajectory; the spline's accelerations at both ends (where a
  // cubic's second derivative peaks) within the limit.
  const auto interval = [&](std::size_t i, std::size_t j) {
    const JointTrajectory piece = JointTrajectory::fromSamples({samples[i], samples[j]});
    if (SafetyChecker::peakSplineAcceleration_radps2(piece) > task.maxAcceleration_radps2 * (1.0 - 1e-6)) return false;
    for (std::size_t k = i; k < j; ++k)
      for (const double t : {samples[k].t_s, 0.5 * (samples[k].t_s + samples[k + 1].t_s)}) {
        const JointTrajectorySample a = piece.at(t - samples[i].t_s), b = task.trajectory.at(t);
        if ((a.q_rad - b.q_rad).cwiseAbs().maxCoeff() > options_.maxThinningDeviation_rad) return false;
        if ((a.qd_radps.cwiseAbs().array() > task.maxVelocity_radps.array()).any()) return false;
        if ((a.q_rad.array() < task.lower_rad.array()).any() || (a.q_rad.array() > task.upper_rad.array()).any())
          return false;
      }
    return true;
  };
  // Greedy: from each kept knot, the knot one period later, or the latest nearer one
  // whose interval passes (the next knot always does: that interval was checked).
  std::vector<JointTrajectorySample> kept = {samples.front()};
  for (std::size_t i = 0; i + 1 < samples.size();) {
    std::size_t j = i + 1;
    while (j + 1 < samples.size() && samples[j].t_s < samples[i].t_s + options_.pointPeriod_s - 1e-9) ++j;
    while (j > i + 1 && !interval(i, j)) --j;
    kept.push_back(samples[j]);
    i = j;
  }
  return JointTrajectory::fromSamples(std::move(kept));
}

double RosTrajectoryExporter::deviation_rad(const JointTrajectory& exported, const JointTrajectory& checked) {
  const auto& knots = checked.samples();
  double worst = 0.0;
  for (std::size_t k = 0; k < knots.size(); ++k) {
    const double t = knots[k].t_s;
    worst = std::max(worst, (exported.at(t).q_rad - knots[k].q_rad).cwiseAbs().maxCoeff());
    if (k + 1 < knots.size()) {
      const double mid = 0.5 * (t + knots[k + 1].t_s);
      worst = std::max(worst, (exported.at(mid).q_rad - checked.at(mid).q_rad).cwiseAbs().maxCoeff());
    }
  }
  return worst;
}

std::optional<std::string> RosTrajectoryExporter::checkThinned(const ExecutedTask& task,
                                                               const JointTrajectory& exported) const {
  const std::string period = "--ros-point-period " + fmt3(options_.pointPeriod_s) + " s";
  const auto& knots = exported.samples();
  for (std::size_t k = 0; k < knots.size(); ++k)
    for (int j = 0; j < 6; ++j) {
      const std::string at = " at t = " + fmt3(knots[k].t_s) + " s";
      if (knots[k].q_rad[j] < task.lower_rad[j] || knots[k].q_rad[j] > task.upper_rad[j])
        return period + " puts joint " + task.jointNames[j] + " outside its position limits" + at;
      const double v = SafetyChecker::jointSpeed_radps(exported, k, j);
      if (v > task.maxVelocity_radps[j] * (1.0 + 1e-9))
        return period + " moves joint " + task.jointNames[j] + " at " + fmt3(v) + " rad/s" + at +
               ", above its checked limit " + fmt3(task.maxVelocity_radps[j]) + " rad/s";
      const double a = SafetyChecker::splineAcceleration_radps2(exported, k, j);
      if (a > task.maxAcceleration_radps2 * (1.0 + 1e-9))
        return period + " accelerates joint " + task.jointNames[j] + " at " + fmt3(a) + " rad/s^2" + at +
               ", above its checked limit " + fmt3(task.maxAcceleration_radps2) + " rad/s^2";
    }
  const double off = deviation_rad(exported, task.trajectory);
  if (!(off <= options_.maxThinningDeviation_rad))
    return period + " leaves the checked trajectory by " + fmt3(off * 1000.0) + " mrad, above the allowed " +
           fmt3(options_.maxThinningDeviation_rad * 1000.0) + " mrad";
  return std::nullopt;
}

std::string RosTrajectoryExporter::toYaml(const ExecutedTask& task) const {
  task.requireExportable("ROS trajectory");
  const JointTrajectory exported = exportedTrajectory(task);
  if (options_.pointPeriod_s > 0.0)
    if (const auto why = checkThinned(task, exported))
      throw srp::core::InvalidInputError("no ROS trajectory written: " + *why +
                                         "; give a smaller --ros-point-period (0 keeps every checked knot)");
  const auto& points = exported.samples();
  using srp::core::exportSafeText;

  std::ostringstream comment;
  comment << "trajectory_msgs/msg/JointTrajectory written by srp execute: the simulated, safety-checked joint\n"
          << "trajectory of task model " << task.taskModelId << " '" << exportSafeText(task.taskName) << "', "
          << points.size() << " points, " << fmt3(task.trajectory.duration_s()) << " s.";
  if (options_.pointPeriod_s > 0.0)
    comment << "\nKnots at least " << fmt3(options_.pointPeriod_s) << " s apart; their spline is within "
            << fmt3(deviation_rad(exported, task.trajectory) * 1000.0) << " mrad of the checked trajectory.";
  if (!task.instruction.empty()) comment << "\ninstruction: " << exportSafeText(task.instruction);
  comment << "\ntrajectory id: " << task.trajectoryId() << " (the URScript program of the same execution has the same id)";
  comment << "\nMove the arm to the first point first; then, e.g.:\n"
          << "  ros2 topic pub --once --yaml-file <this file> " << exportSafeText(options_.topic)
          << " trajectory_msgs/msg/JointTrajectory\n"
          << "Gripper (not in this message; e.g. ur_msgs/srv/SetIO on the tool output), simulated times:";
  for (const auto& e : task.gripperEvents)
    comment << "\n  t = " << fmt3(e.t_s) << " s: " << (e.kind == GripperEvent::Kind::Grasp ? "grasp" : "release")
            << " the " << exportSafeText(e.part);

  YAML::Emitter out;
  out.SetOutputCharset(YAML::EscapeNonAscii);  // the file is ASCII, whatever a name holds
  out << YAML::Comment(comment.str());
  out << YAML::BeginMap;
  out << YAML::Key << "header" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "stamp" << YAML::Value << YAML::Flow << YAML::BeginMap << YAML::Key << "sec" << YAML::Value << 0
      << YAML::Key << "nanosec" << YAML::Value << 0 << YAML::EndMap;
  out << YAML::Key << "frame_id" << YAML::Value;
  emitText(out, options_.frameId, YAML::SingleQuoted);
  out << YAML::EndMap;
  out << YAML::Key << "joint_names" << YAML::Value << YAML::Flow << YAML::BeginSeq;
  for (int j = 0; j < 6; ++j) emitText(out, task.jointNames[j], YAML::Auto);
  out << YAML::EndSeq;
  out << YAML::Key << "points" << YAML::Value << YAML::BeginSeq;
  for (const auto& p : points) {
    if (!p.q_rad.allFinite() || !p.qd_radps.allFinite() || !std::isfinite(p.t_s))
      throw srp::core::InvalidInputError("no ROS trajectory written: a non-finite knot at t = " + fmt3(p.t_s) + " s");
    const auto [sec, nsec] = duration(p.t_s);
    out << YAML::BeginMap;
    out << YAML::Key << "positions" << YAML::Value;
    emitJoints(out, p.q_rad);
    out << YAML::Key << "velocities" << YAML::Value;
    emitJoints(out, p.qd_radps);
    out << YAML::Key << "accelerations" << YAML::Value << YAML::Flow << YAML::BeginSeq << YAML::EndSeq;
    out << YAML::Key << "effort" << YAML::Value << YAML::Flow << YAML::BeginSeq << YAML::EndSeq;
    out << YAML::Key << "time_from_start" << YAML::Value << YAML::Flow << YAML::BeginMap << YAML::Key << "sec"
        << YAML::Value << sec << YAML::Key << "nanosec" << YAML::Value << nsec << YAML::EndMap;
    out << YAML::EndMap;
  }
  out << YAML::EndSeq << YAML::EndMap;
  if (!out.good())
    throw srp::core::InvalidInputError("no ROS trajectory written: the YAML emitter failed (" + out.GetLastError() + ")");
  return std::string(out.c_str()) + "\n";
}

void RosTrajectoryExporter::write(const ExecutedTask& task, const std::string& path) const {
  srp::core::writeFileAtomically(path, toYaml(task));
}

}  // namespace srp::execution
