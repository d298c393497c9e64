#include "srp/execution/PlacementTarget.h"

#include <cmath>
#include <sstream>

#include "srp/core/Text.h"

namespace srp::execution {
namespace {

using srp::core::normaliseName;

bool isStackWord(const std::string& r) {
  return r == "on" || r == "onto" || r == "on to" || r == "on top of" || r == "upon" || r == "atop" ||
         r == "on the top of" || r == "stacked on";
}

/// The instances the step's relations name (nullptr: not named).
struct Grounded {
  const CellObject* container = nullptr;
  const CellObject* neighbour = nullptr;
  const CellObject* stackOn = nullptr;
  const CellObject* direction = nullptr;
  const CellObject* betweenA = nullptr;
  const CellObject* betweenB = nullptr;
};

/// One landmark phrase -> one instance (SceneGrounder), else nullptr and the reason
/// naming the candidates.
const CellObject* groundLandmark(const SceneGrounder& grounder, const CellObject& part, const SpatialRelation& rel,
                                 const ObjectReference& ref, std::optional<CellObjectKind> kind, std::string& reason) {
  const CellObject* o = nullptr;
  try {
    o = &grounder.ground(ref, {}, kind);
  } catch (const GroundingError& e) {
    reason = "target '" + rel.relation + " the " + ref.describe() + "': " + e.what();
    return nullptr;
  }
  if (o->name == part.name) {
    reason = "the " + part.name + " cannot be placed " + rel.relation + " itself";
    return nullptr;
  }
  return o;
}

/// "between A and B" (each one instance) or "between the stars" (a plural naming exactly two).
bool groundBetween(const SceneGrounder& grounder, const CellObject& part, const SpatialRelation& rel, Grounded& g,
                   std::string& reason) {
  if (rel.secondLandmark) {
    g.betweenA = groundLandmark(grounder, part, rel, rel.landmark, std::nullopt, reason);
    if (!g.betweenA) return false;
    g.betweenB = groundLandmark(grounder, part, rel, *rel.secondLandmark, std::nullopt, reason);
    if (!g.betweenB) return false;
  } else {
    std::vector<const CellObject*> both;
    for (const CellObject* o : grounder.candidates(rel.landmark))
      if (o->name != part.name) both.push_back(o);
    if (both.size() != 2) {
      reason = "'between' needs two landmarks; 'the " + rel.landmark.describe() + "' names " +
               std::to_string(both.size()) + " instance(s) in the scene";
      return false;
    }
    g.betweenA = both[0];
    g.betweenB = both[1];
  }
  if (g.betweenA->name == g.betweenB->name) {
    reason = "'between' needs two different landmarks; both name the " + g.betweenA->name;
    return false;
  }
  return true;
}

/// The two view directions of "front left" etc.; false when the words do not name a corner.
bool cornerDirectionsOf(const std::string& corner, const srp::core::ViewFrame& view, std::vector<Eigen::Vector2d>& out) {
  std::istringstream words(corner);
  for (std::string w; words >> w;)
    if (auto d = view.direction(w == "rear" ? "behind" : w)) out.push_back(*d);
  return out.size() == 2 && std::abs(out[0].dot(out[1])) <= 0.5;
}

/// One target relation: its landmarks into `g` and `t` (ids for check()); false with the reason.
bool groundRelation(const PlacementContext& ctx, const SceneGrounder& grounder, const SpatialRelation& rel,
                    PlacementTarget& t, Grounded& g, std::string& reason) {
  const std::optional<PlacementKind> named = placementKindOf(rel);
  if (!named) {
    reason = "unknown target relation '" + rel.relation +
             "' (known: in/into/on/onto, on top of, next to/beside/adjacent to, left of, right of, in front "
             "of, behind, between, in the <front|back> <left|right> corner of)";
    return false;
  }
  PlacementKind kind = *named;
  const CellObject& part = ctx.part();
  if (kind == PlacementKind::OnTop) {
    const CellObject* l = groundLandmark(grounder, part, rel, rel.landmark, std::nullopt, reason);
    if (!l) return false;
    if (l->kind == CellObjectKind::Container) kind = PlacementKind::In;
  }
  std::pair<std::string, std::string> ids;
  const CellObject** slot = nullptr;
  std::optional<CellObjectKind> landmarkKind;
  switch (kind) {
    case PlacementKind::In: slot = &g.container, landmarkKind = CellObjectKind::Container; break;
    case PlacementKind::Corner: slot = &g.container, landmarkKind = CellObjectKind::Container; break;
    case PlacementKind::NextTo: slot = &g.neighbour, landmarkKind = CellObjectKind::Part; break;
    case PlacementKind::OnTop: slot = &g.stackOn, landmarkKind = CellObjectKind::Part; break;
    case PlacementKind::Direction: slot = &g.direction; break;
    case PlacementKind::Between:
      if (!groundBetween(grounder, part, rel, g, reason)) return false;
      t.landmarkIds.emplace_back(g.betweenA->name, g.betweenB->name);
      return true;
  }
  *slot = groundLandmark(grounder, part, rel, rel.landmark, landmarkKind, reason);
  if (!*slot) return false;
  ids.first = (*slot)->name;
  if (kind == PlacementKind::Corner) {
    t.cornerDirections.clear();
    if (!cornerDirectionsOf(rel.corner, ctx.view(), t.cornerDirections)) {
      reason = "unknown corner '" + rel.corner + "' of the " + g.container->name +
               " (say front left, front right, back left or back right)";
      return false;
    }
    t.corner = rel.corner;
  }
  if (kind == PlacementKind::Direction) {
    t.direction = *ctx.view().direction(normaliseName(rel.relation));
    t.directionText = rel.relation;
  }
  t.landmarkIds.push_back(ids);
  return true;
}

}  // namespace

std::optional<PlacementKind> placementKindOf(const SpatialRelation& rel) {
  const std::string r = normaliseName(rel.relation);
  if (!rel.corner.empty() || r.find("corner") != std::string::npos) return PlacementKind::Corner;
  if (r == "between" || r == "in between") return PlacementKind::Between;
  if (!srp::core::ViewFrame::directionWord(r).empty()) return PlacementKind::Direction;
  if (isNeighbourRelation(r)) return PlacementKind::NextTo;
  if (isStackWord(r)) return PlacementKind::OnTop;
  if (isContainmentRelation(r)) return PlacementKind::In;
  return std::nullopt;
}

std::optional<PlacementTarget> resolveTarget(const PlacementContext& ctx, const ExecutionStep& step,
                                             std::string& reason) {
  const CellObject& part = ctx.part();
  const SceneGrounder grounder(ctx.scene(), ctx.options().grounding);
  PlacementTarget t;
  Grounded g;
  for (const auto& rel : step.target)
    if (!groundRelation(ctx, grounder, rel, t, g, reason)) return std::nullopt;
  // Several "next to" relations keep the last one; other mixes are ambiguous.
  const int others = (g.stackOn != nullptr) + (g.direction != nullptr) + (g.betweenA != nullptr);
  if (others > 1 || (others == 1 && g.neighbour)) {
    reason = "the target relations of the " + part.name + " name several landmarks to place it by; give one";
    return std::nullopt;
  }
  const CellObject* landmark = g.stackOn ? g.stackOn : g.direction ? g.direction : g.betweenA ? g.betweenA : g.neighbour;
  t.containerNamed = g.container != nullptr;
  const CellObject* container = g.container;
  if (!container && landmark && landmark->kind == CellObjectKind::Part && !g.stackOn) {
    // "beside the star" with the star in a container: the part goes in there too.
    if (g.betweenA) {
      const CellObject* ca = ctx.containerOf(*g.betweenA);
      const CellObject* cb = g.betweenB->kind == CellObjectKind::Part ? ctx.containerOf(*g.betweenB) : nullptr;
      if (ca && cb && ca->name == cb->name) container = ca;
    } else {
      for (const auto& o : ctx.scene().objects)
        if (o.kind == CellObjectKind::Container && isInside(*landmark, o)) container = &o;
    }
  }
  if (!container && !landmark) {
    reason = "the instruction gives no target location for the " + part.name;
    return std::nullopt;
  }
  t.kind = g.stackOn      ? PlacementKind::OnTop
           : g.direction  ? PlacementKind::Direction
           : g.betweenA   ? PlacementKind::Between
           : g.neighbour  ? PlacementKind::NextTo
           : t.cornerDirections.empty() ? PlacementKind::In
                                        : PlacementKind::Corner;
  t.container = container ? container->name : "";
  t.landmark = landmark ? landmark->name : "";
  t.secondLandmark = g.betweenB ? g.betweenB->name : "";
  t.demoOffsetFromNeighbour_m = step.demoOffsetFromNeighbour_m;
  t.demoPositionInContainer_m = step.demoPositionInContainer_m;
  return t;
}

}  // namespace srp::execution
