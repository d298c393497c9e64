#pragma once
/// \file UrScriptExporter.h
/// \brief One URScript program per execution that replays the simulated,
/// safety-checked joint trajectory on a Universal Robots controller.
///
/// Why servoj and not blended movej: the checked trajectory is a time-parametrised
/// spline (learned DMP shapes, minimum-jerk approach/lift, holds), checked against
/// the joint limits, the speed limits and the arm spheres' clearance to the table
/// and the container walls (2 mm) *along that spline*. servoj at the controller's
/// 125 Hz with the spline sampled every 8 ms replays exactly those positions at
/// those times. Blended movej waypoints would be re-timed by the controller's own
/// trapezoidal profiles and the blend radii cut the corners between waypoints: the
/// path driven would not be the path checked (near a wall, 2 mm is less than a blend).
///
/// Program layout: `def <name>():`, a header comment (task model, instruction, steps,
/// limits used, servo parameters, gripper pin), a preamble (tool output
/// off = released, `movej` slowly to the first configuration), one `servoj` line per
/// 8 ms tick, and at each grasp / release event: `stopj` (the arm is at rest there:
/// the executor holds after every segment), `set_tool_digital_out(pin, True/False)`
/// and `sleep(wait)`; `end`. Positions are written with 7 decimals (< 1e-7 rad).

#include <string>

#include "srp/execution/ExecutedTask.h"

namespace srp::execution {

class UrScriptExporter {
 public:
  struct Options {
    std::string programName = "srp_task";  ///< a URScript identifier (letter, then letters, digits, '_')
    int gripperDigitalOut = 0;             ///< tool digital output (0 or 1): True = grasp (suction on), False = release
    double gripperWait_s = 0.3;            ///< wait after switching the output (vacuum build-up / release)
    double servoPeriod_s = 0.008;          ///< servoj t: 0.008 s = the CB3 / e-Series 125 Hz control loop
    double servoLookahead_s = 0.1;         ///< servoj lookahead_time, UR's range 0.03-0.2 s
    double servoGain = 300.0;              ///< servoj gain, UR's range 100-2000
    double preambleSpeed_radps = 0.3;      ///< movej v to the first configuration ("slowly")
    double preambleAcceleration_radps2 = 0.5;
    double stopDeceleration_radps2 = 2.0;  ///< stopj a before a gripper switch (the arm is already at rest)
  };

  /// Throws InvalidInputError naming a bad option (pin not 0/1, negative wait,
  /// servo parameters outside UR's documented ranges, non-positive preamble speed).
  explicit UrScriptExporter(Options options);
  UrScriptExporter() : UrScriptExporter(Options{}) {}

  /// The program text. Throws InvalidInputError when the task may not be exported
  /// (ExecutedTask::whyNotExportable) or when a resampled tick would break a joint
  /// position or speed limit (not expected: the spline was checked; never clipped).
  std::string toScript(const ExecutedTask& task) const;

  /// toScript() into `path`, atomically (core::writeFileAtomically); throws
  /// FileError when it cannot be written, leaving a previous file as it was.
  void write(const ExecutedTask& task, const std::string& path) const;

  const Options& options() const { return options_; }

 private:
  Options options_;
};

}  // namespace srp::execution
