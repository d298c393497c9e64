#include "srp/execution/PlacementPlanner.h"

#include <algorithm>
#include <cctype>
#include <cmath>

namespace srp::execution {
namespace {

using srp::core::Pose3;

double yawOfPose(const Pose3& X) { return srp::core::yawOf(X.linear()); }

Pose3 uprightPose(const Eigen::Vector3d& p, double yaw) {
  Pose3 X = Pose3::Identity();
  X.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  X.translation() = p;
  return X;
}

/// Footprint rectangle corners of `o` placed at X (world x, y).
std::array<Eigen::Vector2d, 4> footprint(const Eigen::Vector3d& size, const Pose3& X, double inflate) {
  std::array<Eigen::Vector2d, 4> c;
  const double hx = size.x() / 2 + inflate, hy = size.y() / 2 + inflate;
  int i = 0;
  for (double sx : {-1.0, 1.0})
    for (double sy : {-1.0, 1.0}) c[i++] = (X * Eigen::Vector3d(sx * hx, sy * hy, 0)).head<2>();
  return c;
}

/// Separating-axis test of two footprints given their rectangle axes.
bool overlaps(const std::array<Eigen::Vector2d, 4>& a, const Pose3& Xa, const std::array<Eigen::Vector2d, 4>& b,
              const Pose3& Xb) {
  const Eigen::Vector2d axes[4] = {Xa.linear().col(0).head<2>(), Xa.linear().col(1).head<2>(),
                                   Xb.linear().col(0).head<2>(), Xb.linear().col(1).head<2>()};
  for (const auto& axis : axes) {
    double amin = 1e9, amax = -1e9, bmin = 1e9, bmax = -1e9;
    for (const auto& p : a) amin = std::min(amin, p.dot(axis)), amax = std::max(amax, p.dot(axis));
    for (const auto& p : b) bmin = std::min(bmin, p.dot(axis)), bmax = std::max(bmax, p.dot(axis));
    if (amax < bmin || bmax < amin) return false;
  }
  return true;
}

/// Half-width of a rectangle of `size` with yaw `yaw` along world direction d.
double support(const Eigen::Vector3d& size, double yaw, const Eigen::Vector2d& d) {
  const Eigen::Vector2d ax(std::cos(yaw), std::sin(yaw)), ay(-std::sin(yaw), std::cos(yaw));
  return std::abs(d.dot(ax)) * size.x() / 2 + std::abs(d.dot(ay)) * size.y() / 2;
}

}  // namespace

bool PlacementPlanner::isInside(const CellObject& part, const CellObject& container) {
  const Eigen::Vector3d p = container.X_world_object.inverse() * part.X_world_object.translation();
  return std::abs(p.x()) <= container.size_m.x() / 2 - container.wallThickness_m &&
         std::abs(p.y()) <= container.size_m.y() / 2 - container.wallThickness_m;
}

bool PlacementPlanner::isFree(const CellDescription& scene, const CellObject& part, const Pose3& X) const {
  const auto mine = footprint(part.size_m, X, options_.clearance_m / 2);
  for (const auto& o : scene.objects) {
    if (o.kind != CellObjectKind::Part || o.name == part.name) continue;
    if (overlaps(mine, X, footprint(o.size_m, o.X_world_object, options_.clearance_m / 2), o.X_world_object))
      return false;
  }
  return true;
}

Placement PlacementPlanner::place(const CellDescription& scene, const CellObject& part,
                                  const ExecutionStep& step) const {
  Placement out;
  const CellObject* container = nullptr;
  const CellObject* neighbour = nullptr;
  const SceneGrounder grounder(scene, options_.grounding);
  auto landmarkOf = [&](const SpatialRelation& rel, CellObjectKind kind) -> const CellObject* {
    try {
      return &grounder.ground(rel.landmark, {}, kind);
    } catch (const GroundingError& e) {
      out.reason = "target '" + rel.relation + " the " + rel.landmark.describe() + "': " + e.what();
      return nullptr;
    }
  };
  for (const auto& rel : step.target) {
    if (isContainmentRelation(rel.relation)) {
      container = landmarkOf(rel, CellObjectKind::Container);
      if (!container) return out;
    } else if (isNeighbourRelation(rel.relation)) {
      neighbour = landmarkOf(rel, CellObjectKind::Part);
      if (!neighbour) return out;
      if (neighbour->name == part.name) {
        out.reason = "the " + part.name + " cannot be placed next to itself";
        return out;
      }
    } else {
      out.reason = "unknown target relation '" + rel.relation + "' (known: in/into/to, next to/beside/adjacent to)";
      return out;
    }
  }
  if (!container && neighbour) {
    // "beside the star" with the star in a container: the part goes in there too.
    for (const auto& o : scene.objects)
      if (o.kind == CellObjectKind::Container && isInside(*neighbour, o)) container = &o;
  }
  if (!container && !neighbour) {
    out.reason = "the instruction gives no target location for the " + part.name;
    return out;
  }
  if (container) out.container = container->name;
  if (neighbour) out.neighbour = neighbour->name;

  const double yaw = container ? yawOfPose(container->X_world_object) : yawOfPose(neighbour->X_world_object);
  const double zSupport = container ? container->X_world_object.translation().z() + container->wallThickness_m : 0.0;
  // Is the whole footprint (plus margin) inside the container's inner walls?
  auto fitsContainer = [&](const Pose3& X) {
    if (!container) return true;
    const Pose3 X_c = container->X_world_object.inverse() * X;
    const double c = std::abs(std::cos(yawOfPose(X_c))), s = std::abs(std::sin(yawOfPose(X_c)));
    const double ex = c * part.size_m.x() / 2 + s * part.size_m.y() / 2;
    const double ey = s * part.size_m.x() / 2 + c * part.size_m.y() / 2;
    const double ix = container->size_m.x() / 2 - container->wallThickness_m - options_.wallMargin_m;
    const double iy = container->size_m.y() / 2 - container->wallThickness_m - options_.wallMargin_m;
    return std::abs(X_c.translation().x()) + ex <= ix + 1e-9 && std::abs(X_c.translation().y()) + ey <= iy + 1e-9;
  };

  if (neighbour) {
    const Eigen::Vector2d c = neighbour->X_world_object.translation().head<2>();
    const double yawN = yawOfPose(neighbour->X_world_object);
    std::vector<Eigen::Vector2d> directions;
    for (int k = 0; k < 4; ++k) directions.emplace_back(std::cos(yaw + k * M_PI / 2), std::sin(yaw + k * M_PI / 2));
    if (step.demoOffsetFromNeighbour_m && step.demoOffsetFromNeighbour_m->norm() > 1e-6) {
      const Eigen::Vector2d d0 = step.demoOffsetFromNeighbour_m->normalized();
      std::stable_sort(directions.begin(), directions.end(),
                       [&](const auto& a, const auto& b) { return a.dot(d0) > b.dot(d0); });
    } else if (container) {
      // No demonstration: the side with the most room inside the container first.
      const Eigen::Vector2d cc = container->X_world_object.translation().head<2>();
      std::stable_sort(directions.begin(), directions.end(),
                       [&](const auto& a, const auto& b) { return a.dot(cc - c) > b.dot(cc - c); });
    }
    for (const auto& d : directions) {
      const double distance = support(neighbour->size_m, yawN, d) + support(part.size_m, yaw, d) + options_.neighbourGap_m;
      Eigen::Vector2d p = c + distance * d;
      if (container) {
        // Slide along the neighbour's side to stay inside the walls, as long as the
        // two footprints still face each other.
        const Pose3& X_wc = container->X_world_object;
        const Eigen::Vector2d perp(-d.y(), d.x());
        const Eigen::Vector2d ax = X_wc.linear().col(0).head<2>(), ay = X_wc.linear().col(1).head<2>();
        const Eigen::Vector2d centre_c = X_wc.translation().head<2>();
        const double inner[2] = {container->size_m.x() / 2 - container->wallThickness_m - options_.wallMargin_m,
                                 container->size_m.y() / 2 - container->wallThickness_m - options_.wallMargin_m};
        const Eigen::Vector2d axes[2] = {ax, ay};
        for (int k = 0; k < 2; ++k) {
          if (std::abs(axes[k].dot(perp)) < 0.5) continue;  // only the coordinate along the side
          const double limit = inner[k] - support(part.size_m, yaw, axes[k]);
          const double coord = (p - centre_c).dot(axes[k]);
          const double clamped = std::clamp(coord, -limit, limit);
          p += (clamped - coord) * axes[k];
        }
        const double facing = support(neighbour->size_m, yawN, perp) + support(part.size_m, yaw, perp) - 0.01;
        if (std::abs((p - c).dot(perp)) > facing) continue;
      }
      const Pose3 X = uprightPose(Eigen::Vector3d(p.x(), p.y(), zSupport), yaw);
      if (fitsContainer(X) && isFree(scene, part, X)) {
        out.X_world_object = X;
        return out;
      }
    }
    out.reason = "no free place next to the " + neighbour->name +
                 (container ? " inside the " + container->name : std::string()) + " for the " + part.name;
    return out;
  }

  // "in X": grid over the inner footprint, nearest to the preferred point first.
  const double ix = container->size_m.x() / 2 - container->wallThickness_m - options_.wallMargin_m - part.size_m.x() / 2;
  const double iy = container->size_m.y() / 2 - container->wallThickness_m - options_.wallMargin_m - part.size_m.y() / 2;
  if (ix < 0 || iy < 0) {
    out.reason = "the " + part.name + " does not fit in the " + container->name;
    return out;
  }
  // Without a demonstration: the inner corner nearest to where the part comes from,
  // which leaves the rest of the container free for its neighbours.
  const Eigen::Vector3d from_c = container->X_world_object.inverse() * part.X_world_object.translation();
  const Eigen::Vector2d corner(from_c.x() < 0 ? -ix : ix, from_c.y() < 0 ? -iy : iy);
  const Eigen::Vector2d preferred = step.demoPositionInContainer_m.value_or(corner);
  std::vector<Eigen::Vector2d> candidates;
  for (double x = -ix; x <= ix + 1e-9; x += options_.gridStep_m)
    for (double y = -iy; y <= iy + 1e-9; y += options_.gridStep_m) candidates.emplace_back(x, y);
  std::sort(candidates.begin(), candidates.end(), [&](const auto& a, const auto& b) {
    return (a - preferred).squaredNorm() < (b - preferred).squaredNorm();
  });
  for (const auto& c : candidates) {
    Pose3 X = container->X_world_object * uprightPose(Eigen::Vector3d(c.x(), c.y(), container->wallThickness_m), 0.0);
    if (isFree(scene, part, X)) {
      out.X_world_object = X;
      return out;
    }
  }
  out.reason = "the " + container->name + " has no free place left for the " + part.name;
  return out;
}

}  // namespace srp::execution
