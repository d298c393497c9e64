#include "srp/core/PositionTrajectory.h"

#include <algorithm>

#include "srp/core/Error.h"

namespace srp::core {

void PositionTrajectory::append(const PositionSample& s) {
  if (!samples_.empty() && !(s.t_s > samples_.back().t_s))
    throw InvalidInputError("trajectory sample at frame " + std::to_string(s.frame) +
                            ": time " + std::to_string(s.t_s) +
                            " s is not after the previous sample's");
  if (s.valid && !s.p_m.allFinite())
    throw InvalidInputError("trajectory sample at frame " + std::to_string(s.frame) +
                            " has a non-finite coordinate; mark it invalid instead");
  samples_.push_back(s);
}

std::size_t PositionTrajectory::validCount() const {
  return static_cast<std::size_t>(
      std::count_if(samples_.begin(), samples_.end(), [](const auto& s) { return s.valid; }));
}

Eigen::Matrix3Xd PositionTrajectory::positions() const {
  Eigen::Matrix3Xd P(3, samples_.size());
  for (std::size_t i = 0; i < samples_.size(); ++i) P.col(i) = samples_[i].p_m;
  return P;
}

Eigen::VectorXd PositionTrajectory::times() const {
  Eigen::VectorXd t(samples_.size());
  for (std::size_t i = 0; i < samples_.size(); ++i) t(i) = samples_[i].t_s;
  return t;
}

}  // namespace srp::core
