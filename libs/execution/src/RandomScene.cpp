#include "srp/execution/RandomScene.h"

#include <random>

#include "srp/core/Error.h"
#include "srp/execution/PlacementPlanner.h"

namespace srp::execution {

CellDescription randomizeCell(const CellDescription& base, const std::string& sourceContainer, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> shift(-0.03, 0.03), turn(-0.2, 0.2), unit(0.0, 1.0);
  CellDescription cell = base;
  for (auto& o : cell.objects) {
    if (o.kind != CellObjectKind::Container) continue;
    const double yaw = srp::core::yawOf(o.X_world_object.linear()) + turn(rng);
    o.X_world_object.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    o.X_world_object.translation() += Eigen::Vector3d(shift(rng), shift(rng), 0.0);
  }
  const CellObject* box = cell.find(sourceContainer);
  if (!box || box->kind != CellObjectKind::Container)
    throw srp::core::InvalidInputError("randomizeCell: no container '" + sourceContainer + "' in the cell");
  const double ix = box->size_m.x() / 2 - box->wallThickness_m, iy = box->size_m.y() / 2 - box->wallThickness_m;
  constexpr double kGap_m = 0.01;
  std::vector<CellObject*> placed;
  for (auto& o : cell.objects) {
    if (o.kind != CellObjectKind::Part) continue;
    bool ok = false;
    for (int attempt = 0; attempt < 2000 && !ok; ++attempt) {
      const double yaw = 2.0 * M_PI * unit(rng);
      const double r = 0.5 * std::hypot(o.size_m.x(), o.size_m.y());  // bounding circle keeps it simple
      if (ix - r < 0 || iy - r < 0) break;
      const Eigen::Vector3d p_box((2 * unit(rng) - 1) * (ix - r), (2 * unit(rng) - 1) * (iy - r), box->wallThickness_m);
      srp::core::Pose3 X = srp::core::Pose3::Identity();
      X.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
      X.translation() = p_box;
      X = box->X_world_object * X;
      ok = true;
      for (const CellObject* q : placed) {
        const double rq = 0.5 * std::hypot(q->size_m.x(), q->size_m.y());
        if ((q->X_world_object.translation() - X.translation()).head<2>().norm() < r + rq + kGap_m) ok = false;
      }
      if (ok) o.X_world_object = X;
    }
    if (!ok)
      throw srp::core::InvalidInputError("randomizeCell: the parts do not fit in the " + sourceContainer +
                                         " (seed " + std::to_string(seed) + ")");
    placed.push_back(&o);
  }
  return cell;
}

}  // namespace srp::execution
