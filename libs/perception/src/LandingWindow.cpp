#include "srp/perception/LandingWindow.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace srp::perception {

cv::Rect landingWindow(const core::CameraIntrinsics& Ks, float minDepth_m, float maxDepth_m,
                       const core::Pose3& X_dst_src, const core::CameraIntrinsics& Kd) {
  const cv::Rect whole(0, 0, Ks.width_px, Ks.height_px);
  if (!(minDepth_m > 0.f) || !(maxDepth_m >= minDepth_m)) return whole;
  const Eigen::Matrix3d R = X_dst_src.linear();
  const Eigen::Vector3d t = X_dst_src.translation();
  // A source point (x z, y z, z) has the destination depth a z + t_z, a = R.row(2) (x, y, 1): affine in
  // (x, y), so within its values at the source image's corners.
  double aMin = std::numeric_limits<double>::max(), aMax = std::numeric_limits<double>::lowest();
  for (const double u : {-0.5, Ks.width_px - 0.5})
    for (const double v : {-0.5, Ks.height_px - 0.5}) {
      const double a = R.row(2).dot(Eigen::Vector3d((u - Ks.cx_px) / Ks.fx_px, (v - Ks.cy_px) / Ks.fy_px, 1.0));
      aMin = std::min(aMin, a);
      aMax = std::max(aMax, a);
    }
  if (aMin <= 0.0) return whole;
  const double qMin = std::max(1e-3, minDepth_m * aMin + t.z()), qMax = maxDepth_m * aMax + t.z();
  if (qMax <= qMin) return whole;
  // The frustum's 8 corners (the destination pixels' outer edges at those depths) in the source camera.
  const Eigen::Matrix3d Rt = R.transpose();
  double uMin = std::numeric_limits<double>::max(), uMax = std::numeric_limits<double>::lowest();
  double vMin = uMin, vMax = uMax;
  for (const double u : {-0.5, Kd.width_px - 0.5})
    for (const double v : {-0.5, Kd.height_px - 0.5})
      for (const double q : {qMin, qMax}) {
        const Eigen::Vector3d p_dst((u - Kd.cx_px) / Kd.fx_px * q, (v - Kd.cy_px) / Kd.fy_px * q, q);
        const Eigen::Vector3d p_src = Rt * (p_dst - t);
        if (p_src.z() <= 1e-6) return whole;
        const double us = Ks.fx_px * p_src.x() / p_src.z() + Ks.cx_px, vs = Ks.fy_px * p_src.y() / p_src.z() + Ks.cy_px;
        uMin = std::min(uMin, us);
        uMax = std::max(uMax, us);
        vMin = std::min(vMin, vs);
        vMax = std::max(vMax, vs);
      }
  constexpr double kMargin_px = 2.0;  // the warp's float rounding, with room to spare
  const double lo = -1e6, hi = 1e6;   // far outside any image: no overflow in the casts below
  const int u0 = static_cast<int>(std::floor(std::clamp(uMin - kMargin_px, lo, hi)));
  const int u1 = static_cast<int>(std::ceil(std::clamp(uMax + kMargin_px, lo, hi)));
  const int v0 = static_cast<int>(std::floor(std::clamp(vMin - kMargin_px, lo, hi)));
  const int v1 = static_cast<int>(std::ceil(std::clamp(vMax + kMargin_px, lo, hi)));
  return cv::Rect(cv::Point(u0, v0), cv::Point(u1 + 1, v1 + 1)) & whole;
}

}  // namespace srp::perception
