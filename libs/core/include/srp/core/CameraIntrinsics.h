#pragma once
/// \file CameraIntrinsics.h
/// \brief Pinhole camera intrinsics without distortion (images are undistorted
/// or rendered), in pixels, for an image of width x height pixels.
///
/// Pixel (u, v): u to the right, v down, origin at the centre of the top-left
/// pixel. Camera optical frame: x right, y down, z forward, metres.
/// Projection u = fx X/Z + cx, v = fy Y/Z + cy; back-projection of a pixel with
/// depth Z [m]: X = (u - cx) Z / fx, Y = (v - cy) Z / fy (SPEC.md §3; the
/// thesis' eq. 6.2 prints the division the wrong way round).

#include <Eigen/Core>
#include <nlohmann/json_fwd.hpp>
#include <optional>

namespace srp::core {

struct CameraIntrinsics {
  double fx_px = 0.0;
  double fy_px = 0.0;
  double cx_px = 0.0;
  double cy_px = 0.0;
  int width_px = 0;
  int height_px = 0;

  /// Point in the camera frame [m] seen at pixel (u, v) with depth Z [m].
  Eigen::Vector3d backProject(double u_px, double v_px, double depth_m) const;

  /// Pixel of a point in the camera frame; nullopt when Z <= 0.
  std::optional<Eigen::Vector2d> project(const Eigen::Vector3d& p_camera_m) const;

  /// True when (u, v) lies inside the image.
  bool contains(double u_px, double v_px) const;

  /// Throws InvalidInputError (naming `what`) unless focal lengths and size are positive.
  void validate(const std::string& what) const;

  bool operator==(const CameraIntrinsics& o) const;
  bool operator!=(const CameraIntrinsics& o) const { return !(*this == o); }
};

void to_json(nlohmann::json& j, const CameraIntrinsics& k);
void from_json(const nlohmann::json& j, CameraIntrinsics& k);

}  // namespace srp::core
