#pragma once
/// \file LensDistortion.h
/// \brief Brown-Conrady lens distortion (OpenCV's and MRPT's "plumb_bob"
/// model: k1, k2, p1, p2, k3) on normalised image coordinates.

#include <Eigen/Core>
#include <nlohmann/json_fwd.hpp>

namespace srp::rawlog {

/// Distortion of a pinhole camera, in the order OpenCV's distCoeffs, MRPT's
/// TCamera::dist and RealSense's coeffs use. With (x, y) = (X/Z, Y/Z) and
/// r^2 = x^2 + y^2:
///   x_d = x (1 + k1 r^2 + k2 r^4 + k3 r^6) + 2 p1 x y + p2 (r^2 + 2 x^2)
///   y_d = y (1 + k1 r^2 + k2 r^4 + k3 r^6) + p1 (r^2 + 2 y^2) + 2 p2 x y
/// and the pixel is (fx x_d + cx, fy y_d + cy). ViSP's one-coefficient model
/// (perspectiveProjWithDistortion) is k1 = kud with the others 0.
struct LensDistortion {
  double k1 = 0.0, k2 = 0.0, p1 = 0.0, p2 = 0.0, k3 = 0.0;

  bool isZero() const { return k1 == 0.0 && k2 == 0.0 && p1 == 0.0 && p2 == 0.0 && k3 == 0.0; }
  /// Distorted normalised coordinates of undistorted ones.
  Eigen::Vector2d distort(const Eigen::Vector2d& xy) const;
  /// Undistorted normalised coordinates of distorted ones (fixed-point
  /// iteration as OpenCV's undistortPoints; exact to < 1e-9 for the moderate
  /// distortion of RGB-D cameras).
  Eigen::Vector2d undistort(const Eigen::Vector2d& xy_distorted) const;

  bool operator==(const LensDistortion& o) const {
    return k1 == o.k1 && k2 == o.k2 && p1 == o.p1 && p2 == o.p2 && k3 == o.k3;
  }
  bool operator!=(const LensDistortion& o) const { return !(*this == o); }
};

/// JSON: {"k1":..,"k2":..,"p1":..,"p2":..,"k3":..}; missing keys are 0.
void to_json(nlohmann::json& j, const LensDistortion& d);
void from_json(const nlohmann::json& j, LensDistortion& d);

}  // namespace srp::rawlog
