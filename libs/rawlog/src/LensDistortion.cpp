#include "srp/rawlog/LensDistortion.h"

#include <nlohmann/json.hpp>

namespace srp::rawlog {

Eigen::Vector2d LensDistortion::distort(const Eigen::Vector2d& xy) const {
  const double x = xy.x(), y = xy.y(), r2 = x * x + y * y;
  const double radial = 1.0 + r2 * (k1 + r2 * (k2 + r2 * k3));
  return {x * radial + 2.0 * p1 * x * y + p2 * (r2 + 2.0 * x * x),
          y * radial + p1 * (r2 + 2.0 * y * y) + 2.0 * p2 * x * y};
}

Eigen::Vector2d LensDistortion::undistort(const Eigen::Vector2d& xy_distorted) const {
  if (isZero()) return xy_distorted;
  Eigen::Vector2d xy = xy_distorted;
  for (int i = 0; i < 30; ++i) {
    const double x = xy.x(), y = xy.y(), r2 = x * x + y * y;
    const double radial = 1.0 + r2 * (k1 + r2 * (k2 + r2 * k3));
    const Eigen::Vector2d tangential(2.0 * p1 * x * y + p2 * (r2 + 2.0 * x * x), p1 * (r2 + 2.0 * y * y) + 2.0 * p2 * x * y);
    const Eigen::Vector2d next = (xy_distorted - tangential) / radial;
    if ((next - xy).squaredNorm() < 1e-24) return next;
    xy = next;
  }
  return xy;
}

void to_json(nlohmann::json& j, const LensDistortion& d) {
  j = nlohmann::json{{"k1", d.k1}, {"k2", d.k2}, {"p1", d.p1}, {"p2", d.p2}, {"k3", d.k3}};
}

void from_json(const nlohmann::json& j, LensDistortion& d) {
  d.k1 = j.value("k1", 0.0);
  d.k2 = j.value("k2", 0.0);
  d.p1 = j.value("p1", 0.0);
  d.p2 = j.value("p2", 0.0);
  d.k3 = j.value("k3", 0.0);
}

}  // namespace srp::rawlog
