#include "srp/execution/PlacementPlanner.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "PlacementGeometry.h"
#include "srp/core/Text.h"
#include "srp/execution/PlacementRelations.h"
#include "srp/execution/PlacementTarget.h"

namespace srp::execution {
namespace {

using namespace placement;
using srp::core::normaliseName;

/// Containment and corner: the footprint's smallest margin to the inner walls (negative:
/// over a wall); a corner also needs the centre in its quadrant.
RelationCheck checkContainment(const SpatialRelation& rel, bool corner, const CellObject& part, const CellObject& box,
                               const srp::core::ViewFrame& view, double tol) {
  RelationCheck c;
  const double margin = marginToInnerWalls(part.size_m, part.X_world_object, box);
  c.quantity = "margin to the inner walls";
  c.value_m = margin;
  const Eigen::Vector3d p_box = box.X_world_object.inverse() * part.X_world_object.translation();
  const double centreInside = std::min(box.size_m.x() / 2 - box.wallThickness_m - std::abs(p_box.x()),
                                       box.size_m.y() / 2 - box.wallThickness_m - std::abs(p_box.y()));
  c.holds = isInside(part, box) && margin >= -tol;
  c.slack_m = std::min(centreInside, margin + tol);
  c.detail = "footprint " + fmt(margin) + " inside the walls";
  if (corner) {
    std::istringstream words(rel.corner);
    double worst = 1e9;
    for (std::string w; words >> w;)
      if (auto d = view.direction(w == "back" || w == "rear" ? "behind" : w))
        worst = std::min(worst, (centre(part) - centre(box)).dot(*d));
    c.holds = c.holds && worst > 0.0 && worst < 1e8;
    c.slack_m = std::min(c.slack_m, worst);
    c.detail += ", " + fmt(worst == 1e9 ? 0.0 : worst) + " into the " + rel.corner + " quadrant";
  }
  return c;
}

/// Stacking: the bottom on the lower part's top, the centre over its footprint, upright.
RelationCheck checkStack(const CellObject& part, const CellObject& lower, double tol) {
  RelationCheck c;
  const Pose3& X = part.X_world_object;
  const double height = X.translation().z() - (lower.X_world_object.translation().z() + lower.size_m.z());
  const Eigen::Vector3d p_a = lower.X_world_object.inverse() * X.translation();
  const bool over = std::abs(p_a.x()) <= lower.size_m.x() / 2 && std::abs(p_a.y()) <= lower.size_m.y() / 2;
  c.quantity = "height above the lower part's top";
  c.value_m = height;
  c.holds = std::abs(height) <= tol && over && X.linear().col(2).z() > std::cos(10.0 * M_PI / 180.0);
  c.slack_m = std::min(tol - std::abs(height), std::min(lower.size_m.x() / 2 - std::abs(p_a.x()),
                                                       lower.size_m.y() / 2 - std::abs(p_a.y())));
  c.detail = "bottom " + fmt(height) + " above the " + lower.name + "'s top, centre " + fmt(p_a.head<2>().norm()) +
             " off its centre";
  return c;
}

/// "next to" (dir = nullopt: along the centres' offset) and the view directions: the gap
/// between the footprints along the direction; a view direction also needs the offset
/// within 45 degrees of it.
RelationCheck checkBeside(const SpatialRelation& rel, const std::optional<Eigen::Vector2d>& viewDir,
                          const CellObject& part, const CellObject& a, const PlacementContext::Options& o) {
  RelationCheck c;
  const Eigen::Vector2d off = centre(part) - centre(a);
  const Eigen::Vector2d dir = viewDir ? *viewDir : Eigen::Vector2d(off.normalized());
  const Eigen::Vector2d perp(-dir.y(), dir.x());
  const double along = off.dot(dir), lateral = std::abs(off.dot(perp));
  const double gap = along - support(a, dir) - support(part, dir);
  c.quantity = "gap";
  c.value_m = gap;
  if (!viewDir) {
    c.holds = gap > -1e-3 && gap <= o.neighbourGap_m + o.neighbourTolerance_m;
    c.slack_m = std::min(gap + 1e-3, o.neighbourGap_m + o.neighbourTolerance_m - gap);
    c.detail = "gap " + fmt(gap) + " to the " + a.name;
  } else {
    c.holds = gap > -1e-3 && along > lateral;
    c.slack_m = std::min(gap + 1e-3, along - lateral);
    c.detail = "gap " + fmt(gap) + " along '" + rel.relation + "', lateral offset " + fmt(lateral);
  }
  return c;
}

/// "between A and B": both gaps along the line A-B open, the centre near that line.
RelationCheck checkBetween(const CellObject& part, const CellObject& a, const CellObject& b, double tol) {
  RelationCheck c;
  c.landmarks = a.name + " and " + b.name;
  const Eigen::Vector2d ca = centre(a), cb = centre(b), p = centre(part);
  const double length = (cb - ca).norm();
  const Eigen::Vector2d u = (cb - ca) / std::max(length, 1e-9), perp(-u.y(), u.x());
  const double t = (p - ca).dot(u), lateral = std::abs((p - ca).dot(perp));
  const double sP = support(part, u);
  const double gapA = t - support(a, u) - sP, gapB = length - t - support(b, u) - sP;
  const double lateralLimit = std::max(support(a, perp), support(b, perp));
  c.quantity = "lateral offset from the line";
  c.value_m = lateral;
  c.holds = gapA > -1e-3 && gapB > -1e-3 && lateral <= lateralLimit + tol;
  c.slack_m = std::min({gapA + 1e-3, gapB + 1e-3, lateralLimit + tol - lateral});
  c.detail = "gaps " + fmt(gapA) + " / " + fmt(gapB) + ", lateral offset " + fmt(lateral);
  return c;
}

}  // namespace

srp::core::ViewFrame PlacementPlanner::viewFrame(const CellDescription& scene) const {
  return scene.viewFrame(options_.grounding.viewpoint);
}

std::vector<Placement> PlacementPlanner::candidates(const CellDescription& scene, const CellObject& part,
                                                    const ExecutionStep& step, std::size_t limit,
                                                    std::string& reason, bool tight) const {
  const PlacementContext ctx(scene, part, options_);
  const std::optional<PlacementTarget> target = resolveTarget(ctx, step, reason);
  if (!target) return {};
  std::vector<Placement> out;
  // Most first candidates check; fetch a few more than asked, everything only when they do not.
  for (const std::size_t fetch : {limit == kAllCandidates ? limit : 4 * limit + 4, kAllCandidates}) {
    out.clear();
    const PlacementCandidates found = placementCandidates(ctx, *target, fetch, tight);
    reason = found.reason;
    for (const auto& c : found.poses) {
      if (!holdsAt(scene, part, step, target->landmarkIds, c.X_world_object)) continue;
      Placement p;
      p.X_world_object = c.X_world_object;
      p.container = c.container;
      p.neighbour = target->kind == PlacementKind::NextTo ? target->landmark : "";
      p.stackedOn = c.stackedOn;
      p.landmarkIds = target->landmarkIds;
      p.tight = c.tight;
      out.push_back(std::move(p));
      if (out.size() >= limit) return out;
    }
    if (found.poses.size() < fetch) break;  // that was every candidate
  }
  if (out.empty() && reason.empty())
    reason = "no place for the " + part.name + " where its target relations hold (" +
             std::to_string(step.target.size()) + " relation(s) checked)";
  return out;
}

Placement PlacementPlanner::place(const CellDescription& scene, const CellObject& part,
                                  const ExecutionStep& step) const {
  std::string reason;
  std::vector<Placement> found = candidates(scene, part, step, 1, reason);
  if (!found.empty()) return found.front();
  Placement none;
  none.reason = reason;
  return none;
}

bool PlacementPlanner::holdsAt(const CellDescription& scene, const CellObject& part, const ExecutionStep& step,
                               const std::vector<std::pair<std::string, std::string>>& landmarkIds,
                               const Pose3& X) const {
  CellDescription moved = scene;
  CellObject* self = nullptr;
  for (auto& o : moved.objects)
    if (o.name == part.name) self = &o;
  if (!self) {
    moved.objects.push_back(part);
    self = &moved.objects.back();
  }
  self->X_world_object = X;
  const auto checks = check(moved, *self, step, landmarkIds);
  return std::all_of(checks.begin(), checks.end(), [](const RelationCheck& c) { return c.holds; });
}

std::optional<Placement> PlacementPlanner::candidateNear(const CellDescription& scene, const CellObject& part,
                                                         const ExecutionStep& step, const Placement& planned,
                                                         double tolerance_m) const {
  if (!planned.X_world_object) return std::nullopt;
  const Pose3& P = *planned.X_world_object;
  const PlacementContext ctx(scene, part, options_);
  std::string reason;
  const std::optional<PlacementTarget> target = resolveTarget(ctx, step, reason);
  if (!target) return std::nullopt;
  const PlacementCandidates found = placementCandidates(ctx, *target, kAllCandidates, planned.tight);
  const PlacementCandidate* best = nullptr;
  double bestDistance = tolerance_m;
  for (const auto& c : found.poses) {
    const double d = (c.X_world_object.translation() - P.translation()).norm();
    if (d <= bestDistance && std::abs(std::remainder(yawOfPose(c.X_world_object) - yawOfPose(P), M_PI)) < 1e-6)
      best = &c, bestDistance = d;
  }
  if (!best || !holdsAt(scene, part, step, target->landmarkIds, best->X_world_object)) return std::nullopt;
  Placement p = planned;
  p.X_world_object = best->X_world_object;
  p.container = best->container;
  p.stackedOn = best->stackedOn;
  p.landmarkIds = target->landmarkIds;
  p.tight = best->tight;
  return p;
}

bool PlacementPlanner::stillAllowed(const CellDescription& scene, const CellObject& part, const ExecutionStep& step,
                                    const Placement& placement) const {
  if (!placement.X_world_object) return false;
  const Pose3& X = *placement.X_world_object;
  if (!holdsAt(scene, part, step, placement.landmarkIds, X)) return false;
  const PlacementContext::Options rules = placement.tight ? options_.tight() : options_;
  const PlacementContext ctx(scene, part, rules);
  if (!ctx.isFree(X)) return false;
  if (!placement.stackedOn.empty()) return true;
  if (const CellObject* box = scene.find(placement.container)) return ctx.fitsInside(*box, X);
  if (X.translation().z() < 1e-6) return ctx.fitsTable(X);
  // A table place resting on a container's floor.
  return std::any_of(scene.objects.begin(), scene.objects.end(), [&](const CellObject& o) {
    return o.kind == CellObjectKind::Container && ctx.fitsInside(o, X);
  });
}

std::vector<RelationCheck> PlacementPlanner::check(const CellDescription& scene, const CellObject& part,
                                                   const ExecutionStep& step,
                                                   const std::vector<std::pair<std::string, std::string>>& landmarkIds) const {
  std::vector<RelationCheck> checks;
  const srp::core::ViewFrame view = viewFrame(scene);
  const SceneGrounder grounder(scene, options_.grounding);
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
    std::optional<PlacementKind> kind = placementKindOf(rel);
    const bool inside = kind == PlacementKind::In || kind == PlacementKind::Corner;
    const CellObject* a = landmarkOf(i, false, rel.landmark,
                                     inside ? std::optional<CellObjectKind>(CellObjectKind::Container) : std::nullopt);
    if (a && a->name == part.name) a = nullptr;
    if (kind == PlacementKind::OnTop && a && a->kind == CellObjectKind::Container) kind = PlacementKind::In;
    const CellObject* b = nullptr;
    if (kind == PlacementKind::Between) {
      if (i < landmarkIds.size() && !landmarkIds[i].second.empty()) b = scene.find(landmarkIds[i].second);
      else if (rel.secondLandmark) b = landmarkOf(i, true, *rel.secondLandmark, std::nullopt);
    }
    RelationCheck c;
    if (!a || !kind || (kind == PlacementKind::Between && !b)) {
      c.detail = !a ? "landmark not in the scene" : "relation not checkable";
      c.slack_m = -1.0;
    } else if (kind == PlacementKind::In || kind == PlacementKind::Corner) {
      c = checkContainment(rel, kind == PlacementKind::Corner, part, *a, view, options_.relationTolerance_m);
    } else if (kind == PlacementKind::OnTop) {
      c = checkStack(part, *a, options_.relationTolerance_m);
    } else if (kind == PlacementKind::NextTo || kind == PlacementKind::Direction) {
      const auto viewDir = kind == PlacementKind::Direction ? view.direction(normaliseName(rel.relation)) : std::nullopt;
      c = checkBeside(rel, viewDir, part, *a, options_);
    } else {
      c = checkBetween(part, *a, *b, options_.relationTolerance_m);
    }
    c.relation = rel.relation;
    if (c.landmarks.empty()) c.landmarks = a ? a->name : rel.landmark.describe();
    checks.push_back(c);
  }
  return checks;
}

}  // namespace srp::execution
