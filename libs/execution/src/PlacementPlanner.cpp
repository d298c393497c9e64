#include "srp/execution/PlacementPlanner.h"

#include "srp/core/Text.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <functional>
#include <sstream>

namespace srp::execution {
namespace {

using srp::core::Pose3;

using srp::core::normaliseName;

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

double support(const CellObject& o, const Eigen::Vector2d& d) { return support(o.size_m, yawOfPose(o.X_world_object), d); }

Eigen::Vector2d centre(const CellObject& o) { return o.X_world_object.translation().head<2>(); }

/// Vertical extents [bottom, top] overlap (1 mm slack: parts resting on each other touch).
bool verticalOverlap(const CellObject& a, double za, const CellObject& b) {
  const double zb = b.X_world_object.translation().z();
  return za < zb + b.size_m.z() - 1e-3 && zb < za + a.size_m.z() - 1e-3;
}

enum class Kind { Containment, Corner, Stack, Neighbour, Direction, Between, Unknown };

bool isStackWord(const std::string& r) {
  return r == "on" || r == "onto" || r == "on to" || r == "on top of" || r == "upon" || r == "atop" ||
         r == "on the top of" || r == "stacked on";
}

Kind kindOf(const SpatialRelation& rel) {
  const std::string r = normaliseName(rel.relation);
  if (!rel.corner.empty() || r.find("corner") != std::string::npos) return Kind::Corner;
  if (r == "between" || r == "in between") return Kind::Between;
  if (!srp::core::ViewFrame::directionWord(r).empty()) return Kind::Direction;
  if (isNeighbourRelation(r)) return Kind::Neighbour;
  if (isStackWord(r)) return Kind::Stack;  // resolved to Containment when the landmark is a container
  if (isContainmentRelation(r)) return Kind::Containment;
  return Kind::Unknown;
}

/// The container holding `o` (its centre inside the inner footprint, resting on its floor level), or nullptr.
const CellObject* containerOf(const CellDescription& scene, const CellObject& o) {
  for (const auto& c : scene.objects)
    if (c.kind == CellObjectKind::Container && PlacementPlanner::isInside(o, c)) return &c;
  return nullptr;
}

std::string fmt(double v_m) {
  std::ostringstream s;
  s.precision(1);
  s << std::fixed << v_m * 1000.0 << " mm";
  return s.str();
}

}  // namespace

bool PlacementPlanner::isInside(const CellObject& part, const CellObject& container) {
  const Eigen::Vector3d p = container.X_world_object.inverse() * part.X_world_object.translation();
  return std::abs(p.x()) <= container.size_m.x() / 2 - container.wallThickness_m &&
         std::abs(p.y()) <= container.size_m.y() / 2 - container.wallThickness_m;
}

srp::core::ViewFrame PlacementPlanner::viewFrame(const CellDescription& scene) const {
  return scene.viewFrame(options_.grounding.viewpoint);
}

bool PlacementPlanner::isFree(const CellDescription& scene, const CellObject& part, const Pose3& X,
                              const std::vector<std::string>& near, double nearClearance_m) const {
  for (const auto& o : scene.objects) {
    if (o.kind != CellObjectKind::Part || o.name == part.name) continue;
    if (!verticalOverlap(part, X.translation().z(), o)) continue;  // stacked above or below
    const bool isNear = std::find(near.begin(), near.end(), o.name) != near.end();
    const double half = (isNear ? nearClearance_m : options_.clearance_m) / 2;
    if (overlaps(footprint(part.size_m, X, half), X, footprint(o.size_m, o.X_world_object, half), o.X_world_object))
      return false;
  }
  return true;
}

Placement PlacementPlanner::place(const CellDescription& scene, const CellObject& part,
                                  const ExecutionStep& step) const {
  Placement out;
  const CellObject* container = nullptr;
  const CellObject* neighbour = nullptr;
  const CellObject* stackOn = nullptr;
  const CellObject* directionLandmark = nullptr;
  const CellObject* betweenA = nullptr;
  const CellObject* betweenB = nullptr;
  std::vector<Eigen::Vector2d> cornerDirections;
  Eigen::Vector2d direction = Eigen::Vector2d::Zero();
  std::string directionText;
  const srp::core::ViewFrame view = viewFrame(scene);
  const SceneGrounder grounder(scene, options_.grounding);
  // One instance for a landmark phrase (SceneGrounder), or the reason naming the candidates.
  auto groundLandmark = [&](const SpatialRelation& rel, const ObjectReference& ref,
                            std::optional<CellObjectKind> kind) -> const CellObject* {
    const CellObject* o = nullptr;
    try {
      o = &grounder.ground(ref, {}, kind);
    } catch (const GroundingError& e) {
      out.reason = "target '" + rel.relation + " the " + ref.describe() + "': " + e.what();
      return nullptr;
    }
    if (o->name == part.name) {
      out.reason = "the " + part.name + " cannot be placed " + rel.relation + " itself";
      return nullptr;
    }
    return o;
  };
  for (const auto& rel : step.target) {
    Kind kind = kindOf(rel);
    std::pair<std::string, std::string> ids;
    if (kind == Kind::Stack) {
      const CellObject* l = groundLandmark(rel, rel.landmark, std::nullopt);
      if (!l) return out;
      kind = l->kind == CellObjectKind::Container ? Kind::Containment : Kind::Stack;
    }
    switch (kind) {
      case Kind::Containment:
        container = groundLandmark(rel, rel.landmark, CellObjectKind::Container);
        if (!container) return out;
        ids.first = container->name;
        break;
      case Kind::Corner: {
        container = groundLandmark(rel, rel.landmark, CellObjectKind::Container);
        if (!container) return out;
        ids.first = container->name;
        std::istringstream words(rel.corner);
        for (std::string w; words >> w;)
          if (auto d = view.direction(w == "rear" ? "behind" : w)) cornerDirections.push_back(*d);
        if (cornerDirections.size() != 2 || std::abs(cornerDirections[0].dot(cornerDirections[1])) > 0.5) {
          out.reason = "unknown corner '" + rel.corner + "' of the " + container->name +
                       " (say front left, front right, back left or back right)";
          return out;
        }
        break;
      }
      case Kind::Neighbour:
        neighbour = groundLandmark(rel, rel.landmark, CellObjectKind::Part);
        if (!neighbour) return out;
        ids.first = neighbour->name;
        break;
      case Kind::Stack:
        stackOn = groundLandmark(rel, rel.landmark, CellObjectKind::Part);
        if (!stackOn) return out;
        ids.first = stackOn->name;
        break;
      case Kind::Direction:
        directionLandmark = groundLandmark(rel, rel.landmark, std::nullopt);
        if (!directionLandmark) return out;
        ids.first = directionLandmark->name;
        direction = *view.direction(normaliseName(rel.relation));
        directionText = rel.relation;
        break;
      case Kind::Between:
        if (rel.secondLandmark) {
          betweenA = groundLandmark(rel, rel.landmark, std::nullopt);
          if (!betweenA) return out;
          betweenB = groundLandmark(rel, *rel.secondLandmark, std::nullopt);
          if (!betweenB) return out;
        } else {
          // "between the stars": a plural landmark naming exactly two instances (the part excluded).
          std::vector<const CellObject*> both;
          for (const CellObject* o : grounder.candidates(rel.landmark))
            if (o->name != part.name) both.push_back(o);
          if (both.size() != 2) {
            out.reason = "'between' needs two landmarks; 'the " + rel.landmark.describe() + "' names " +
                         std::to_string(both.size()) + " instance(s) in the scene";
            return out;
          }
          betweenA = both[0];
          betweenB = both[1];
        }
        if (betweenA->name == betweenB->name) {
          out.reason = "'between' needs two different landmarks; both name the " + betweenA->name;
          return out;
        }
        ids = {betweenA->name, betweenB->name};
        break;
      case Kind::Unknown:
        out.reason = "unknown target relation '" + rel.relation +
                     "' (known: in/into/on/onto, on top of, next to/beside/adjacent to, left of, right of, in front "
                     "of, behind, between, in the <front|back> <left|right> corner of)";
        return out;
    }
    out.landmarkIds.push_back(ids);
  }
  // Several "next to" relations keep the last one (as before); other mixes are ambiguous.
  const int others = (stackOn != nullptr) + (directionLandmark != nullptr) + (betweenA != nullptr);
  if (others > 1 || (others == 1 && neighbour)) {
    out.reason = "the target relations of the " + part.name + " name several landmarks to place it by; give one";
    return out;
  }
  if (stackOn || directionLandmark || betweenA) neighbour = nullptr;

  const CellObject* landmark = stackOn ? stackOn : directionLandmark ? directionLandmark : betweenA ? betweenA : neighbour;
  const bool containerNamed = container != nullptr;
  if (!container && landmark && landmark->kind == CellObjectKind::Part && !stackOn) {
    // "beside the star" with the star in a container: the part goes in there too.
    if (betweenA) {
      const CellObject* ca = containerOf(scene, *betweenA);
      const CellObject* cb = betweenB->kind == CellObjectKind::Part ? containerOf(scene, *betweenB) : nullptr;
      if (ca && cb && ca->name == cb->name) container = ca;
    } else {
      for (const auto& o : scene.objects)
        if (o.kind == CellObjectKind::Container && isInside(*landmark, o)) container = &o;
    }
  }
  if (!container && !landmark) {
    out.reason = "the instruction gives no target location for the " + part.name;
    return out;
  }
  if (container) out.container = container->name;
  if (neighbour) out.neighbour = neighbour->name;

  double yaw = container ? yawOfPose(container->X_world_object) : yawOfPose(landmark->X_world_object);
  double zSupport = container ? container->X_world_object.translation().z() + container->wallThickness_m : 0.0;
  // A landmark's container that has no room left: beside it on the table (the relation
  // to the landmark still holds there), unless the instruction named the container.
  auto moveToTable = [&]() {
    if (containerNamed || !container) return false;
    container = nullptr;
    out.container.clear();
    yaw = yawOfPose(landmark->X_world_object);
    zSupport = 0.0;
    return true;
  };
  // Is the whole footprint (plus margin) inside the container's inner walls?
  auto fitsIn = [&](const CellObject* box, const Pose3& X) {
    if (!box) return true;
    const CellObject* container = box;  // the inner footprint of `box`
    const Pose3 X_c = container->X_world_object.inverse() * X;
    const double c = std::abs(std::cos(yawOfPose(X_c))), s = std::abs(std::sin(yawOfPose(X_c)));
    const double ex = c * part.size_m.x() / 2 + s * part.size_m.y() / 2;
    const double ey = s * part.size_m.x() / 2 + c * part.size_m.y() / 2;
    const double ix = container->size_m.x() / 2 - container->wallThickness_m - options_.wallMargin_m;
    const double iy = container->size_m.y() / 2 - container->wallThickness_m - options_.wallMargin_m;
    return std::abs(X_c.translation().x()) + ex <= ix + 1e-9 && std::abs(X_c.translation().y()) + ey <= iy + 1e-9;
  };
  auto fitsContainer = [&](const Pose3& X) { return fitsIn(container, X); };
  auto inReach = [&](const Pose3& X) {
    const double r = (X.translation().head<2>() - scene.X_world_base.translation().head<2>()).norm();
    return r >= options_.minReach_m && r <= options_.maxReach_m;
  };
  // On the table: inside its top, clear of every container's outer walls (plus margin).
  auto fitsTable = [&](const Pose3& X) {
    if (container) return true;
    const Eigen::Vector2d p = X.translation().head<2>() - scene.tableCentre_m;
    const double yawX = yawOfPose(X);
    if (std::abs(p.x()) + support(part.size_m, yawX, Eigen::Vector2d::UnitX()) > scene.tableHalfExtents_m.x() ||
        std::abs(p.y()) + support(part.size_m, yawX, Eigen::Vector2d::UnitY()) > scene.tableHalfExtents_m.y())
      return false;
    const auto mine = footprint(part.size_m, X, options_.wallMargin_m);
    for (const auto& o : scene.objects)
      if (o.kind == CellObjectKind::Container &&
          overlaps(mine, X, footprint(o.size_m, o.X_world_object, 0.0), o.X_world_object))
        return false;
    return true;
  };
  auto where = [&]() { return container ? " inside the " + container->name : std::string(" on the table"); };

  if (stackOn) {
    if (container && !isInside(*stackOn, *container)) {
      out.reason = "the " + stackOn->name + " is not in the " + container->name + ", so the " + part.name +
                   " cannot go on it there";
      return out;
    }
    const double top = stackOn->X_world_object.translation().z() + stackOn->size_m.z();
    for (const auto& o : scene.objects) {
      if (o.kind != CellObjectKind::Part || o.name == part.name || o.name == stackOn->name) continue;
      if (std::abs(o.X_world_object.translation().z() - top) < 0.01 &&
          overlaps(footprint(o.size_m, o.X_world_object, 0.0), o.X_world_object,
                   footprint(stackOn->size_m, stackOn->X_world_object, 0.0), stackOn->X_world_object)) {
        out.reason = "the " + o.name + " already lies on the " + stackOn->name + "; the " + part.name +
                     " cannot be stacked there";
        return out;
      }
    }
    const Eigen::Vector2d c = centre(*stackOn);
    const Pose3 X = uprightPose(Eigen::Vector3d(c.x(), c.y(), top), yawOfPose(stackOn->X_world_object));
    if (!inReach(X)) {
      out.reason = "the " + stackOn->name + " is out of the arm's reach for stacking the " + part.name;
      return out;
    }
    out.stackedOn = stackOn->name;
    out.X_world_object = X;
    return out;
  }

  // "between": its two landmarks may be nearer than clearance_m (set below).
  std::vector<std::string> near;
  double nearClearance_m = options_.clearance_m;
  // Candidates around an ideal point p0, nearest first; the first that fits everything wins.
  auto search = [&](std::vector<Eigen::Vector2d> candidates, const Eigen::Vector2d& p0,
                    const std::function<bool(const Eigen::Vector2d&)>& keeps) -> std::optional<Pose3> {
    std::stable_sort(candidates.begin(), candidates.end(),
                     [&](const auto& a, const auto& b) { return (a - p0).squaredNorm() < (b - p0).squaredNorm(); });
    for (const auto& p : candidates) {
      if (!keeps(p)) continue;
      Pose3 X = uprightPose(Eigen::Vector3d(p.x(), p.y(), zSupport), yaw);
      if (!container) {
        // A table place that falls wholly inside a container rests on its floor instead.
        for (const auto& o : scene.objects)
          if (o.kind == CellObjectKind::Container && fitsIn(&o, X)) {
            X.translation().z() = o.X_world_object.translation().z() + o.wallThickness_m;
            if (inReach(X) && isFree(scene, part, X, near, nearClearance_m)) return X;
          }
      }
      if (fitsContainer(X) && fitsTable(X) && inReach(X) && isFree(scene, part, X, near, nearClearance_m)) return X;
    }
    return std::nullopt;
  };

  if (directionLandmark) {
    auto attempt = [&](double extraMax_m) {
      const Eigen::Vector2d c = centre(*directionLandmark), perp(-direction.y(), direction.x());
      const double d0 = support(*directionLandmark, direction) + support(part.size_m, yaw, direction) + options_.neighbourGap_m;
      std::vector<Eigen::Vector2d> candidates;
      for (double extra = 0.0; extra <= extraMax_m + 1e-9; extra += options_.gridStep_m)
        for (double lateral = -0.08; lateral <= 0.08 + 1e-9; lateral += options_.gridStep_m)
          candidates.push_back(c + (d0 + extra) * direction + lateral * perp);
      // Within 45 degrees of the named direction, so "left of" still reads as left.
      return search(candidates, c + d0 * direction, [&](const Eigen::Vector2d& p) {
        return (p - c).dot(direction) > std::abs((p - c).dot(perp)) + 1e-6;
      });
    };
    // Further out on the table: past a container in the way, as far as the cone allows.
    constexpr double kInsideExtra_m = 0.12, kTableExtra_m = 0.30;
    auto X = attempt(container ? kInsideExtra_m : kTableExtra_m);
    if (!X && moveToTable()) X = attempt(kTableExtra_m);
    if (!X) {
      out.reason = "no free place " + directionText + " the " + directionLandmark->name + where() + " for the " +
                   part.name + " (blocked by other parts, the walls, the table edge or the arm's reach)";
      return out;
    }
    out.X_world_object = X;
    return out;
  }

  if (betweenA) {
    const Eigen::Vector2d a = centre(*betweenA), b = centre(*betweenB);
    const double length = (b - a).norm();
    const Eigen::Vector2d u = (b - a) / std::max(length, 1e-9), perp(-u.y(), u.x());
    const double sA = support(*betweenA, u), sB = support(*betweenB, u);
    auto attempt = [&]() -> std::optional<Pose3> {
      // The part's narrower side along A-B: it needs the least room there.
      yaw = std::atan2(u.y(), u.x()) + (part.size_m.x() <= part.size_m.y() ? 0.0 : M_PI / 2);
      const double sP = support(part.size_m, yaw, u);
      const double room = length - sA - sB, needed = 2 * sP + 2 * options_.betweenMinClearance_m;
      if (room < needed) {
        out.reason = "not enough room between the " + betweenA->name + " and the " + betweenB->name + " for the " +
                     part.name + " (" + fmt(room) + " free along the line between them, " + fmt(needed) +
                     " needed: its narrower side " + fmt(2 * sP) + " and " + fmt(options_.betweenMinClearance_m) +
                     " on each side)";
        return std::nullopt;
      }
      // A tight gap: the part in the middle, nearer A and B than clearance_m.
      nearClearance_m = std::min(options_.clearance_m, (room - 2 * sP) / 2 - 1e-4);  // 0.1 mm: exactly centred touches
      near = {betweenA->name, betweenB->name};
      const Eigen::Vector2d p0 = a + (sA + room / 2) * u;
      const double slack = std::max(0.0, (room - 2 * sP - 2 * nearClearance_m) / 2);
      const double lateralLimit = std::max(support(*betweenA, perp), support(*betweenB, perp));
      std::vector<Eigen::Vector2d> candidates;
      for (double along = -slack; along <= slack + 1e-9; along += options_.gridStep_m / 2)
        for (double lateral = -lateralLimit; lateral <= lateralLimit + 1e-9; lateral += options_.gridStep_m / 2)
          candidates.push_back(p0 + along * u + lateral * perp);
      candidates.push_back(p0);
      const auto X = search(candidates, p0, [](const Eigen::Vector2d&) { return true; });
      if (!X)
        out.reason = "no free place between the " + betweenA->name + " and the " + betweenB->name + where() +
                     " for the " + part.name + " (blocked by other parts, the walls, the table edge or the arm's reach)";
      return X;
    };
    auto X = attempt();
    if (!X && moveToTable()) X = attempt();
    if (X) out.reason.clear();
    out.X_world_object = X;
    return out;
  }

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
      if (fitsContainer(X) && fitsTable(X) && isFree(scene, part, X)) {
        out.X_world_object = X;
        return out;
      }
    }
    out.reason = "no free place next to the " + neighbour->name +
                 (container ? " inside the " + container->name : std::string()) + " for the " + part.name;
    return out;
  }

  // "in X": grid over the inner footprint, nearest to the preferred point first; the
  // part along the container's axes, then (an oblong part, when that found no place)
  // turned by 90 degrees, which may fit where the first did not (a cuboid across a
  // corner another part narrows).
  const double wx = container->size_m.x() / 2 - container->wallThickness_m - options_.wallMargin_m;
  const double wy = container->size_m.y() / 2 - container->wallThickness_m - options_.wallMargin_m;
  if (std::min(wx, wy) < std::min(part.size_m.x(), part.size_m.y()) / 2 ||
      std::max(wx, wy) < std::max(part.size_m.x(), part.size_m.y()) / 2) {
    out.reason = "the " + part.name + " does not fit in the " + container->name;
    return out;
  }
  const Eigen::Vector2d cc = container->X_world_object.translation().head<2>();
  const bool oblong = std::abs(part.size_m.x() - part.size_m.y()) > 1e-3;
  for (const double turn : {0.0, M_PI / 2}) {
    if (turn != 0.0 && !oblong) break;
    const double hx = turn == 0.0 ? part.size_m.x() / 2 : part.size_m.y() / 2;
    const double hy = turn == 0.0 ? part.size_m.y() / 2 : part.size_m.x() / 2;
    const double ix = wx - hx, iy = wy - hy;
    if (ix < 0 || iy < 0) continue;
    // Without a demonstration: the inner corner nearest to where the part comes from,
    // which leaves the rest of the container free for its neighbours. A named corner:
    // the inner corner furthest along the corner's two view directions.
    const Eigen::Vector3d from_c = container->X_world_object.inverse() * part.X_world_object.translation();
    Eigen::Vector2d corner(from_c.x() < 0 ? -ix : ix, from_c.y() < 0 ? -iy : iy);
    if (!cornerDirections.empty()) {
      const Eigen::Vector2d w = cornerDirections[0] + cornerDirections[1];
      const Eigen::Matrix2d R_wc = container->X_world_object.linear().topLeftCorner<2, 2>();
      const Eigen::Vector2d w_c = R_wc.transpose() * w;
      corner = Eigen::Vector2d(w_c.x() < 0 ? -ix : ix, w_c.y() < 0 ? -iy : iy);
    }
    const Eigen::Vector2d preferred =
        cornerDirections.empty() ? step.demoPositionInContainer_m.value_or(corner) : corner;
    std::vector<Eigen::Vector2d> candidates;
    for (double x = -ix; x <= ix + 1e-9; x += options_.gridStep_m)
      for (double y = -iy; y <= iy + 1e-9; y += options_.gridStep_m) candidates.emplace_back(x, y);
    std::sort(candidates.begin(), candidates.end(), [&](const auto& a, const auto& b) {
      return (a - preferred).squaredNorm() < (b - preferred).squaredNorm();
    });
    for (const auto& c : candidates) {
      Pose3 X = container->X_world_object * uprightPose(Eigen::Vector3d(c.x(), c.y(), container->wallThickness_m), turn);
      // A named corner: stay in its quadrant.
      bool inQuadrant = true;
      for (const auto& d : cornerDirections) inQuadrant = inQuadrant && (X.translation().head<2>() - cc).dot(d) > 0.0;
      if (inQuadrant && isFree(scene, part, X)) {
        out.X_world_object = X;
        return out;
      }
    }
  }
  out.reason = cornerDirections.empty()
                   ? "the " + container->name + " has no free place left for the " + part.name
                   : "the " + step.target.back().corner + " corner of the " + container->name +
                         " has no free place left for the " + part.name;
  return out;
}

std::vector<RelationCheck> PlacementPlanner::check(const CellDescription& scene, const CellObject& part,
                                                   const ExecutionStep& step,
                                                   const std::vector<std::pair<std::string, std::string>>& landmarkIds) const {
  std::vector<RelationCheck> checks;
  const srp::core::ViewFrame view = viewFrame(scene);
  const SceneGrounder grounder(scene, options_.grounding);
  const double tol = options_.relationTolerance_m;
  const Pose3& X = part.X_world_object;
  const Eigen::Vector2d p = X.translation().head<2>();
  const double yaw = yawOfPose(X);
  // The landmark instance: the one placement grounded (landmarkIds), else grounded now.
  auto landmarkOf = [&](std::size_t i, bool second, const ObjectReference& ref,
                        std::optional<CellObjectKind> kind) -> const CellObject* {
    if (i < landmarkIds.size()) {
      const std::string& id = second ? landmarkIds[i].second : landmarkIds[i].first;
      if (!id.empty()) return scene.find(id);
    }
    try {
      return &grounder.ground(ref, {}, kind);
    } catch (const GroundingError&) {
      return nullptr;
    }
  };
  for (std::size_t i = 0; i < step.target.size(); ++i) {
    const SpatialRelation& rel = step.target[i];
    RelationCheck c;
    c.relation = rel.relation;
    Kind kind = kindOf(rel);
    const CellObject* a = landmarkOf(i, false, rel.landmark,
                                     kind == Kind::Containment || kind == Kind::Corner
                                         ? std::optional<CellObjectKind>(CellObjectKind::Container)
                                         : std::nullopt);
    if (a && a->name == part.name) a = nullptr;
    if (kind == Kind::Stack && a) kind = a->kind == CellObjectKind::Container ? Kind::Containment : Kind::Stack;
    const CellObject* b = nullptr;
    if (kind == Kind::Between) {
      if (i < landmarkIds.size() && !landmarkIds[i].second.empty()) b = scene.find(landmarkIds[i].second);
      else if (rel.secondLandmark) b = landmarkOf(i, true, *rel.secondLandmark, std::nullopt);
    }
    c.landmarks = a ? a->name : rel.landmark.describe();
    if (!a || kind == Kind::Unknown || (kind == Kind::Between && !b)) {
      c.detail = !a ? "landmark not in the scene" : "relation not checkable";
      checks.push_back(c);
      continue;
    }
    switch (kind) {
      case Kind::Containment:
      case Kind::Corner: {
        // Smallest distance of the footprint to the inner walls (negative: over a wall).
        const Pose3 X_c = a->X_world_object.inverse() * X;
        const double yc = yawOfPose(X_c);
        const double ex = std::abs(std::cos(yc)) * part.size_m.x() / 2 + std::abs(std::sin(yc)) * part.size_m.y() / 2;
        const double ey = std::abs(std::sin(yc)) * part.size_m.x() / 2 + std::abs(std::cos(yc)) * part.size_m.y() / 2;
        const double margin = std::min(a->size_m.x() / 2 - a->wallThickness_m - std::abs(X_c.translation().x()) - ex,
                                       a->size_m.y() / 2 - a->wallThickness_m - std::abs(X_c.translation().y()) - ey);
        c.quantity = "margin to the inner walls";
        c.value_m = margin;
        c.holds = isInside(part, *a) && margin >= -tol;
        c.detail = "footprint " + fmt(margin) + " inside the walls";
        if (kind == Kind::Corner) {
          std::istringstream words(rel.corner);
          double worst = 1e9;
          for (std::string w; words >> w;)
            if (auto d = view.direction(w == "back" || w == "rear" ? "behind" : w))
              worst = std::min(worst, (p - centre(*a)).dot(*d));
          c.holds = c.holds && worst > 0.0 && worst < 1e8;
          c.detail += ", " + fmt(worst == 1e9 ? 0.0 : worst) + " into the " + rel.corner + " quadrant";
        }
        break;
      }
      case Kind::Stack: {
        const double top = a->X_world_object.translation().z() + a->size_m.z();
        const double height = X.translation().z() - top;
        const Eigen::Vector3d p_a = a->X_world_object.inverse() * X.translation();
        const bool over = std::abs(p_a.x()) <= a->size_m.x() / 2 && std::abs(p_a.y()) <= a->size_m.y() / 2;
        c.quantity = "height above the lower part's top";
        c.value_m = height;
        c.holds = std::abs(height) <= tol && over && X.linear().col(2).z() > std::cos(10.0 * M_PI / 180.0);
        c.detail = "bottom " + fmt(height) + " above the " + a->name + "'s top, centre " +
                   fmt(p_a.head<2>().norm()) + " off its centre";
        break;
      }
      case Kind::Neighbour:
      case Kind::Direction: {
        const Eigen::Vector2d off = p - centre(*a);
        const Eigen::Vector2d dir = kind == Kind::Direction ? *view.direction(normaliseName(rel.relation))
                                                            : off.normalized();
        const Eigen::Vector2d perp(-dir.y(), dir.x());
        const double along = off.dot(dir), lateral = std::abs(off.dot(perp));
        const double gap = along - support(*a, dir) - support(part.size_m, yaw, dir);
        c.quantity = "gap";
        c.value_m = gap;
        if (kind == Kind::Neighbour) {
          c.holds = gap > -1e-3 && gap <= options_.neighbourGap_m + options_.neighbourTolerance_m;
          c.detail = "gap " + fmt(gap) + " to the " + a->name;
        } else {
          c.holds = gap > -1e-3 && along > lateral;
          c.detail = "gap " + fmt(gap) + " along '" + rel.relation + "', lateral offset " + fmt(lateral);
        }
        break;
      }
      case Kind::Between: {
        c.landmarks = a->name + " and " + b->name;
        const Eigen::Vector2d ca = centre(*a), cb = centre(*b);
        const double length = (cb - ca).norm();
        const Eigen::Vector2d u = (cb - ca) / std::max(length, 1e-9), perp(-u.y(), u.x());
        const double t = (p - ca).dot(u), lateral = std::abs((p - ca).dot(perp));
        const double sP = support(part.size_m, yaw, u);
        const double gapA = t - support(*a, u) - sP, gapB = length - t - support(*b, u) - sP;
        const double lateralLimit = std::max(support(*a, perp), support(*b, perp));
        c.quantity = "lateral offset from the line";
        c.value_m = lateral;
        c.holds = gapA > -1e-3 && gapB > -1e-3 && lateral <= lateralLimit + tol;
        c.detail = "gaps " + fmt(gapA) + " / " + fmt(gapB) + ", lateral offset " + fmt(lateral);
        break;
      }
      case Kind::Unknown:
        break;
    }
    checks.push_back(c);
  }
  return checks;
}

}  // namespace srp::execution
