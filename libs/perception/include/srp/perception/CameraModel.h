#pragma once
/// \file CameraModel.h
/// \brief The pinhole camera of an RGB-D frame, backed by ViSP's
/// vpCameraParameters (kept private), for pixel <-> metre conversions.

#include <Eigen/Core>
#include <memory>
#include <string>

#include "srp/core/CameraIntrinsics.h"

namespace srp::perception {

/// Pinhole camera without distortion (depth registered to colour, images
/// undistorted). Pixel (u, v): u right, v down. Camera optical frame: x right,
/// y down, z forward, metres. Back-projection of pixel (u, v) at depth Z:
/// X = (u - cx) Z / fx, Y = (v - cy) Z / fy (ViSP's vpPixelMeterConversion
/// gives the normalised x = X/Z, y = Y/Z).
///
/// \code
///   auto cam = CameraModel::fromVispXml("calib/camera.xml", "color_camera", 640, 480);
///   Eigen::Vector3d p_camera_m = cam.pixelToCamera(320.0, 240.0, 0.85);
/// \endcode
class CameraModel {
 public:
  /// Throws InvalidInputError when the intrinsics are not usable.
  explicit CameraModel(const core::CameraIntrinsics& intrinsics);
  ~CameraModel();
  CameraModel(const CameraModel& o);
  CameraModel& operator=(const CameraModel& o);

  /// Reads camera `cameraName` from a ViSP calibration XML (vpXmlParserCamera,
  /// model without distortion, or with distortion whose coefficients are then
  /// ignored: srp's images are undistorted). Throws FileError naming the file.
  static CameraModel fromVispXml(const std::string& path, const std::string& cameraName, int width_px,
                                 int height_px);

  const core::CameraIntrinsics& intrinsics() const { return intrinsics_; }

  /// Point in the camera frame [m] seen at pixel (u, v) with depth Z [m].
  Eigen::Vector3d pixelToCamera(double u_px, double v_px, double depth_m) const;
  /// Pixel of a camera-frame point (Z > 0 required; no check).
  Eigen::Vector2d cameraToPixel(const Eigen::Vector3d& p_camera_m) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  core::CameraIntrinsics intrinsics_;
};

}  // namespace srp::perception
