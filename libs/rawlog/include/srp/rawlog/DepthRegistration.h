#pragma once
/// \file DepthRegistration.h
/// \brief Depth registration: a depth image seen by the depth camera,
/// re-projected into the colour camera (its size, its intrinsics, its lens),
/// for RGB-D sensors whose two cameras differ (RealSense, Azure Kinect,
/// Kinect without hardware registration, two-camera rigs).

#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "srp/core/CameraIntrinsics.h"
#include "srp/core/Pose.h"
#include "srp/rawlog/LensDistortion.h"

namespace srp::rawlog {

/// Maps depth images of the depth camera onto the colour camera's pixel grid.
///
/// For each depth pixel (u, v) with depth Z: back-project with the depth
/// intrinsics (undistorted), transform by X_colour_depth, project with the
/// colour intrinsics and lens distortion. Depth in the result is Z along the
/// colour camera's optical axis [m]; the colour image is never touched.
/// Pixels are filled so that upsampling (640x480 depth onto 1280x720 or
/// 1920x1080 colour) leaves no grid holes:
/// - the depth image is treated as a surface: each pair of triangles between
///   four neighbouring depth pixels whose depths are continuous (no jump
///   larger than a surface seen at 76 degrees plus 0.5 % of the depth) is
///   rasterised into the colour image with perspective-correct (1/Z)
///   interpolation, exact for planes;
/// - each depth pixel's footprint (its four corners at its depth) is splatted
///   too, tilted like the surface around it (depth gradient from its
///   continuous neighbours), which fills the half-pixel rims at silhouettes
///   the triangles do not reach; a splat replaces a triangle's depth only when it lies in front of
///   it by more than that jump (another surface);
/// - a z-buffer keeps the nearest depth per colour pixel, so surfaces the
///   colour camera sees behind a foreground object are hidden as they are.
/// Colour pixels the depth camera does not see (occluded from it, outside its
/// view, invalid depth) stay 0 (invalid).
///
/// Why not ViSP's vpCameraParameters: its distortion model has one radial
/// coefficient and cannot represent MRPT's or RealSense's five Brown-Conrady
/// coefficients, and rawlog (a low module every other one uses) does not link ViSP.
class DepthRegistration {
 public:
  /// One camera: intrinsics of its images (size included) and lens distortion.
  struct Camera {
    srp::core::CameraIntrinsics K;
    LensDistortion distortion;
  };

  /// Throws InvalidInputError (naming the camera) for invalid intrinsics.
  DepthRegistration(const Camera& depthCamera, const Camera& colourCamera, const srp::core::Pose3& X_colour_depth);

  /// depth_m: CV_32FC1 of the depth camera's size (0 = invalid). Returns the
  /// colour-sized CV_32FC1 depth [m] in the colour camera. Throws
  /// InvalidInputError when the type or size does not match.
  cv::Mat registerDepth(const cv::Mat& depth_m) const;

  const Camera& depthCamera() const { return depth_; }
  const Camera& colourCamera() const { return colour_; }
  const srp::core::Pose3& X_colour_depth() const { return X_colour_depth_; }

 private:
  Camera depth_, colour_;
  srp::core::Pose3 X_colour_depth_;
  std::vector<Eigen::Vector2f> rays_;        ///< undistorted (x, y) per depth pixel centre, row-major
  std::vector<Eigen::Vector2f> cornerRays_;  ///< same at pixel corners, (W+1) x (H+1)
};

}  // namespace srp::rawlog
