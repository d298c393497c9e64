#include "srp/execution/PlacementContext.h"

#include <algorithm>

#include "PlacementGeometry.h"

namespace srp::execution {

using namespace placement;

PlacementContext::PlacementContext(const CellDescription& scene, const CellObject& part, const Options& options)
    : scene_(scene), part_(part), options_(options), view_(scene.viewFrame(options.grounding.viewpoint)) {}

const CellObject* PlacementContext::containerOf(const CellObject& o) const {
  for (const auto& c : scene_.objects)
    if (c.kind == CellObjectKind::Container && isInside(o, c)) return &c;
  return nullptr;
}

bool PlacementContext::fitsInside(const CellObject& container, const Pose3& X) const {
  return marginToInnerWalls(part_.size_m, X, container) >= options_.wallMargin_m - 1e-9 &&
         distanceToWalls(container, X.translation().head<2>()) >= toolClearanceFrom(container, X) - 1e-9;
}

double PlacementContext::toolClearanceFrom(const CellObject& container, const Pose3& X) const {
  return placement::toolClearanceFrom(options_.toolClearance_m, options_.minClearance_m, part_.size_m, X.translation().z(), container);
}

bool PlacementContext::fitsTable(const Pose3& X) const {
  const Eigen::Vector2d p = X.translation().head<2>() - scene_.tableCentre_m;
  const double yaw = yawOfPose(X);
  if (std::abs(p.x()) + support(part_.size_m, yaw, Eigen::Vector2d::UnitX()) > scene_.tableHalfExtents_m.x() ||
      std::abs(p.y()) + support(part_.size_m, yaw, Eigen::Vector2d::UnitY()) > scene_.tableHalfExtents_m.y())
    return false;
  const auto mine = footprint(part_.size_m, X, options_.wallMargin_m);
  for (const auto& o : scene_.objects) {
    if (o.kind != CellObjectKind::Container) continue;
    if (overlaps(mine, X, footprint(o.size_m, o.X_world_object, 0.0), o.X_world_object)) return false;
    if (distanceToWalls(o, X.translation().head<2>()) < toolClearanceFrom(o, X) - 1e-9) return false;
  }
  return true;
}

bool PlacementContext::inReach(const Pose3& X) const {
  const double r = (X.translation().head<2>() - scene_.X_world_base.translation().head<2>()).norm();
  return r >= options_.minReach_m && r <= options_.maxReach_m;
}

bool PlacementContext::isFree(const Pose3& X) const {
  const double half = options_.clearance_m / 2;
  for (const auto& o : scene_.objects) {
    if (o.kind != CellObjectKind::Part || o.name == part_.name) continue;
    if (!verticalOverlap(part_, X.translation().z(), o)) continue;  // stacked above or below
    if (overlaps(footprint(part_.size_m, X, half), X, footprint(o.size_m, o.X_world_object, half), o.X_world_object))
      return false;
  }
  return true;
}

std::vector<double> PlacementContext::turns() const {
  const bool square = std::abs(part_.size_m.x() - part_.size_m.y()) <= 1e-3;
  const double range = square ? M_PI / 2 : M_PI;
  std::vector<double> out;
  for (double t = 0.0; t < range - 1e-9; t += options_.turnStep_rad) out.push_back(t);
  return out;
}

std::optional<Pose3> PlacementContext::rest(const Eigen::Vector2d& p, double yaw, const CellObject* container,
                                            bool checkReach) const {
  auto reachable = [&](const Pose3& X) { return !checkReach || inReach(X); };
  if (container) {
    const Pose3 X = uprightPose(
        Eigen::Vector3d(p.x(), p.y(), container->X_world_object.translation().z() + container->wallThickness_m), yaw);
    if (fitsInside(*container, X) && reachable(X) && isFree(X)) return X;
    return std::nullopt;
  }
  Pose3 X = uprightPose(Eigen::Vector3d(p.x(), p.y(), 0.0), yaw);
  // A table place that falls wholly inside a container rests on its floor instead.
  for (const auto& o : scene_.objects)
    if (o.kind == CellObjectKind::Container && fitsInside(o, X)) {
      Pose3 onFloor = X;
      onFloor.translation().z() = o.X_world_object.translation().z() + o.wallThickness_m;
      if (reachable(onFloor) && isFree(onFloor)) return onFloor;
    }
  if (fitsTable(X) && reachable(X) && isFree(X)) return X;
  return std::nullopt;
}

PlacementContext::Options PlacementContext::Options::tight() const {
  PlacementContext::Options o = *this;
  o.clearance_m = o.wallMargin_m = minClearance_m;
  o.gridStep_m = gridStep_m / 2;
  o.turnStep_rad = tightTurnStep_rad;
  return o;
}

}  // namespace srp::execution
