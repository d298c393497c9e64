#pragma once
/// \file MarkerHandDetector.h
/// \brief The hand from an AprilTag (tag36h11) on the back of a glove.

#include <optional>

#include "srp/perception/AprilTagDetector.h"
#include "srp/perception/HandDetector.h"

namespace srp::perception {

/// Palm centre = X_camera_tag * p_tag_palm. The tag pose comes from the tag's
/// size alone, so the hand has a 3D position even where the depth image has a
/// hole (ToF motion blur on the moving hand); where the depth inside the tag is
/// valid, its median replaces the tag's (less precise) distance along the ray.
/// Frames are expected in time order: the tag is looked for first near where
/// it was in the previous frame.
class MarkerHandDetector : public HandDetector {
 public:
  struct Options {
    double tagSize_m = 0.05;   ///< black square side on the glove
    int tagId = 0;             ///< -1: any tag36h11 tag
    /// Palm centre in the tag frame (tag z points into the back of the hand).
    Eigen::Vector3d p_tag_palm_m = Eigen::Vector3d(0.0, 0.0, 0.0136);
    bool useDepth = true;      ///< refine the distance with the depth image
    double maxDepthDisagreement_m = 0.03;
    float quadDecimate = 1.0f;
    /// Search first a window this many tag sides wide around the tag of the
    /// previous frame (about 15x cheaper than the whole image); when the tag
    /// is not there, the lost-tag search below in the same frame. 0: always
    /// the whole image. 2.5 gives the hand errors of 4 (default demo, seeds
    /// 2/3: median 1.0-1.1 mm, p95 within 0.1 mm) on about 0.4x the window area.
    double trackWindowTagSides = 2.5;
    /// While the tag is lost, search only the part of the image that changed
    /// since the previous frame (the whole image when more than half
    /// changed, or on the first frame): a hand out of view costs no search.
    bool searchChangedRegionOnly = true;
    int changeThreshold = 30;   ///< grey levels: a pixel changed
    int changeMargin_px = 48;   ///< the changed region grows by this much (at least)
    /// Every this many lost frames the whole image anyway: what changed too
    /// slowly to count frame to frame (light) is looked at too.
    int fullSearchEveryFrames = 15;
  };
  explicit MarkerHandDetector(const Options& options);
  std::optional<HandObservation> detect(const rawlog::RgbdFrame& frame) override;
  std::string name() const override { return "marker"; }

 private:
  Options options_;
  /// Where `grey` changed against the previous (lost) frame: nullopt when
  /// there is no previous frame, an empty rectangle when nothing changed.
  std::optional<cv::Rect> changedRegion(const cv::Mat& grey) const;

  AprilTagDetector tags_;
  std::optional<cv::Rect> lastTagBox_px_;  ///< the tag's image box in the previous frame
  cv::Mat previousGrey_;                   ///< the previous frame, kept while the tag is lost
  int lostFrames_ = 0;                     ///< frames since the tag was last found
};

}  // namespace srp::perception
