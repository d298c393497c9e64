#pragma once
/// \file AprilTagDetector.h
/// \brief AprilTag (tag36h11) detection and per-tag pose, via ViSP's
/// vpDetectorAprilTag (kept private).

#include <Eigen/Core>
#include <array>
#include <memory>
#include <opencv2/core.hpp>
#include <vector>

#include "srp/core/CameraIntrinsics.h"
#include "srp/core/Pose.h"

namespace srp::perception {

/// One detected tag. Tag frame (AprilTag's; ViSP's default is this one turned
/// half a turn about x): origin at the tag centre, x right and y down as the
/// tag is read, z into the tag (away from a camera that faces it), metres. `corners_px[i]` is the image of
/// `corners_tag_m[i]`.
struct TagDetection {
  int id = -1;
  std::array<Eigen::Vector2d, 4> corners_px;     ///< (u, v) pixels
  std::array<Eigen::Vector3d, 4> corners_tag_m;  ///< the same corners in the tag frame
  Eigen::Vector2d centre_px = Eigen::Vector2d::Zero();
  core::Pose3 X_camera_tag = core::Pose3::Identity();  ///< from the tag size alone
  double reprojectionError_px = 0.0;                   ///< RMS over the 4 corners
};

/// Detects tag36h11 tags of one physical size (the black square's side,
/// `tagSize_m`) in colour or grey images and estimates each tag's pose from
/// its four corners (ViSP: homography then virtual visual servoing).
///
/// \code
///   AprilTagDetector detector({0.0955});
///   for (const TagDetection& tag : detector.detect(frame.colour_bgr8, frame.intrinsics))
///     std::cout << tag.id << " at " << tag.X_camera_tag.translation().transpose() << "\n";
/// \endcode
class AprilTagDetector {
 public:
  struct Options {
    double tagSize_m = 0.0955;   ///< side of the black square [m]
    float quadDecimate = 1.0f;   ///< >1 trades small/far tags for speed
    int threads = 1;
  };

  explicit AprilTagDetector(const Options& options);
  ~AprilTagDetector();
  AprilTagDetector(const AprilTagDetector&) = delete;
  AprilTagDetector& operator=(const AprilTagDetector&) = delete;

  /// All tags in the image (CV_8UC3 BGR or CV_8UC1). Not thread-safe (the
  /// ViSP detector keeps state); use one detector per thread.
  std::vector<TagDetection> detect(const cv::Mat& image, const core::CameraIntrinsics& intrinsics);

  const Options& options() const { return options_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  Options options_;
};

}  // namespace srp::perception
