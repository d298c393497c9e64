#pragma once
// The acceptance tests' own answer to "could any placement satisfy this relation?",
// written without the planner's code: a brute-force search over the part's poses (a 1 mm
// grid, 2 mm on the open table, every 5 degrees of yaw) in the region the relation allows,
// with its own footprint geometry. A pose counts when the part rests on the table or
// wholly inside a container's walls, keeps kMinGap_m from every other part at its height,
// from the walls and the containers' outer walls, leaves the suction tool room beside the
// walls (below), lies on the table and within the arm's placing range, and the relation holds as PlacementPlanner::check() measures it after a
// placement (gaps > -1 mm, "next to" at most 30 mm, view directions within 45 degrees,
// "between" within the landmarks' larger half-width + 5 mm of their line, corners in
// their quadrant). When it finds no pose, the refusal is confirmed.
// Frames: world = table frame, z up, metres.

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "srp/core/ViewFrame.h"
#include "srp/execution/CellDescription.h"

namespace srp::execution::acceptance {

/// The least gap the cell keeps between parts and from walls (PlacementContext::Options::minClearance_m:
/// the SafetyChecker's 2 mm to container walls).
constexpr double kMinGap_m = 0.002;
constexpr double kCheckSlack_m = 0.001;        // the relation checks allow footprints 1 mm into each other
constexpr double kNeighbourMaxGap_m = 0.030;   // "next to": neighbourGap_m + neighbourTolerance_m
constexpr double kLateralSlack_m = 0.005;      // "between": relationTolerance_m
constexpr double kMinReach_m = 0.15, kMaxReach_m = 0.80;  // the arm's placing range (PlacementContext::Options)
constexpr double kFineStep_m = 0.001, kTableStep_m = 0.002;
/// The suction tool (sim/ur5/ur5.urdf, link suction_tool: a collision cylinder of radius
/// 20 mm from tool0 down to the tool centre point) is lowered straight down onto the part's
/// top, its axis through the part's centre (the executor grasps the top's centre and ends
/// every placement with a vertical descent). Wherever the part's top lies below a container
/// wall's top + kMinGap_m, the cylinder passes beside that wall, so the part's centre keeps
/// kToolRadius_m + kMinGap_m from it (the safety checker's 2 mm to container walls).
constexpr double kToolRadius_m = 0.020;
constexpr double kYawStep_rad = 5.0 * M_PI / 180.0;

/// A part's footprint: centre, yaw, half extents (world x, y).
struct Footprint {
  Eigen::Vector2d centre;
  double yaw = 0.0;
  Eigen::Vector2d half;
  static Footprint of(const CellObject& o) {
    const Eigen::Matrix3d R = o.X_world_object.linear();
    return {o.X_world_object.translation().head<2>(), std::atan2(R(1, 0), R(0, 0)), o.size_m.head<2>() / 2};
  }
  Eigen::Vector2d axis(int k) const {
    return k == 0 ? Eigen::Vector2d(std::cos(yaw), std::sin(yaw)) : Eigen::Vector2d(-std::sin(yaw), std::cos(yaw));
  }
  /// Half-width along the unit direction d.
  double extent(const Eigen::Vector2d& d) const {
    return std::abs(d.dot(axis(0))) * half.x() + std::abs(d.dot(axis(1))) * half.y();
  }
};

/// Largest gap between two footprints along their four axes (negative: overlapping).
inline double gapBetween(const Footprint& a, const Footprint& b) {
  double best = -1e9;
  for (const Footprint* f : {&a, &b})
    for (int k = 0; k < 2; ++k) {
      const Eigen::Vector2d n = f->axis(k);
      const double d = std::abs((b.centre - a.centre).dot(n));
      best = std::max(best, d - a.extent(n) - b.extent(n));
    }
  return best;
}

/// Smallest distance of the footprint to the container's inner walls (negative: over one).
inline double insideWalls(const Footprint& f, const CellObject& box) {
  const Footprint b = Footprint::of(box);
  const Eigen::Vector2d off = f.centre - b.centre;
  double worst = 1e9;
  for (int k = 0; k < 2; ++k) {
    const Eigen::Vector2d n = b.axis(k);
    worst = std::min(worst, b.half[k] - box.wallThickness_m - std::abs(off.dot(n)) - f.extent(n));
  }
  return worst;
}

/// Horizontal distance of point p from the container's nearest wall: its inner walls when
/// `inside` (p within them), else its outer outline.
inline double wallDistance(const CellObject& box, const Eigen::Vector2d& p, bool inside) {
  const Footprint b = Footprint::of(box);
  const Eigen::Vector2d off = p - b.centre;
  const double u = std::abs(off.dot(b.axis(0))), v = std::abs(off.dot(b.axis(1)));
  if (inside) return std::min(b.half.x() - box.wallThickness_m - u, b.half.y() - box.wallThickness_m - v);
  return std::hypot(std::max(u - b.half.x(), 0.0), std::max(v - b.half.y(), 0.0));
}

/// Does the tool lowered onto `mover` resting at bottom height z keep its clearance from
/// every container wall it comes level with? (kToolRadius_m above.)
inline bool toolFits(const CellDescription& scene, const CellObject& mover, const Footprint& f, double z,
                     const CellObject* floor) {
  for (const auto& c : scene.objects) {
    if (c.kind != CellObjectKind::Container) continue;
    const double wallTop = c.X_world_object.translation().z() + c.size_m.z();
    if (z + mover.size_m.z() >= wallTop + kMinGap_m) continue;  // the tool stays above these walls
    if (wallDistance(c, f.centre, &c == floor) < kToolRadius_m + kMinGap_m) return false;
  }
  return true;
}

struct Relation {
  enum Kind { In, Corner, Direction, NextTo, Between, OnTop } kind = In;
  const CellObject* a = nullptr;  ///< container (In, Corner) or landmark (A of Between)
  const CellObject* b = nullptr;  ///< B of Between
  Eigen::Vector2d direction = Eigen::Vector2d::Zero();  ///< Direction
  std::vector<Eigen::Vector2d> quadrant;                ///< Corner: its two view directions
};

/// The relation measured as the after-placement check measures it.
inline bool relationHolds(const Relation& r, const Footprint& f) {
  const Footprint a = Footprint::of(*r.a);
  switch (r.kind) {
    case Relation::In: return true;  // inside the walls: checked as the support
    case Relation::Corner:
      return std::all_of(r.quadrant.begin(), r.quadrant.end(),
                         [&](const Eigen::Vector2d& d) { return (f.centre - a.centre).dot(d) > 0.0; });
    case Relation::Direction: {
      const Eigen::Vector2d off = f.centre - a.centre, perp(-r.direction.y(), r.direction.x());
      const double along = off.dot(r.direction);
      return along > std::abs(off.dot(perp)) && along - a.extent(r.direction) - f.extent(r.direction) > -kCheckSlack_m;
    }
    case Relation::NextTo: {
      const Eigen::Vector2d off = f.centre - a.centre;
      const Eigen::Vector2d d = off.normalized();
      const double gap = off.norm() - a.extent(d) - f.extent(d);
      return gap > -kCheckSlack_m && gap <= kNeighbourMaxGap_m;
    }
    case Relation::Between: {
      const Footprint b = Footprint::of(*r.b);
      const double length = (b.centre - a.centre).norm();
      const Eigen::Vector2d u = (b.centre - a.centre) / length, perp(-u.y(), u.x());
      const double t = (f.centre - a.centre).dot(u), lateral = std::abs((f.centre - a.centre).dot(perp));
      return t - a.extent(u) - f.extent(u) > -kCheckSlack_m && length - t - b.extent(u) - f.extent(u) > -kCheckSlack_m &&
             lateral <= std::max(a.extent(perp), b.extent(perp)) + kLateralSlack_m;
    }
    case Relation::OnTop: return false;  // not searched (see anyPlacement)
  }
  return false;
}

/// May `mover` rest with footprint f (on the table or wholly inside a container; for In
/// and Corner inside r.a) keeping kMinGap_m from the other parts at its height and the walls?
inline bool restsFree(const CellDescription& scene, const CellObject& mover, const Relation& r, const Footprint& f) {
  const double reach = (f.centre - scene.X_world_base.translation().head<2>()).norm();
  if (reach < kMinReach_m || reach > kMaxReach_m) return false;
  const CellObject* floor = nullptr;
  for (const auto& c : scene.objects) {
    if (c.kind != CellObjectKind::Container) continue;
    if (insideWalls(f, c) >= kMinGap_m) floor = &c;
    else if (gapBetween(f, Footprint::of(c)) < kMinGap_m) return false;  // on a wall
  }
  if ((r.kind == Relation::In || r.kind == Relation::Corner) && floor != r.a) return false;
  if (!floor) {
    const Eigen::Vector2d p = f.centre - scene.tableCentre_m;
    if (std::abs(p.x()) + f.extent(Eigen::Vector2d::UnitX()) > scene.tableHalfExtents_m.x() ||
        std::abs(p.y()) + f.extent(Eigen::Vector2d::UnitY()) > scene.tableHalfExtents_m.y())
      return false;
  }
  const double z = floor ? floor->X_world_object.translation().z() + floor->wallThickness_m : 0.0;
  if (!toolFits(scene, mover, f, z, floor)) return false;
  for (const auto& o : scene.objects) {
    if (o.kind != CellObjectKind::Part || o.name == mover.name) continue;
    const double zo = o.X_world_object.translation().z();
    if (zo >= z + mover.size_m.z() - 1e-3 || z >= zo + o.size_m.z() - 1e-3) continue;  // above or below
    if (gapBetween(f, Footprint::of(o)) < kMinGap_m) return false;
  }
  return true;
}

/// A pose (centre, yaw) of `mover` satisfying `r` with the rules above, or nullopt.
/// OnTop: the landmark's top must be free and within reach.
inline std::optional<Footprint> anyPlacement(const CellDescription& scene, const CellObject& mover, const Relation& r) {
  if (r.kind == Relation::OnTop) {
    const double top = r.a->X_world_object.translation().z() + r.a->size_m.z();
    const Footprint a = Footprint::of(*r.a);
    for (const auto& o : scene.objects)
      if (o.kind == CellObjectKind::Part && o.name != mover.name && o.name != r.a->name &&
          std::abs(o.X_world_object.translation().z() - top) < 0.01 && gapBetween(a, Footprint::of(o)) < 0.0)
        return std::nullopt;
    const double reach = (a.centre - scene.X_world_base.translation().head<2>()).norm();
    if (reach < kMinReach_m || reach > kMaxReach_m) return std::nullopt;
    const Footprint f{a.centre, a.yaw, mover.size_m.head<2>() / 2};
    const CellObject* floor = nullptr;
    for (const auto& c : scene.objects)
      if (c.kind == CellObjectKind::Container && insideWalls(a, c) >= 0.0) floor = &c;
    if (!toolFits(scene, mover, f, top, floor)) return std::nullopt;
    return f;
  }
  // The region: the container (In, Corner) or a square around the landmark(s).
  const Footprint a = Footprint::of(*r.a);
  Eigen::Vector2d centre = a.centre, u = a.axis(0), v = a.axis(1);
  Eigen::Vector2d halfSize(0.45, 0.45);
  double step = kTableStep_m;
  if (r.kind == Relation::In || r.kind == Relation::Corner) {
    halfSize = a.half;
    step = kFineStep_m;
  } else if (r.kind == Relation::NextTo) {
    halfSize = Eigen::Vector2d::Constant(a.half.norm() + mover.size_m.head<2>().norm() / 2 + kNeighbourMaxGap_m);
    step = kFineStep_m;
  } else if (r.kind == Relation::Between) {
    const Footprint b = Footprint::of(*r.b);
    centre = (a.centre + b.centre) / 2;
    u = (b.centre - a.centre).normalized();
    v = Eigen::Vector2d(-u.y(), u.x());
    halfSize = Eigen::Vector2d((b.centre - a.centre).norm() / 2,
                               std::max(a.half.norm(), b.half.norm()) + kLateralSlack_m);
    step = kFineStep_m;
  }
  for (double x = -halfSize.x(); x <= halfSize.x(); x += step)
    for (double y = -halfSize.y(); y <= halfSize.y(); y += step)
      for (double yaw = 0.0; yaw < M_PI; yaw += kYawStep_rad) {
        const Footprint f{centre + x * u + y * v, yaw, mover.size_m.head<2>() / 2};
        if (relationHolds(r, f) && restsFree(scene, mover, r, f)) return f;
      }
  return std::nullopt;
}

}  // namespace srp::execution::acceptance
