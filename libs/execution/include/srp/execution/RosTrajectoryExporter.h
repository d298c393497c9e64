#pragma once
/// \file RosTrajectoryExporter.h
/// \brief The simulated, safety-checked joint trajectory of one execution as a ROS 2
/// `trajectory_msgs/msg/JointTrajectory` in the YAML that `ros2 topic pub` reads
/// (one document: header, joint_names, points with positions, velocities and
/// time_from_start {sec, nanosec}), for a joint_trajectory_controller.
///
/// Points are the trajectory's own knots (every 10 ms and the ends of the holds)
/// with their velocities and no accelerations: the controller then interpolates
/// them with cubic Hermite splines, the same spline the SafetyChecker checked.
/// `pointPeriod_s` > 0 keeps fewer knots for tools that cannot take a large
/// message: about one per period (ends kept), a knot dropped only where the
/// controller's spline through the remaining ones keeps the joint position, speed
/// and acceleration limits and stays within `maxThinningDeviation_rad` of the
/// checked trajectory (where the trajectory runs at its limits, more knots stay).
/// The result is checked again as a whole (checkThinned()) before it is written.
/// The gripper (not part of the message) and the start configuration are in the
/// header comments.
///
/// The YAML is written by yaml-cpp's emitter (the data cannot be read as anything
/// but one JointTrajectory document); every text in the comments (task name,
/// instruction, part names) goes through core::exportSafeText() first, so the
/// file is printable ASCII and no comment can end early.

#include <optional>
#include <string>

#include "srp/execution/ExecutedTask.h"

namespace srp::execution {

class RosTrajectoryExporter {
 public:
  struct Options {
    double pointPeriod_s = 0.0;  ///< 0: every knot; > 0: about one knot per period, where the checks allow
    /// Largest difference [rad], any joint, any time, allowed between the spline
    /// through the kept knots and the checked trajectory when pointPeriod_s > 0 (at
    /// 0.9 m from the base, 5 mrad moves the tool by about 4.5 mm).
    double maxThinningDeviation_rad = 0.005;
    std::string frameId;  ///< header.frame_id (the controller ignores it)
    std::string topic = "/scaled_joint_trajectory_controller/joint_trajectory";  ///< named in the comments only
  };

  /// Throws InvalidInputError on a negative or non-finite point period or a
  /// non-positive deviation bound.
  explicit RosTrajectoryExporter(Options options);
  RosTrajectoryExporter() : RosTrajectoryExporter(Options{}) {}

  /// The YAML text; throws InvalidInputError when the task may not be exported
  /// (ExecutedTask::whyNotExportable) or the thinned trajectory fails checkThinned().
  std::string toYaml(const ExecutedTask& task) const;

  /// toYaml() into `path`, atomically (core::writeFileAtomically); throws
  /// FileError when it cannot be written, leaving a previous file as it was.
  void write(const ExecutedTask& task, const std::string& path) const;

  /// What the controller would interpolate: the knots kept for pointPeriod_s
  /// (greedy, each interval checked as described above).
  JointTrajectory exportedTrajectory(const ExecutedTask& task) const;

  /// Largest |exported - checked| [rad] over the joints, at every knot of the
  /// checked trajectory and half-way between knots.
  static double deviation_rad(const JointTrajectory& exported, const JointTrajectory& checked);

  /// Why the exported (thinned) trajectory may not be written, or nullopt: a joint
  /// outside its position limits, above its checked speed or acceleration, or more
  /// than maxThinningDeviation_rad from the checked trajectory.
  std::optional<std::string> checkThinned(const ExecutedTask& task, const JointTrajectory& exported) const;

 private:
  Options options_;
};

}  // namespace srp::execution
