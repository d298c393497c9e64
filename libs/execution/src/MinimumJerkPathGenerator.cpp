#include "srp/execution/MinimumJerkPathGenerator.h"

#include <algorithm>
#include <cmath>

#include "srp/core/Error.h"

namespace srp::execution {

void appendPath(CartesianPath& path, const CartesianPath& next) {
  if (next.empty()) return;
  if (path.empty()) {
    path = next;
    return;
  }
  const double t0 = path.back().t_s;
  for (std::size_t i = 1; i < next.size(); ++i) path.push_back({t0 + next[i].t_s, next[i].X_world_tcp});
}

CartesianPath MinimumJerkPathGenerator::straight(const srp::core::Pose3& a, const srp::core::Pose3& b,
                                                 double dt_s) const {
  if (!(dt_s > 0.0)) throw srp::core::InvalidInputError("MinimumJerkPathGenerator: dt must be > 0 s");
  const double distance = (b.translation() - a.translation()).norm();
  const double angle = srp::core::rotationAngleBetween(a.linear(), b.linear());
  const double T = std::max({options_.minSegmentDuration_s, distance / options_.meanSpeed_mps,
                             angle / options_.meanAngularSpeed_radps});
  const int n = std::max(2, static_cast<int>(std::ceil(T / dt_s)));
  const Eigen::Quaterniond qa(a.linear()), qb(b.linear());
  CartesianPath path;
  path.reserve(n + 1);
  for (int i = 0; i <= n; ++i) {
    const double tau = static_cast<double>(i) / n;
    const double s = tau * tau * tau * (10.0 - 15.0 * tau + 6.0 * tau * tau);
    srp::core::Pose3 X = srp::core::Pose3::Identity();
    X.linear() = qa.slerp(s, qb).toRotationMatrix();
    X.translation() = a.translation() + s * (b.translation() - a.translation());
    path.push_back({tau * T, X});
  }
  path.back().X_world_tcp = b;
  return path;
}

CartesianPath MinimumJerkPathGenerator::generate(srp::core::SkillType skill, int, const srp::core::Pose3& a,
                                                 const srp::core::Pose3& b, double dt_s) const {
  if (skill != srp::core::SkillType::Reach && skill != srp::core::SkillType::Move)
    throw srp::core::InvalidInputError("MinimumJerkPathGenerator: paths exist for Reach and Move only, not " +
                                       srp::core::toString(skill));
  const double zCross = std::max({options_.clearanceHeight_m, a.translation().z(), b.translation().z()});
  srp::core::Pose3 up = a, over = b;
  up.translation().z() = zCross;
  over.translation().z() = zCross;
  // Turn the tool during the crossing, not while inside a container.
  over.linear() = b.linear();
  CartesianPath path;
  srp::core::Pose3 from = a;
  for (const srp::core::Pose3& to : {up, over, b}) {
    if ((to.translation() - from.translation()).norm() < 1e-3 &&
        srp::core::rotationAngleBetween(to.linear(), from.linear()) < 1e-3)
      continue;
    appendPath(path, straight(from, to, dt_s));
    from = to;
  }
  if (path.empty()) path = {{0.0, a}, {options_.minSegmentDuration_s, b}};
  return path;
}

}  // namespace srp::execution
