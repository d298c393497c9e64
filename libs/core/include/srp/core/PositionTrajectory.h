#pragma once
/// \file PositionTrajectory.h
/// \brief A timestamped 3D position trajectory in one named frame (metres,
/// seconds), with a validity flag per sample for detections that failed.

#include <Eigen/Core>
#include <string>
#include <vector>

namespace srp::core {

/// One sample: frame index, time [s], position [m] in the trajectory's frame.
struct PositionSample {
  int frame = 0;
  double t_s = 0.0;
  Eigen::Vector3d p_m = Eigen::Vector3d::Zero();
  bool valid = true;  ///< false: no detection in this frame (p_m is meaningless)
};

/// Positions of one point (the palm centre, an object's origin) over time,
/// expressed in `frame()` (e.g. "camera"). Samples are kept in time order.
class PositionTrajectory {
 public:
  PositionTrajectory() = default;
  explicit PositionTrajectory(std::string frame) : frame_(std::move(frame)) {}

  const std::string& frame() const { return frame_; }
  const std::vector<PositionSample>& samples() const { return samples_; }
  std::vector<PositionSample>& samples() { return samples_; }
  std::size_t size() const { return samples_.size(); }
  bool empty() const { return samples_.empty(); }
  const PositionSample& operator[](std::size_t i) const { return samples_[i]; }

  /// Appends a sample; throws InvalidInputError if its time is not after the
  /// previous sample's or a valid sample has a non-finite coordinate.
  void append(const PositionSample& s);

  /// Number of samples with valid == true.
  std::size_t validCount() const;

  /// Positions as a 3 x N matrix (invalid samples included as stored).
  Eigen::Matrix3Xd positions() const;

  /// Times [s] as a vector of N.
  Eigen::VectorXd times() const;

 private:
  std::string frame_ = "camera";
  std::vector<PositionSample> samples_;
};

}  // namespace srp::core
