#pragma once
// A small ray-cast RGB-D world of known geometry for fast unit tests: a table
// (top at z = 0 of the table frame, z up), a floor below it, two walls, and
// boxes (solid, or open boxes built from a floor and four walls) standing on
// or above the table. Each pixel's depth is the exact distance along the
// optical axis to the first surface its ray meets; its colour is that
// surface's, shaded by the angle to the ray (so faces differ a little, as in a
// real image).
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/core.hpp>
#include <vector>

#include "srp/core/CameraIntrinsics.h"
#include "srp/core/Pose.h"
#include "srp/rawlog/RgbdFrame.h"

namespace srp::perception::testing {

/// An oriented box in the table frame: centre, half extents, yaw about z, colour (BGR).
struct BoxPrimitive {
  Eigen::Vector3d centre_m = Eigen::Vector3d::Zero();
  Eigen::Vector3d half_m = Eigen::Vector3d::Constant(0.02);
  double yaw_rad = 0.0;
  cv::Vec3b bgr{128, 128, 128};
};

/// A solid box of `size_m` whose bottom face's centre is at `bottom_m`.
inline BoxPrimitive solidBox(const Eigen::Vector3d& bottom_m, const Eigen::Vector3d& size_m, cv::Vec3b bgr,
                         double yaw_rad = 0.0) {
  return {bottom_m + Eigen::Vector3d(0, 0, size_m.z() / 2), size_m / 2, yaw_rad, bgr};
}

/// An open box (a bin) of outer size `size_m` standing at `bottom_m`: a floor and four walls `wall_m` thick.
inline std::vector<BoxPrimitive> openBox(const Eigen::Vector3d& bottom_m, const Eigen::Vector3d& size_m, double wall_m,
                                     cv::Vec3b bgr) {
  const Eigen::Vector3d s = size_m;
  const double t = wall_m;
  const Eigen::Vector3d b = bottom_m;
  return {solidBox(b, {s.x(), s.y(), t}, bgr), solidBox(b + Eigen::Vector3d(s.x() / 2 - t / 2, 0, 0), {t, s.y(), s.z()}, bgr),
          solidBox(b + Eigen::Vector3d(-s.x() / 2 + t / 2, 0, 0), {t, s.y(), s.z()}, bgr),
          solidBox(b + Eigen::Vector3d(0, s.y() / 2 - t / 2, 0), {s.x(), t, s.z()}, bgr),
          solidBox(b + Eigen::Vector3d(0, -s.y() / 2 + t / 2, 0), {s.x(), t, s.z()}, bgr)};
}

/// The camera at `eye_m` looking at `target_m` (table frame), image x right, y down: X_table_camera.
inline core::Pose3 lookAt(const Eigen::Vector3d& eye_m, const Eigen::Vector3d& target_m) {
  const Eigen::Vector3d z = (target_m - eye_m).normalized();
  const Eigen::Vector3d x = z.cross(Eigen::Vector3d::UnitZ()).normalized();
  core::Pose3 X = core::Pose3::Identity();
  X.linear().col(0) = x;
  X.linear().col(1) = z.cross(x);
  X.linear().col(2) = z;
  X.translation() = eye_m;
  return X;
}

struct BoxWorld {
  core::CameraIntrinsics intrinsics{300.0, 300.0, 159.5, 119.5, 320, 240};
  Eigen::Vector2d tableMin_m{-0.6, -0.35}, tableMax_m{0.6, 0.55};
  cv::Vec3b tableBgr{150, 175, 190};
  double floorZ_m = -0.75;
  double backWallY_m = 1.0, sideWallX_m = -1.1;  ///< walls (planes) behind and left of the table
  std::vector<BoxPrimitive> boxes;

  /// The frame seen by a camera at X_table_camera.
  rawlog::RgbdFrame render(const core::Pose3& X_table_camera, int index, double t_s) const {
    const auto& k = intrinsics;
    rawlog::RgbdFrame f;
    f.index = index;
    f.t_s = t_s;
    f.intrinsics = k;
    f.colour_bgr8 = cv::Mat(k.height_px, k.width_px, CV_8UC3, cv::Scalar(60, 60, 60));
    f.depth_m = cv::Mat(k.height_px, k.width_px, CV_32FC1, cv::Scalar(0.0f));
    const Eigen::Matrix3d R = X_table_camera.linear();
    const Eigen::Vector3d o = X_table_camera.translation();
    for (int v = 0; v < k.height_px; ++v)
      for (int u = 0; u < k.width_px; ++u) {
        const Eigen::Vector3d d = R * Eigen::Vector3d((u - k.cx_px) / k.fx_px, (v - k.cy_px) / k.fy_px, 1.0);
        double best = std::numeric_limits<double>::infinity();
        Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
        cv::Vec3b colour(60, 60, 60);
        const auto plane = [&](int axis, double at, const Eigen::Vector3d& n, cv::Vec3b c, bool tableOnly) {
          if (std::abs(d(axis)) < 1e-12) return;
          const double s = (at - o(axis)) / d(axis);
          if (!(s > 1e-6) || s >= best) return;
          const Eigen::Vector3d p = o + s * d;
          if (tableOnly && (p.x() < tableMin_m.x() || p.x() > tableMax_m.x() || p.y() < tableMin_m.y() ||
                            p.y() > tableMax_m.y()))
            return;
          best = s, normal = n, colour = c;
        };
        plane(2, 0.0, Eigen::Vector3d::UnitZ(), tableBgr, true);
        plane(2, floorZ_m, Eigen::Vector3d::UnitZ(), cv::Vec3b(90, 100, 110), false);
        plane(1, backWallY_m, -Eigen::Vector3d::UnitY(), cv::Vec3b(200, 200, 195), false);
        plane(0, sideWallX_m, Eigen::Vector3d::UnitX(), cv::Vec3b(180, 190, 190), false);
        for (const auto& b : boxes) {
          // Slabs in the box frame.
          const Eigen::Matrix3d Rb = Eigen::AngleAxisd(b.yaw_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix();
          const Eigen::Vector3d ob = Rb.transpose() * (o - b.centre_m), db = Rb.transpose() * d;
          double tNear = -std::numeric_limits<double>::infinity(), tFar = std::numeric_limits<double>::infinity();
          int axisNear = 0;
          bool miss = false;
          for (int a = 0; a < 3 && !miss; ++a) {
            if (std::abs(db(a)) < 1e-12) {
              miss = std::abs(ob(a)) > b.half_m(a);
              continue;
            }
            double t1 = (-b.half_m(a) - ob(a)) / db(a), t2 = (b.half_m(a) - ob(a)) / db(a);
            if (t1 > t2) std::swap(t1, t2);
            if (t1 > tNear) tNear = t1, axisNear = a;
            tFar = std::min(tFar, t2);
            miss = tNear > tFar;
          }
          if (miss || !(tNear > 1e-6) || tNear >= best) continue;
          Eigen::Vector3d n = Eigen::Vector3d::Zero();
          n(axisNear) = db(axisNear) > 0 ? -1.0 : 1.0;
          best = tNear, normal = Rb * n, colour = b.bgr;
        }
        if (!std::isfinite(best)) continue;
        const double shade = 0.75 + 0.25 * std::abs(normal.dot(d.normalized()));
        f.colour_bgr8.at<cv::Vec3b>(v, u) = cv::Vec3b(cv::saturate_cast<uchar>(colour[0] * shade),
                                                     cv::saturate_cast<uchar>(colour[1] * shade),
                                                     cv::saturate_cast<uchar>(colour[2] * shade));
        f.depth_m.at<float>(v, u) = static_cast<float>(best);  // d has unit optical-axis component
      }
    return f;
  }
};

}  // namespace srp::perception::testing
