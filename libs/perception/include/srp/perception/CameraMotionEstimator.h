#pragma once
/// \file CameraMotionEstimator.h
/// \brief Whether the camera of a recording moves, and where it is in every
/// frame: each frame's depth aligned to a key frame's by ICP.

#include <memory>
#include <optional>
#include <vector>

#include <opencv2/core.hpp>

#include "srp/core/CameraIntrinsics.h"
#include "srp/core/Pose.h"
#include "srp/rawlog/RgbdFrame.h"

namespace srp::perception {

/// The camera's pose in every frame relative to the first frame's camera,
/// `X_camera0_camera` (optical frames, metres), from the depth images alone:
/// OpenCV's point-to-plane ICP odometry (cv::rgbd::ICPOdometry, opencv
/// contrib) at a reduced resolution, each frame against a key frame (the first
/// frame, until the alignment fails or the camera has turned or moved far from
/// it), started from the previous frame's pose. Depth only: a scene lit by a
/// bright window or crossed by a demonstrator in a dark shirt moves a
/// photometric estimate (RgbdOdometry) by centimetres, the depth ICP by less
/// than a millimetre (HRT1 recordings, see the perception README).
///
/// The camera *moved* when a frame's pose leaves the first frame's by more
/// than Options::movedTranslation_m or Options::movedRotation_rad. While it
/// has not, only every Options::checkStride-th frame is aligned (the others
/// keep the last pose, identity up to the thresholds); once it has, every
/// frame is.
///
/// \code
///   CameraMotionEstimator motion(frames[0].intrinsics);
///   for (const auto& f : frames) motion.add(f);
///   if (motion.moved()) ... motion.X_camera0_camera(i) ...
/// \endcode
class CameraMotionEstimator {
 public:
  struct Options {
    /// Depth images are reduced by this factor (nearest pixel) before ICP.
    int downscale = 4;
    double minDepth_m = 0.2;
    double maxDepth_m = 4.0;
    /// Point pairs farther apart than this along the depth are not matched
    /// (a demonstrator's moving arm).
    double maxDepthDiff_m = 0.05;
    /// Share of the pixels ICP samples per level.
    double maxPointsPart = 0.15;
    /// ICP iterations per pyramid level, finest first.
    std::vector<int> iterations = {7, 10};
    /// The camera moved when a frame's pose leaves the first frame's camera
    /// by more than either. Fixed cameras: at most 0.5 mm / 0.02 deg on the
    /// HRT1 recordings; a hand-held camera: 1.4 deg by frame 12 of the real
    /// cube recording.
    double movedTranslation_m = 0.01;
    double movedRotation_rad = 0.5 * 3.14159265358979323846 / 180.0;
    /// While the camera has not moved, every checkStride-th frame is aligned.
    int checkStride = 3;
    /// A new key frame when the camera is this far from the key frame's pose.
    double keyFrameTranslation_m = 0.15;
    double keyFrameRotation_rad = 15.0 * 3.14159265358979323846 / 180.0;
  };

  explicit CameraMotionEstimator(const core::CameraIntrinsics& intrinsics);
  CameraMotionEstimator(const core::CameraIntrinsics& intrinsics, const Options& options);
  ~CameraMotionEstimator();
  CameraMotionEstimator(const CameraMotionEstimator&) = delete;
  CameraMotionEstimator& operator=(const CameraMotionEstimator&) = delete;

  /// Adds the next frame (frames in time order) and returns its camera's pose
  /// in the first frame's camera. `mask` (CV_8UC1, the frame's size, non-zero
  /// = usable; empty = every valid depth) leaves out what moves by itself (a
  /// demonstrator's arm). A frame whose alignment fails keeps the previous
  /// frame's pose and starts a new key frame.
  core::Pose3 add(const rawlog::RgbdFrame& frame, const cv::Mat& mask = cv::Mat());

  /// Every frame's pose so far, in the order added (X_camera0_camera).
  const std::vector<core::Pose3>& poses() const { return poses_; }
  /// True once a frame's pose left the first frame's by more than the thresholds.
  bool moved() const { return movedAt_ >= 0; }
  /// Index (in the order added) of the first frame that did; -1 when none.
  int movedAt() const { return movedAt_; }
  /// The largest distance and turn from the first frame's camera seen so far.
  double maxTranslation_m() const { return maxTranslation_m_; }
  double maxRotation_rad() const { return maxRotation_rad_; }
  /// Frames whose alignment failed.
  int failures() const { return failures_; }
  const Options& options() const { return options_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  Options options_;
  std::vector<core::Pose3> poses_;
  int movedAt_ = -1;
  int failures_ = 0;
  double maxTranslation_m_ = 0.0, maxRotation_rad_ = 0.0;
};

}  // namespace srp::perception
