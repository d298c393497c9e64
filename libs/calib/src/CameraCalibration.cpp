#include "srp/calib/CameraCalibration.h"

#include <cmath>

namespace srp::calib {

Eigen::Vector2d CameraCalibration::projectDistorted(const Eigen::Vector3d& p) const {
  const double x = p.x() / p.z(), y = p.y() / p.z();
  const double k = 1.0 + kud * (x * x + y * y);
  return {intrinsics.cx_px + intrinsics.fx_px * x * k, intrinsics.cy_px + intrinsics.fy_px * y * k};
}

Eigen::Vector2d CameraCalibration::undistortPixel(const Eigen::Vector2d& d) const {
  const auto& K = intrinsics;
  const double xd = (d.x() - K.cx_px) / K.fx_px, yd = (d.y() - K.cy_px) / K.fy_px;
  // Solve r_d = r (1 + kud r^2) for r along the ray (Newton from r = r_d).
  const double rd = std::hypot(xd, yd);
  double r = rd;
  for (int i = 0; i < 30 && rd > 0.0; ++i) {
    const double f = r * (1.0 + kud * r * r) - rd;
    const double df = 1.0 + 3.0 * kud * r * r;
    if (df == 0.0) break;
    r -= f / df;
  }
  const double s = rd > 0.0 ? r / rd : 1.0;
  return {K.cx_px + K.fx_px * xd * s, K.cy_px + K.fy_px * yd * s};
}

double CameraCalibration::fitKdu(const srp::core::CameraIntrinsics& K, double kud) {
  if (kud == 0.0) return 0.0;
  CameraCalibration c;
  c.intrinsics = K;
  c.kud = kud;
  // u - u_d = (u_d - u0) kdu r_d^2: linear least squares over a pixel grid.
  double num = 0.0, den = 0.0;
  const int n = 40;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j) {
      const Eigen::Vector2d d((K.width_px - 1) * double(i) / n, (K.height_px - 1) * double(j) / n);
      const Eigen::Vector2d u = c.undistortPixel(d);
      const double xd = (d.x() - K.cx_px) / K.fx_px, yd = (d.y() - K.cy_px) / K.fy_px;
      const double r2 = xd * xd + yd * yd;
      const Eigen::Vector2d a((d.x() - K.cx_px) * r2, (d.y() - K.cy_px) * r2);
      num += a.dot(u - d);
      den += a.dot(a);
    }
  return den > 0.0 ? num / den : 0.0;
}

bool CameraCalibration::operator==(const CameraCalibration& o) const {
  return name == o.name && intrinsics == o.intrinsics && kud == o.kud && kdu == o.kdu;
}

}  // namespace srp::calib
