#pragma once
/// \file CameraCalibration.h
/// \brief A calibrated camera: pinhole intrinsics plus ViSP's one-coefficient
/// radial distortion model, the model stored in ViSP camera XML files.

#include <Eigen/Core>
#include <string>

#include "srp/core/CameraIntrinsics.h"

namespace srp::calib {

/// Intrinsics (pixels) and radial distortion of one camera.
///
/// Distortion follows ViSP's `perspectiveProjWithDistortion` model. With
/// (x, y) the undistorted normalised coordinates (X/Z, Y/Z) and
/// (u0, v0) = (cx, cy), (px, py) = (fx, fy):
/// - undistorted to distorted: u_d = u0 + px x (1 + kud (x^2 + y^2)), same for v;
///   kud equals OpenCV's k1 with k2 = k3 = p1 = p2 = 0;
/// - distorted to undistorted: u = u0 + (u_d - u0)(1 + kdu r_d^2) with
///   r_d^2 = ((u_d - u0)/px)^2 + ((v_d - v0)/py)^2 (an approximation of the
///   inverse, fitted over the image).
/// kud = kdu = 0 means no distortion (rendered or rectified images).
struct CameraCalibration {
  std::string name = "Camera";        ///< camera name in the XML file
  srp::core::CameraIntrinsics intrinsics;
  double kud = 0.0;                   ///< undistorted -> distorted radial coefficient
  double kdu = 0.0;                   ///< distorted -> undistorted radial coefficient

  bool hasDistortion() const { return kud != 0.0 || kdu != 0.0; }

  /// Distorted pixel of a point in the camera frame [m] (Z > 0 assumed).
  Eigen::Vector2d projectDistorted(const Eigen::Vector3d& p_camera_m) const;

  /// Exact inverse of the kud model (Newton iterations), as undistorted pixel.
  Eigen::Vector2d undistortPixel(const Eigen::Vector2d& distorted_px) const;

  /// kdu fitted by least squares to the exact inverse of kud over the image.
  static double fitKdu(const srp::core::CameraIntrinsics& K, double kud);

  bool operator==(const CameraCalibration& o) const;
  bool operator!=(const CameraCalibration& o) const { return !(*this == o); }
};

}  // namespace srp::calib
