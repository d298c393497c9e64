#pragma once
/// \file MarkerFreeHandDetector.h
/// \brief The bare hand without a marker: depth foreground against the
/// hand-free first frames, skin colour, and connection to the image border
/// where the arm enters; the hand point is the palm centre, found from the
/// arm's geometry (its axis and the wrist), not from any marker.

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "srp/perception/HandDetector.h"

namespace srp::perception {

/// Marker-free hand detector (no tag is decoded or used as a feature: it works
/// on a plain glove or a bare hand).
///
/// Background: a per-pixel median depth and mean colour of the first
/// `backgroundFrames` frames, which must show no hand (a demo's first second).
///
/// Per frame (pixels of the colour image, registered depth):
/// 1. foreground = closer than the background by `minForeground_m`, or no
///    depth where the colour changed (the moving hand's depth holes);
/// 2. the arm = the largest foreground component touching the image border;
/// 3. the hand = its skin-coloured part (YCrCb box), holes filled (a held
///    object, a badge); the sleeve = the rest of the arm that reaches the
///    border (a carried object is not part of it);
/// 4. the arm axis = principal direction of sleeve + hand, pointing from the
///    border into the image; the wrist = where the hand meets the sleeve (the
///    cuff line), or, with a bare forearm (no sleeve seen), the narrowest
///    station of the width profile along the axis before the hand widens;
/// 5. the palm centre = the wrist plus `palmFromWrist_m` along the axis (a
///    fixed length of the hand: the palm centre does not move when the
///    fingers close, unlike the hand's blob centre or its thickest point),
///    centred across the hand at that station;
/// 6. depth: median of the valid depth on the hand within `palmRadius_m` of
///    that pixel, else of the whole hand's valid depth, plus `palmDepth_m`
///    (the palm centre lies inside the hand, below the visible back);
///    no valid hand depth at all: `hasDepth = false` (the caller carries the
///    last depth along the ray, see DemoPerception).
///
/// When no wrist is found (the hand just entering, no sleeve and no narrowing)
/// the palm is the thickest point (distance-transform maximum) of the hand
/// beyond `palmFromEntry` of its reach from the border.
///
/// State across frames: the background, and the last palm-to-wrist length in
/// pixels per metre of depth is not kept (each frame stands alone apart from
/// the background), so the detector can be reused on any frame order after
/// the background frames.
class MarkerFreeHandDetector : public HandDetector {
 public:
  struct Options {
    int backgroundFrames = 10;
    double minForeground_m = 0.02;
    bool useSkin = true;
    int minPixels = 300;
    /// Palm centre below the visible back of the hand along the ray [m].
    double palmDepth_m = 0.0125;
    /// Palm centre from the wrist (cuff line) along the arm axis, in the
    /// plane of the hand [m].
    double palmFromWrist_m = 0.122;
    /// Radius of the palm disc whose valid depth gives the palm depth [m].
    double palmRadius_m = 0.03;
    /// Without a wrist in view: palm centre back from the fingertips along the
    /// hand's axis [m] (relaxed fingers, as when the hand enters or leaves).
    double palmFromFingertips_m = 0.125;
  };

  /// What the last detect() found, in pixels (for drawing and tests).
  struct Geometry {
    bool haveWrist = false;
    Eigen::Vector2d entry_px = Eigen::Vector2d::Zero();  ///< mean of the arm's border pixels
    Eigen::Vector2d wrist_px = Eigen::Vector2d::Zero();  ///< cuff line centre
    double wristDepth_m = 0.0;                            ///< depth at the wrist (sets the pixel scale)
    Eigen::Vector2d axis = Eigen::Vector2d::UnitX();     ///< unit, from the border towards the fingers
    Eigen::Vector2d palm_px = Eigen::Vector2d::Zero();
  };

  explicit MarkerFreeHandDetector(const Options& options);
  std::optional<HandObservation> detect(const rawlog::RgbdFrame& frame) override;
  std::string name() const override { return "marker-free"; }
  const Options& options() const { return options_; }

  /// Hand mask of the last frame (CV_8UC1), for drawing.
  const cv::Mat& lastMask() const { return lastMask_; }
  const Geometry& lastGeometry() const { return geometry_; }

 private:
  Options options_;
  std::vector<cv::Mat> depthHistory_, colourHistory_;
  cv::Mat backgroundDepth_m_, backgroundColour_;
  cv::Mat lastMask_;
  Geometry geometry_;
  double lastDepth_m_ = 0.0;  ///< last valid hand depth (for the wrist's scale in a depth hole)
};

}  // namespace srp::perception
