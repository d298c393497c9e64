#pragma once
/// \file HandDetector.h
/// \brief The one interface of the hand detectors (marker on a glove, or
/// marker-free), and what they report per frame.

#include <Eigen/Core>
#include <memory>
#include <optional>
#include <string>

#include "srp/rawlog/RgbdFrame.h"

namespace srp::perception {

/// The hand in one frame. The hand point is the palm centre, camera optical
/// frame, metres.
struct HandObservation {
  Eigen::Vector2d palm_px = Eigen::Vector2d::Zero();       ///< palm centre in the image
  Eigen::Vector3d p_camera_palm_m = Eigen::Vector3d::Zero();
  bool hasDepth = false;   ///< false: seen in the image but no depth (the caller carries the last depth forward)
  double confidence = 0.0;
};

/// A hand detector sees one frame at a time, in order (it may learn from the
/// first frames, e.g. a background). nullopt = no hand in this frame.
class HandDetector {
 public:
  virtual ~HandDetector() = default;
  virtual std::optional<HandObservation> detect(const rawlog::RgbdFrame& frame) = 0;
  virtual std::string name() const = 0;
};

}  // namespace srp::perception
