#pragma once
/// \file MinimumJerkPathGenerator.h
/// \brief Minimum-jerk Cartesian paths (s(tau) = 10 tau^3 - 15 tau^4 + 6 tau^5,
/// positions interpolated linearly, orientations by slerp) that lift to a
/// clearance height, cross over, and lower, so a carried part clears container walls.

#include "srp/execution/CartesianPathGenerator.h"

namespace srp::execution {

class MinimumJerkPathGenerator : public CartesianPathGenerator {
 public:
  struct Options {
    double clearanceHeight_m = 0.16;  ///< tcp height [m, world z] for crossing between places
    double meanSpeed_mps = 0.25;      ///< mean tcp speed of a segment
    double meanAngularSpeed_radps = 0.8;
    double minSegmentDuration_s = 0.4;
  };

  MinimumJerkPathGenerator() : MinimumJerkPathGenerator(Options{}) {}
  explicit MinimumJerkPathGenerator(Options options) : options_(options) {}

  /// Lift to max(clearance, start z, goal z), cross, lower; segments that would be
  /// shorter than 1 mm are dropped.
  CartesianPath generate(srp::core::SkillType skill, const std::string& object, const srp::core::Pose3& X_world_start,
                         const srp::core::Pose3& X_world_goal, double dt_s) const override;
  std::string name() const override { return "minimum-jerk"; }

  /// One straight minimum-jerk segment, duration from the options' mean speeds.
  CartesianPath straight(const srp::core::Pose3& X_world_start, const srp::core::Pose3& X_world_goal,
                         double dt_s) const;

  const Options& options() const { return options_; }

 private:
  Options options_;
};

/// Appends `next` to `path`, shifting its times (its first sample, equal to the last
/// of `path`, is dropped).
void appendPath(CartesianPath& path, const CartesianPath& next);

}  // namespace srp::execution
