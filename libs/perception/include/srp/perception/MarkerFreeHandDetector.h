#pragma once
/// \file MarkerFreeHandDetector.h
/// \brief The bare hand without a marker: depth foreground against the
/// hand-free first frames, skin colour, and connection to the image border
/// where the arm enters; the palm centre from the arm's geometry (its axis and
/// the wrist at the cuff), not from any marker.

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "srp/perception/HandDetector.h"

namespace srp::perception {

/// Marker-free hand detector (no tag is decoded or used as a feature: it works
/// on a plain glove or a bare hand in a sleeve).
///
/// Background: a per-pixel median depth and mean colour of the first
/// `backgroundFrames` frames, which must show no hand (a demo's first second).
///
/// Per frame (pixels of the colour image, registered depth):
/// 1. foreground = closer than the background by `minForeground_m`, or a
///    depth hole where the colour changed (the moving hand's holes: on a ToF
///    camera more than half of the hand has no depth);
/// 2. the arm = the largest foreground component touching the image border
///    (where it enters);
/// 3. the hand = its skin-coloured part (YCrCb box), holes filled (a held
///    object, a badge); the sleeve = the largest non-skin part of the arm that
///    reaches the border (a carried object does not);
/// 4. the wrist = the cuff line, the hand's pixels next to the sleeve; the
///    arm axis = principal direction of sleeve + hand, pointing inwards;
///    the palm centre = the wrist plus `palmFromWrist_m` along the axis
///    (a fixed length of the hand: it does not move when the fingers close
///    round an object, unlike the blob's centre or its thickest point);
/// 5. no cuff in view (the skin itself reaches the border while the hand
///    enters or leaves, or no sleeve): the palm centre lies
///    `palmFromFingertips_m` back from the fingertips along the hand's
///    principal axis (the inward border normal for a short blob), on the
///    hand's centre line; it may lie outside the image;
/// 6. depth: median of the valid depth on the hand within `palmRadius_m` of
///    the palm pixel, plus `palmDepth_m` (the palm centre lies inside the
///    hand, below its visible back). None there (a hole, or the palm out of
///    view): `hasDepth = false` when the last palm depth is at most 3 frames
///    old (the caller carries it along the palm's ray, see DemoPerception;
///    `palm_px` is placed for that depth), else the whole hand's valid depth,
///    else `hasDepth = false`.
///
/// The palm is placed in metres: the anchor pixel (cuff or fingertips)
/// back-projected at the palm's depth, plus the length along the axis.
/// State across frames: the background and the last palm depth with its age
/// (no smoothing: each palm is measured in its own frame). Defaults measured on srp::synth's demonstrator
/// (a glove and a sleeve, 7 cm wide);
/// a real demonstrator's hand size sets palmFromWrist_m / palmFromFingertips_m.
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
    double palmFromWrist_m = 0.13;
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
  double lastDepth_m_ = 0.0;  ///< last measured depth of the palm's visible back
  int lastDepthFrame_ = 0;    ///< the frameCount_ it was measured in
  int frameCount_ = 0;        ///< frames seen
};

}  // namespace srp::perception
