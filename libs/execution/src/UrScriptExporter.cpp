#include "srp/execution/UrScriptExporter.h"

#include <cctype>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "srp/core/Error.h"
#include "srp/core/OutputFile.h"
#include "srp/core/SafeText.h"

namespace srp::execution {
namespace {

std::string jointList(const JointVector& q, int decimals) {
  std::ostringstream o;
  o << std::fixed << std::setprecision(decimals) << "[";
  for (int i = 0; i < 6; ++i) o << (i ? ", " : "") << q[i];
  o << "]";
  return o.str();
}

/// Text from a user or a file inside a comment: printable ASCII only (core/SafeText.h).
std::string oneLine(const std::string& s) { return srp::core::exportSafeText(s); }

bool isIdentifier(const std::string& name) {
  if (name.empty() || name.size() > 64 || !std::isalpha(static_cast<unsigned char>(name[0]))) return false;
  for (char c : name)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_') return false;
  return true;
}

}  // namespace

UrScriptExporter::UrScriptExporter(Options options) : options_(std::move(options)) {
  const auto& o = options_;
  auto bad = [](const std::string& what) { throw srp::core::InvalidInputError("UrScriptExporter: " + what); };
  if (o.gripperDigitalOut < 0 || o.gripperDigitalOut > 1)
    bad("gripper tool digital output " + std::to_string(o.gripperDigitalOut) +
        " does not exist; UR tool flanges have outputs 0 and 1");
  if (!(o.gripperWait_s >= 0.0) || o.gripperWait_s > 10.0)
    bad("gripper wait " + std::to_string(o.gripperWait_s) + " s must be within 0-10 s");
  if (!(o.servoPeriod_s >= 0.002 && o.servoPeriod_s <= 0.1))
    bad("servo period " + std::to_string(o.servoPeriod_s) + " s must be within 0.002-0.1 s (0.008 = 125 Hz)");
  if (!(o.servoLookahead_s >= 0.03 && o.servoLookahead_s <= 0.2))
    bad("servoj lookahead " + std::to_string(o.servoLookahead_s) + " s must be within 0.03-0.2 s (UR's range)");
  if (!(o.servoGain >= 100.0 && o.servoGain <= 2000.0))
    bad("servoj gain " + std::to_string(o.servoGain) + " must be within 100-2000 (UR's range)");
  if (!(o.preambleSpeed_radps > 0.0 && o.preambleSpeed_radps <= 1.0) || !(o.preambleAcceleration_radps2 > 0.0) ||
      !(o.stopDeceleration_radps2 > 0.0))
    bad("preamble speed must be within (0, 1] rad/s and the accelerations positive");
  if (!isIdentifier(o.programName))
    bad("program name '" + oneLine(o.programName) +
        "' must be a URScript identifier: a letter, then up to 63 letters, digits or '_'");
}

std::string UrScriptExporter::toScript(const ExecutedTask& task) const {
  task.requireExportable("URScript");
  const auto& o = options_;
  const JointTrajectory& tr = task.trajectory;
  const double T = o.servoPeriod_s;
  const int ticks = static_cast<int>(std::ceil(tr.duration_s() / T - 1e-9)) + 1;

  // Resample on the global 8 ms grid and verify what is written against the limits.
  std::vector<JointVector> q(ticks);
  for (int k = 0; k < ticks; ++k) q[k] = tr.at(k * T).q_rad;
  double peakSpeed = 0.0, peakAcc = 0.0;
  int peakSpeedJoint = 0;
  for (int k = 0; k < ticks; ++k) {
    if (!q[k].allFinite())
      throw srp::core::InvalidInputError("UrScriptExporter: tick " + std::to_string(k) + " holds a non-finite joint position");
    for (int j = 0; j < 6; ++j) {
      if (q[k][j] < task.lower_rad[j] || q[k][j] > task.upper_rad[j])
        throw srp::core::InvalidInputError("UrScriptExporter: tick " + std::to_string(k) + " puts " +
                                           oneLine(task.jointNames[j]) + " outside its position limits");
      if (k == 0) continue;
      const double v = std::abs(q[k][j] - q[k - 1][j]) / T;
      if (v > task.maxVelocity_radps[j] * (1.0 + 1e-9))
        throw srp::core::InvalidInputError("UrScriptExporter: tick " + std::to_string(k) + " moves " +
                                           oneLine(task.jointNames[j]) + " at " + std::to_string(v) +
                                           " rad/s, above its checked limit " +
                                           std::to_string(task.maxVelocity_radps[j]) + " rad/s");
      if (v > peakSpeed) peakSpeed = v, peakSpeedJoint = j;
      if (k + 1 < ticks) peakAcc = std::max(peakAcc, std::abs(q[k + 1][j] - 2 * q[k][j] + q[k - 1][j]) / (T * T));
    }
  }

  std::ostringstream s;
  s << std::fixed << std::setprecision(3);
  // The header is inside the def: a controller reading the program from port 30002
  // runs a script as one program only when it starts with `def`.
  s << "def " << o.programName << "():\n";
  s << "# " << o.programName << ": URScript written by srp execute (semantic robot programming)\n";
  s << "# task model: " << (task.taskModelId ? std::to_string(task.taskModelId) : std::string("-")) << " '"
    << oneLine(task.taskName) << "'\n";
  s << "# instruction: " << (task.instruction.empty() ? "(the stored plan)" : oneLine(task.instruction)) << "\n";
  s << "# trajectory id: " << task.trajectoryId() << " (the ROS 2 YAML of the same execution has the same id)\n";
  if (!task.scene.empty()) s << "# scene: " << oneLine(task.scene) << "\n";
  for (const auto& st : task.report.steps)
    s << "# step " << st.index + 1 << ": " << oneLine(st.object) << " -> " << oneLine(st.relation) << ": "
      << toString(st.status) << (st.reason.empty() ? "" : " (" + oneLine(st.reason) + ")") << "\n";
  s << "# trajectory: the simulated, safety-checked joint reference, " << tr.duration_s() << " s, replayed with\n"
    << "#   servoj every " << T << " s (" << std::setprecision(0) << 1.0 / T << std::setprecision(3)
    << " Hz), lookahead " << o.servoLookahead_s << " s, gain " << std::setprecision(0) << o.servoGain
    << std::setprecision(3) << "; " << ticks << " ticks\n";
  s << "# joints (rad, base to wrist):";
  for (int j = 0; j < 6; ++j) s << " " << oneLine(task.jointNames[j]);
  s << "\n# limits checked: joint positions within the URDF limits; joint speeds <= URDF limit x "
    << task.velocityFraction << " =";
  for (int j = 0; j < 6; ++j) s << " " << task.maxVelocity_radps[j];
  s << " rad/s;\n#   joint accelerations on the spline <= " << task.maxAcceleration_radps2
    << " rad/s^2; arm above the table and clear of the container walls (SafetyChecker)\n";
  s << "# in this program: peak joint speed " << peakSpeed << " rad/s (" << oneLine(task.jointNames[peakSpeedJoint])
    << "), peak joint acceleration " << peakAcc << " rad/s^2\n";
  s << "# gripper: tool digital output " << o.gripperDigitalOut << ": True = grasp (suction on), False = release; wait "
    << o.gripperWait_s << " s after each switch\n";
  s << "# preamble: movej to the first configuration at v = " << o.preambleSpeed_radps << " rad/s, a = "
    << o.preambleAcceleration_radps2 << " rad/s^2\n";
  s << "# run: send to the controller's port 30002 (nc <robot-ip> 30002 < this file), or in PolyScope a Script\n"
    << "#   node (File) with this file followed by a Script expression '" << o.programName << "()'\n";
  s << "  # preamble: gripper released, move slowly to the first configuration\n";
  s << "  set_tool_digital_out(" << o.gripperDigitalOut << ", False)\n";
  s << "  movej(" << jointList(q.front(), 7) << ", a=" << o.preambleAcceleration_radps2
    << ", v=" << o.preambleSpeed_radps << ")\n";
  const std::string servoArgs = [&] {
    std::ostringstream a;
    a << std::setprecision(6) << ", 0, 0, " << T << ", " << o.servoLookahead_s << ", " << o.servoGain << ")\n";
    return a.str();
  }();
  std::size_t nextEvent = 0;
  int motion = 1;
  s << "  # motion 1 from t = 0.000 s\n";
  for (int k = 0; k < ticks; ++k) {
    s << "  servoj(" << jointList(q[k], 7) << servoArgs;
    // Events between this tick and the next happen here (the arm holds still around them).
    while (nextEvent < task.gripperEvents.size() &&
           (k + 1 == ticks || task.gripperEvents[nextEvent].t_s < (k + 1) * T - 1e-9)) {
      const GripperEvent& e = task.gripperEvents[nextEvent++];
      const bool grasp = e.kind == GripperEvent::Kind::Grasp;
      s << "  stopj(" << o.stopDeceleration_radps2 << ")\n";
      s << "  # " << (grasp ? "grasp the " : "release the ") << oneLine(e.part) << " (simulated t = " << e.t_s
        << " s)\n";
      s << "  set_tool_digital_out(" << o.gripperDigitalOut << ", " << (grasp ? "True" : "False") << ")\n";
      s << "  sleep(" << o.gripperWait_s << ")\n";
      if (k + 1 < ticks) s << "  # motion " << ++motion << " from t = " << (k + 1) * T << " s\n";
    }
  }
  s << "  stopj(" << o.stopDeceleration_radps2 << ")\n";
  s << "end\n";
  // Indent the header comments to the def's body.
  std::string text = s.str(), out;
  out.reserve(text.size() + 2048);
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) out += (line.rfind("# ", 0) == 0 || line == "#" ? "  " : "") + line + "\n";
  return out;
}

void UrScriptExporter::write(const ExecutedTask& task, const std::string& path) const {
  srp::core::writeFileAtomically(path, toScript(task));
}

}  // namespace srp::execution
