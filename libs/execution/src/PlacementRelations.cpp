#include "srp/execution/PlacementRelations.h"

#include <algorithm>
#include <cmath>

#include "PlacementGeometry.h"

namespace srp::execution {
namespace {

using namespace placement;

/// Appends allowed poses up to the caller's limit.
struct Collector {
  PlacementCandidates& out;
  std::size_t limit;
  bool full() const { return out.poses.size() >= limit; }
  void add(const Pose3& X, const std::string& container, bool tight = false) {
    out.poses.push_back({X, container, "", tight});
  }
};

void sortByDistance(std::vector<Eigen::Vector2d>& points, const Eigen::Vector2d& p0) {
  std::stable_sort(points.begin(), points.end(),
                   [&](const auto& a, const auto& b) { return (a - p0).squaredNorm() < (b - p0).squaredNorm(); });
}

std::string where(const CellObject* container) {
  return container ? " inside the " + container->name : std::string(" on the table");
}

const CellObject* containerOf(const PlacementContext& ctx, const PlacementTarget& t) {
  return t.container.empty() ? nullptr : ctx.scene().find(t.container);
}

/// The inner corner (container frame, x, y) the part goes nearest to: the named corner,
/// else the one nearest to where the part comes from; ix, iy: the centre's free half-extents.
Eigen::Vector2d preferredCorner(const PlacementContext& ctx, const PlacementTarget& t, const CellObject& container,
                                double ix, double iy) {
  const Eigen::Vector3d from_c = container.X_world_object.inverse() * ctx.part().X_world_object.translation();
  Eigen::Vector2d side(from_c.x(), from_c.y());
  if (!t.cornerDirections.empty()) {
    const Eigen::Matrix2d R_wc = container.X_world_object.linear().topLeftCorner<2, 2>();
    side = R_wc.transpose() * (t.cornerDirections[0] + t.cornerDirections[1]);
  }
  return {side.x() < 0 ? -ix : ix, side.y() < 0 ? -iy : iy};
}

}  // namespace

namespace {

PlacementCandidates byKind(const PlacementContext& ctx, const PlacementTarget& target, std::size_t limit) {
  switch (target.kind) {
    case PlacementKind::In:
    case PlacementKind::Corner: return placeIn(ctx, target, limit);
    case PlacementKind::OnTop: return placeOnTop(ctx, target, limit);
    case PlacementKind::NextTo: return placeNextTo(ctx, target, limit);
    case PlacementKind::Direction: return placeInDirection(ctx, target, limit);
    case PlacementKind::Between: return placeBetween(ctx, target, limit);
  }
  return {};
}

}  // namespace

PlacementCandidates placementCandidates(const PlacementContext& ctx, const PlacementTarget& target, std::size_t limit,
                                        bool tight) {
  PlacementCandidates out = byKind(ctx, target, limit);
  if (!tight || out.poses.size() >= limit || target.kind == PlacementKind::OnTop) return out;
  // Then the tight places (PlacementContext::Options::tight()) the full clearances did not allow.
  const PlacementContext::Options rules = ctx.options().tight();
  const PlacementContext tightContext(ctx.scene(), ctx.part(), rules);
  const std::size_t full = out.poses.size();
  PlacementCandidates more = byKind(tightContext, target, limit == kAllCandidates ? limit : limit + full);
  auto known = [&](const PlacementCandidate& c) {
    return std::any_of(out.poses.begin(), out.poses.begin() + static_cast<std::ptrdiff_t>(full), [&](const auto& q) {
      return (q.X_world_object.translation() - c.X_world_object.translation()).norm() < 1e-6 &&
             std::abs(std::remainder(yawOfPose(q.X_world_object) - yawOfPose(c.X_world_object), M_PI)) < 1e-6;
    });
  };
  for (auto& c : more.poses) {
    if (out.poses.size() >= limit) break;
    if (full > 0 && known(c)) continue;
    c.tight = true;
    out.poses.push_back(std::move(c));
  }
  if (out.poses.empty()) out.reason = more.reason;
  return out;
}

PlacementCandidates placeIn(const PlacementContext& ctx, const PlacementTarget& t, std::size_t limit) {
  PlacementCandidates out;
  Collector collect{out, limit};
  const CellObject& part = ctx.part();
  const CellObject& container = *ctx.scene().find(t.container);
  const PlacementContext::Options& o = ctx.options();
  const double innerX = container.size_m.x() / 2 - container.wallThickness_m;
  const double innerY = container.size_m.y() / 2 - container.wallThickness_m;
  const double wx = innerX - o.wallMargin_m, wy = innerY - o.wallMargin_m;
  if (std::min(wx, wy) < std::min(part.size_m.x(), part.size_m.y()) / 2 ||
      std::max(wx, wy) < std::max(part.size_m.x(), part.size_m.y()) / 2) {
    out.reason = "the " + part.name + " does not fit in the " + container.name;
    return out;
  }
  const Eigen::Vector2d cc = centre(container);
  const double tool = ctx.toolClearanceFrom(container, container.X_world_object * uprightPose(
                                                           Eigen::Vector3d(0, 0, container.wallThickness_m), 0.0));
  for (const double turn : ctx.turns()) {
    // The centre's free half-extents (footprint inside the margins, centre clear for the tool).
    const double c = std::abs(std::cos(turn)), s = std::abs(std::sin(turn));
    const double ix = std::min(wx - (c * part.size_m.x() + s * part.size_m.y()) / 2, innerX - tool);
    const double iy = std::min(wy - (s * part.size_m.x() + c * part.size_m.y()) / 2, innerY - tool);
    if (ix < 0 || iy < 0) continue;
    const Eigen::Vector2d corner = preferredCorner(ctx, t, container, ix, iy);
    const Eigen::Vector2d preferred = t.cornerDirections.empty() ? t.demoPositionInContainer_m.value_or(corner) : corner;
    std::vector<Eigen::Vector2d> grid;
    for (double x = -ix; x <= ix + 1e-9; x += o.gridStep_m)
      for (double y = -iy; y <= iy + 1e-9; y += o.gridStep_m) grid.emplace_back(x, y);
    sortByDistance(grid, preferred);
    for (const auto& g : grid) {
      const Pose3 X = container.X_world_object * uprightPose(Eigen::Vector3d(g.x(), g.y(), container.wallThickness_m), turn);
      bool inQuadrant = true;  // a named corner: stay in its quadrant
      for (const auto& d : t.cornerDirections) inQuadrant = inQuadrant && (X.translation().head<2>() - cc).dot(d) > 0.0;
      if (inQuadrant && ctx.isFree(X)) collect.add(X, container.name);
      if (collect.full()) return out;
    }
  }
  if (out.poses.empty())
    out.reason = t.cornerDirections.empty() ? "the " + container.name + " has no free place left for the " + part.name
                                            : "the " + t.corner + " corner of the " + container.name +
                                                  " has no free place left for the " + part.name;
  return out;
}

PlacementCandidates placeOnTop(const PlacementContext& ctx, const PlacementTarget& t, std::size_t) {
  PlacementCandidates out;
  const CellObject& part = ctx.part();
  const CellObject& lower = *ctx.scene().find(t.landmark);
  const CellObject* container = containerOf(ctx, t);
  if (container && !isInside(lower, *container)) {
    out.reason = "the " + lower.name + " is not in the " + container->name + ", so the " + part.name +
                 " cannot go on it there";
    return out;
  }
  const double top = lower.X_world_object.translation().z() + lower.size_m.z();
  for (const auto& o : ctx.scene().objects) {
    if (o.kind != CellObjectKind::Part || o.name == part.name || o.name == lower.name) continue;
    if (std::abs(o.X_world_object.translation().z() - top) < 0.01 &&
        overlaps(footprint(o.size_m, o.X_world_object, 0.0), o.X_world_object,
                 footprint(lower.size_m, lower.X_world_object, 0.0), lower.X_world_object)) {
      out.reason = "the " + o.name + " already lies on the " + lower.name + "; the " + part.name +
                   " cannot be stacked there";
      return out;
    }
  }
  const Eigen::Vector2d c = centre(lower);
  const Pose3 X = uprightPose(Eigen::Vector3d(c.x(), c.y(), top), yawOfPose(lower.X_world_object));
  if (!ctx.inReach(X)) {
    out.reason = "the " + lower.name + " is out of the arm's reach for stacking the " + part.name;
    return out;
  }
  for (const auto& wall : ctx.scene().objects)
    if (wall.kind == CellObjectKind::Container && distanceToWalls(wall, c) < ctx.toolClearanceFrom(wall, X) - 1e-9) {
      out.reason = "the suction tool would not clear the " + wall.name + "'s wall (" + fmt(distanceToWalls(wall, c)) +
                   " from the " + lower.name + "'s centre, " + fmt(ctx.options().toolClearance_m) + " needed)";
      return out;
    }
  out.poses.push_back({X, container ? container->name : "", lower.name, false});
  return out;
}

PlacementCandidates placeNextTo(const PlacementContext& ctx, const PlacementTarget& t, std::size_t limit) {
  PlacementCandidates out;
  Collector collect{out, limit};
  const CellObject& part = ctx.part();
  const CellObject& neighbour = *ctx.scene().find(t.landmark);
  const CellObject* container = containerOf(ctx, t);
  const PlacementContext::Options& o = ctx.options();
  const Eigen::Vector2d c = centre(neighbour);
  const double yaw0 = yawOfPose(container ? container->X_world_object : neighbour.X_world_object);
  const double z = container ? container->X_world_object.translation().z() + container->wallThickness_m : 0.0;
  // The four sides: the demonstration's first, else (in a container) the one facing its centre.
  std::vector<Eigen::Vector2d> sides;
  for (int k = 0; k < 4; ++k) sides.emplace_back(std::cos(yaw0 + k * M_PI / 2), std::sin(yaw0 + k * M_PI / 2));
  const Eigen::Vector2d towards = t.demoOffsetFromNeighbour_m && t.demoOffsetFromNeighbour_m->norm() > 1e-6
                                      ? t.demoOffsetFromNeighbour_m->normalized()
                                  : container ? Eigen::Vector2d(centre(*container) - c)
                                              : Eigen::Vector2d::Zero();
  std::stable_sort(sides.begin(), sides.end(), [&](const auto& a, const auto& b) { return a.dot(towards) > b.dot(towards); });
  // The place beside side d at `gap`, slid by `slide` along it and back inside the walls.
  auto tryPlace = [&](double yaw, const Eigen::Vector2d& d, double gap, double slide) {
    const Eigen::Vector2d perp(-d.y(), d.x());
    Eigen::Vector2d p = c + (support(neighbour, d) + support(part.size_m, yaw, d) + gap) * d + slide * perp;
    if (container) {
      const Eigen::Vector2d cc = centre(*container);
      for (int k = 0; k < 2; ++k) {
        const Eigen::Vector2d axis = container->X_world_object.linear().col(k).head<2>();
        if (std::abs(axis.dot(perp)) < 0.5) continue;  // only the coordinate along the side
        const double limit = container->size_m[k] / 2 - container->wallThickness_m - o.wallMargin_m -
                             support(part.size_m, yaw, axis);
        const double coord = (p - cc).dot(axis);
        p += (std::clamp(coord, -limit, limit) - coord) * axis;
      }
      // The two footprints must still face each other.
      if (std::abs((p - c).dot(perp)) > support(neighbour, perp) + support(part.size_m, yaw, perp) - 0.01) return;
    }
    const Pose3 X = uprightPose(Eigen::Vector3d(p.x(), p.y(), z), yaw);
    const bool fits = container ? ctx.fitsInside(*container, X) : ctx.fitsTable(X);
    const bool seen = std::any_of(out.poses.begin(), out.poses.end(), [&](const PlacementCandidate& q) {
      return (q.X_world_object.translation() - X.translation()).norm() < 1e-6 &&
             std::abs(yawOfPose(q.X_world_object) - yaw) < 1e-9;
    });
    if (fits && !seen && ctx.isFree(X)) collect.add(X, container ? container->name : "");
  };
  const double slideMax = 0.06;
  for (const double turn : ctx.turns()) {
    const double yaw = yaw0 + turn;
    for (const auto& d : sides) tryPlace(yaw, d, o.neighbourGap_m, 0.0);
    for (const auto& d : sides)
      for (double s = o.gridStep_m; s <= slideMax + 1e-9 && !collect.full(); s += o.gridStep_m)
        for (const double slide : {s, -s}) tryPlace(yaw, d, o.neighbourGap_m, slide);
    for (const double gap : {o.clearance_m, o.neighbourGap_m + o.neighbourTolerance_m / 2})
      for (const auto& d : sides)
        for (double s = 0.0; s <= slideMax + 1e-9 && !collect.full(); s += o.gridStep_m)
          for (const double slide : {s, -s}) tryPlace(yaw, d, gap, slide);
    if (collect.full()) break;
  }
  if (out.poses.size() > limit) out.poses.resize(limit);
  if (out.poses.empty())
    out.reason = "no free place next to the " + neighbour.name +
                 (container ? " inside the " + container->name : std::string()) + " for the " + part.name;
  return out;
}

PlacementCandidates placeInDirection(const PlacementContext& ctx, const PlacementTarget& t, std::size_t limit) {
  PlacementCandidates out;
  Collector collect{out, limit};
  const CellObject& part = ctx.part();
  const CellObject& landmark = *ctx.scene().find(t.landmark);
  const CellObject* container = containerOf(ctx, t);
  const PlacementContext::Options& o = ctx.options();
  const Eigen::Vector2d c = centre(landmark), d = t.direction, perp(-d.y(), d.x());
  // Further out on the table: past a container in the way, as far as the 45-degree cone allows.
  constexpr double kInsideExtra_m = 0.12, kTableExtra_m = 0.30, kLateral_m = 0.08;
  // Gaps from neighbourGap_m out to extraMax_m more, or (closer) from clearance_m up to neighbourGap_m.
  auto attempt = [&](const CellObject* in, double yaw, double extraMax_m, bool closer = false) {
    const double d0 = support(landmark, d) + support(part.size_m, yaw, d) + o.neighbourGap_m;
    const double from = closer ? o.clearance_m - o.neighbourGap_m : 0.0, to = closer ? -1e-6 : extraMax_m;
    std::vector<Eigen::Vector2d> grid;
    for (double extra = from; extra <= to + 1e-9; extra += closer ? o.gridStep_m / 5 : o.gridStep_m)
      for (double lateral = -kLateral_m; lateral <= kLateral_m + 1e-9; lateral += o.gridStep_m) {
        const Eigen::Vector2d p = c + (d0 + extra) * d + lateral * perp;
        // Within 45 degrees of the named direction, so "left of" still reads as left.
        if ((p - c).dot(d) > std::abs((p - c).dot(perp)) + 1e-6) grid.push_back(p);
      }
    sortByDistance(grid, c + d0 * d);
    for (const auto& p : grid) {
      if (collect.full()) return;
      if (const auto X = ctx.rest(p, yaw, in, true)) collect.add(*X, in ? in->name : "");
    }
  };
  const double yawIn = yawOfPose(container ? container->X_world_object : landmark.X_world_object);
  for (const double turn : ctx.turns()) attempt(container, yawIn + turn, container ? kInsideExtra_m : kTableExtra_m);
  for (const double turn : ctx.turns()) attempt(container, yawIn + turn, 0.0, true);
  // A landmark's container with no room: beside the landmark on the table (unless the container was named).
  if (container && !t.containerNamed && out.poses.empty())
    for (const double turn : ctx.turns()) attempt(nullptr, yawOfPose(landmark.X_world_object) + turn, kTableExtra_m);
  if (out.poses.empty())
    out.reason = "no free place " + t.directionText + " the " + landmark.name +
                 where(container && t.containerNamed ? container : nullptr) + " for the " +
                 part.name + " (blocked by other parts, the walls, the table edge or the arm's reach)";
  return out;
}

/// The after-placement check allows the footprints 1 mm into each other along the line;
/// candidates stay this much inside each limit of the check.
constexpr double kBetweenSlack_m = 1e-3;
constexpr double kInsideCheck_m = 1e-5;

/// 0, +-step, +-2 step, ... and +-limit itself (a band narrower than the step is still tried).
std::vector<double> symmetricSamples(double limit, double step) {
  std::vector<double> out{0.0};
  for (double v = step; v < limit - 1e-9; v += step) out.insert(out.end(), {v, -v});
  if (limit > 1e-9) out.insert(out.end(), {limit, -limit});
  return out;
}

PlacementCandidates placeBetween(const PlacementContext& ctx, const PlacementTarget& t, std::size_t limit) {
  PlacementCandidates out;
  Collector collect{out, limit};
  const CellObject& part = ctx.part();
  const CellObject& A = *ctx.scene().find(t.landmark);
  const CellObject& B = *ctx.scene().find(t.secondLandmark);
  const PlacementContext::Options& o = ctx.options();
  const Eigen::Vector2d a = centre(A), b = centre(B);
  const double length = (b - a).norm();
  const Eigen::Vector2d u = (b - a) / std::max(length, 1e-9), perp(-u.y(), u.x());
  const double sA = support(A, u), sB = support(B, u), room = length - sA - sB;
  // The whole band the after-placement check allows beside the line: turned landmarks are
  // narrower off the line than their projections onto it, so a part offset sideways can
  // keep its clearances where one on the line cannot.
  const double lateralLimit = std::max(support(A, perp), support(B, perp)) + o.relationTolerance_m - kInsideCheck_m;
  // The part's narrower side along A-B first: it needs the least room there.
  const double narrow = std::atan2(u.y(), u.x()) + (part.size_m.x() <= part.size_m.y() ? 0.0 : M_PI / 2);
  auto attempt = [&](const CellObject* in, double yaw) {
    // Along the line, as far as the footprints may still be told apart along it (the
    // check's 1 mm); the clearances to A, B and the rest are kept by rest() with the
    // footprints as they lie (turned), not their projections onto the line.
    const double slack = (room - 2 * support(part.size_m, yaw, u)) / 2 + kBetweenSlack_m - kInsideCheck_m;
    if (slack < 0.0) return;
    const Eigen::Vector2d p0 = a + (sA + room / 2) * u;
    std::vector<Eigen::Vector2d> grid;
    for (const double along : symmetricSamples(slack, o.gridStep_m / 2))
      for (const double lateral : symmetricSamples(lateralLimit, o.gridStep_m / 2))
        grid.push_back(p0 + along * u + lateral * perp);
    sortByDistance(grid, p0);
    for (const auto& p : grid) {
      if (collect.full()) return;
      if (const auto X = ctx.rest(p, yaw, in, true)) collect.add(*X, in ? in->name : "");
    }
  };
  const CellObject* container = containerOf(ctx, t);
  for (const double turn : ctx.turns()) attempt(container, narrow + turn);
  if (container && !t.containerNamed && out.poses.empty())
    for (const double turn : ctx.turns()) attempt(nullptr, narrow + turn);
  const double sP = support(part.size_m, narrow, u), needed = 2 * sP + 2 * o.clearance_m;
  if (out.poses.empty() && room < needed)
    out.reason = "not enough room between the " + A.name + " and the " + B.name + " for the " + part.name + " (" +
                 fmt(room) + " free along the line between them, " + fmt(needed) + " needed: its narrower side " +
                 fmt(2 * sP) + " and " + fmt(o.clearance_m) + " on each side)";
  else if (out.poses.empty())
    out.reason = "no free place between the " + A.name + " and the " + B.name +
                 where(container && t.containerNamed ? container : nullptr) + " for the " + part.name +
                 " (blocked by other parts, the walls, the table edge or the arm's reach)";
  return out;
}

}  // namespace srp::execution
