#pragma once
/// \file MarkerFreeHandDetector.h
/// \brief The bare hand without a marker: depth foreground against the
/// hand-free first frames, skin colour, and connection to the image border
/// where the arm enters; the hand point is the palm centre.

#include <opencv2/core.hpp>

#include "srp/perception/HandDetector.h"

namespace srp::perception {

/// Learns a background (per-pixel median depth and colour) from the first
/// `backgroundFrames` frames it sees, which must show no hand (the demo's
/// first second). Then, per frame: foreground = closer than the background by
/// `minForeground_m` (or depth missing where the colour changed), and skin
/// coloured (YCrCb box) when `useSkin`; the hand is the largest foreground
/// component touching the image border; the palm centre is the innermost
/// point (distance-transform maximum) of the part away from the border; its
/// 3D point uses the median depth of the palm disc, pushed `palmDepth_m`
/// below the visible surface (the palm centre is inside the hand).
class MarkerFreeHandDetector : public HandDetector {
 public:
  struct Options {
    int backgroundFrames = 10;
    double minForeground_m = 0.02;
    bool useSkin = true;
    int minPixels = 300;
    double palmDepth_m = 0.015;
  };
  explicit MarkerFreeHandDetector(const Options& options);
  std::optional<HandObservation> detect(const rawlog::RgbdFrame& frame) override;
  std::string name() const override { return "marker-free"; }

  /// Foreground mask of the last frame (CV_8UC1), for drawing.
  const cv::Mat& lastMask() const { return lastMask_; }

 private:
  Options options_;
  std::vector<cv::Mat> depthHistory_, colourHistory_;
  cv::Mat backgroundDepth_m_, backgroundColour_;
  cv::Mat lastMask_;
};

}  // namespace srp::perception
