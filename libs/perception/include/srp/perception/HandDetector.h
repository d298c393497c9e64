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
/// A caller holding the whole recording may first show every frame to
/// preview() (in order, before the first detect()): a detector may learn from
/// the whole recording (a background behind a demonstrator who is in view from
/// the first frame, the demonstrator's skin colour).
class HandDetector {
 public:
  virtual ~HandDetector() = default;
  /// Pre-pass over the recording; the default ignores it.
  virtual void preview(const rawlog::RgbdFrame& /*frame*/) {}
  virtual std::optional<HandObservation> detect(const rawlog::RgbdFrame& frame) = 0;
  virtual std::string name() const = 0;
};

}  // namespace srp::perception
