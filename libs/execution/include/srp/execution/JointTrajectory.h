#pragma once
/// \file JointTrajectory.h
/// \brief A time-sampled trajectory of the six arm joints (radians, seconds) with
/// velocities and accelerations, interpolated by cubic Hermite splines.

#include <string>
#include <vector>

#include "srp/execution/RobotModel.h"

namespace srp::execution {

struct JointTrajectorySample {
  double t_s = 0.0;  ///< time from the trajectory's start
  JointVector q_rad = JointVector::Zero();
  JointVector qd_radps = JointVector::Zero();
  JointVector qdd_radps2 = JointVector::Zero();
};

class JointTrajectory {
 public:
  JointTrajectory() = default;

  /// Builds a trajectory from joint positions at strictly increasing times; the
  /// velocities and accelerations are central finite differences, zero at both ends
  /// (the robot starts and stops at rest). Throws InvalidInputError on fewer than
  /// two samples, non-increasing times or non-finite values.
  static JointTrajectory fromPositions(const std::vector<double>& t_s,
                                       const std::vector<JointVector>& q_rad);

  /// A trajectory from samples as they are (velocities kept: the spline through them
  /// is theirs), times shifted to start at 0. Throws InvalidInputError on fewer than
  /// two samples, non-increasing times or non-finite values.
  static JointTrajectory fromSamples(std::vector<JointTrajectorySample> samples);

  /// A trajectory that holds q for duration_s.
  static JointTrajectory hold(const JointVector& q_rad, double duration_s);

  const std::vector<JointTrajectorySample>& samples() const { return samples_; }
  bool empty() const { return samples_.empty(); }
  double duration_s() const { return samples_.empty() ? 0.0 : samples_.back().t_s; }

  /// Position, velocity and acceleration at time t (clamped to [0, duration]).
  JointTrajectorySample at(double t_s) const;

  /// Appends `next` (whose first sample must equal this one's last position), shifting its times.
  void append(const JointTrajectory& next);

  /// CSV with header t_s,q1_rad..q6_rad,qd1_radps..qd6_radps; throws FileError.
  void writeCsv(const std::string& path) const;

 private:
  std::vector<JointTrajectorySample> samples_;
};

}  // namespace srp::execution
