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
/// `pointPeriod_s` > 0 keeps fewer knots (at least that far apart, ends kept) for
/// tools that cannot take a large message; between kept knots the controller's
/// spline then differs slightly from the checked one (the README gives the size).
/// The gripper (not part of the message) and the start configuration are in the
/// header comments.

#include <string>

#include "srp/execution/ExecutedTask.h"

namespace srp::execution {

struct RosTrajectoryOptions {
  double pointPeriod_s = 0.0;  ///< 0: every knot; > 0: knots at least this far apart
  std::string frameId;          ///< header.frame_id (the controller ignores it)
  std::string topic = "/scaled_joint_trajectory_controller/joint_trajectory";  ///< named in the comments only
};

class RosTrajectoryExporter {
 public:
  /// Throws InvalidInputError on a negative point period.
  explicit RosTrajectoryExporter(RosTrajectoryOptions options = {});

  /// The YAML text; throws InvalidInputError when the task may not be exported
  /// (ExecutedTask::whyNotExportable).
  std::string toYaml(const ExecutedTask& task) const;

  /// toYaml() into `path`; throws FileError when it cannot be written.
  void write(const ExecutedTask& task, const std::string& path) const;

 private:
  RosTrajectoryOptions options_;
};

}  // namespace srp::execution
