#pragma once
/// \file SkillLearner.h
/// \brief Turns a segmented demo into one SkillSet per moved object: Reach and
/// Move DMPs from the smoothed hand trajectory, grasp/release poses with
/// pre/post poses offset along the approach axis, and a quaternion DMP of the
/// object's orientation during Move.

#include <optional>
#include <vector>

#include "srp/motion/Dmp.h"
#include "srp/motion/Segmenter.h"
#include "srp/motion/SkillSet.h"

namespace srp::motion {

class SkillLearner {
 public:
  struct Options {
    Dmp::Options dmp{};                  ///< Default mode, lambda by GCV
    double approachOffset_m = 0.02;      ///< dp of the pre/post poses (thesis: 2 cm)
    /// Fixed approach axis in the demo frame (e.g. the table normal pointing
    /// into the table); nullopt: the direction the hand came from over its
    /// last 3 cm before the grasp/release (searched back `approachWindow` samples).
    std::optional<Eigen::Vector3d> approachAxis;
    int approachWindow = 60;
  };

  SkillLearner() = default;
  explicit SkillLearner(Options options) : options_(std::move(options)) {}

  /// One SkillSet per moved object, plan order (objects that never moved are
  /// skipped: they have no skills). `objects` gives the yaw per sample.
  /// Throws InvalidInputError naming the object and skill when a segment has
  /// fewer than 3 samples (nothing is learned then).
  std::vector<SkillSet> learn(const Segmentation& segmentation, const std::vector<ObjectTrack>& objects) const;

  const Options& options() const { return options_; }

 private:
  Options options_;
};

}  // namespace srp::motion
