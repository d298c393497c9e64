#include "PlacementRefinement.h"

#include <nlopt.hpp>

#include <algorithm>
#include <cmath>
#include <set>

#include "PlacementGeometry.h"
#include "srp/execution/PlacementTarget.h"

namespace srp::execution {
namespace {

using namespace placement;

constexpr double kMove_m = 0.02;            // each coordinate stays within this of the discrete plan
constexpr double kTurn_rad = 0.2;           // and each yaw within this
constexpr double kTurnScale_rad = 0.1;      // objective: 1 per 0.1 rad turned (squared)
constexpr double kRelationSlack_m = 1e-3;   // relations keep this much slack (or what they had)
constexpr double kMoveScale_m = 0.01;       // objective: 1 per cm moved (squared)
constexpr double kGapScale_m = 0.001;       // objective: 10 per mm of clearance missing (squared)
constexpr double kGapWeight = 10.0;
constexpr double kGapAbove_m = 2e-4;        // aim this far above clearance_m (the optimum stops just short)
constexpr int kMaxEvaluations = 400;
constexpr double kInside_m = 2e-5;           // constraints are met this far inside

/// Step `step`'s part against the part `other` in the scene the step is placed in.
struct Pair {
  std::size_t step;
  std::string other;
  double required_m;  ///< the gap it must keep (the rule of the discrete plan)
};

class Refinement {
 public:
  Refinement(const PlacementPlanner& planner, const CellDescription& scene, const ExecutionPlan& plan,
             const std::vector<PlannedPlacement>& steps)
      : planner_(planner), o_(planner.options()), scene_(scene), plan_(plan), steps_(steps) {}

  /// False for plans it does not refine (nothing tight, stacking, a part moved twice, a table place on a floor).
  bool applicable() const {
    std::set<std::string> parts;
    bool tight = false;
    for (const auto& s : steps_) {
      if (!s.placement.X_world_object) continue;
      if (!s.placement.stackedOn.empty() || !parts.insert(s.part).second) return false;
      if (s.placement.container.empty() && s.placement.X_world_object->translation().z() > 1e-6) return false;
      tight = tight || s.placement.tight;
    }
    return tight;
  }

  /// Optimises; true when the refined plan checks and replaced steps().
  bool solve() {
    for (std::size_t i = 0; i < steps_.size(); ++i)
      if (steps_[i].placement.X_world_object) placed_.push_back(i);
    setUp();
    std::vector<double> x;
    for (const std::size_t i : placed_) {
      const Eigen::Vector3d p = steps_[i].placement.X_world_object->translation();
      x.push_back(p.x());
      x.push_back(p.y());
      x.push_back(yawOfPose(*steps_[i].placement.X_world_object));
    }
    start_ = x;
    nlopt::opt opt(nlopt::LN_COBYLA, static_cast<unsigned>(x.size()));
    std::vector<double> lower(x), upper(x);
    for (std::size_t k = 0; k < x.size(); ++k) {
      const double range = k % 3 == 2 ? kTurn_rad : kMove_m;
      lower[k] -= range, upper[k] += range;
    }
    opt.set_lower_bounds(lower);
    opt.set_upper_bounds(upper);
    opt.set_min_objective(&Refinement::objectiveOf, this);
    opt.add_inequality_mconstraint(&Refinement::constraintsOf, this, std::vector<double>(constraintCount_, 1e-6));
    opt.set_xtol_abs(1e-5);
    opt.set_maxeval(kMaxEvaluations);
    double value = 0.0;
    try {
      opt.optimize(x, value);
    } catch (const std::exception&) {
      return false;  // the discrete plan stays
    }
    const std::vector<PlannedPlacement> refined = at(x.data());
    if (!valid(refined)) return false;
    steps_ = refined;
    return true;
  }

  const std::vector<PlannedPlacement>& steps() const { return steps_; }

 private:
  /// The scene right after step i: the plan's steps up to i at their poses in `s`.
  CellDescription sceneAfter(std::size_t i, const std::vector<PlannedPlacement>& s) const {
    CellDescription now = scene_;
    for (std::size_t k = 0; k <= i; ++k)
      if (s[k].placement.X_world_object)
        for (auto& obj : now.objects)
          if (obj.name == s[k].part) obj.X_world_object = *s[k].placement.X_world_object;
    return now;
  }

  std::vector<PlannedPlacement> at(const double* x) const {
    std::vector<PlannedPlacement> s = steps_;
    for (std::size_t k = 0; k < placed_.size(); ++k) {
      Pose3& X = *s[placed_[k]].placement.X_world_object;
      X = uprightPose(Eigen::Vector3d(x[3 * k], x[3 * k + 1], X.translation().z()), x[3 * k + 2]);
    }
    return s;
  }

  /// The relations placed by the view directions and "between" keep the arm's reach.
  bool needsReach(std::size_t i) const {
    return std::any_of(plan_.steps[i].target.begin(), plan_.steps[i].target.end(), [](const SpatialRelation& r) {
      const auto kind = placementKindOf(r);
      return kind == PlacementKind::Direction || kind == PlacementKind::Between;
    });
  }

  /// The rules step i was planned with (tight: PlacementContext::Options::tight()).
  PlacementContext::Options rulesOf(std::size_t i) const { return steps_[i].placement.tight ? o_.tight() : o_; }

  /// The pairs to keep apart and the relation slack to keep, from the discrete plan.
  void setUp() {
    for (const std::size_t i : placed_) {
      const CellDescription now = sceneAfter(i, steps_);
      const CellObject& part = *now.find(steps_[i].part);
      for (const auto& o : now.objects) {
        if (o.kind != CellObjectKind::Part || o.name == part.name) continue;
        if (!verticalOverlap(part, part.X_world_object.translation().z(), o)) continue;
        pairs_.push_back({i, o.name, rulesOf(i).clearance_m});
      }
      for (const auto& c : planner_.check(now, part, plan_.steps[i], steps_[i].placement.landmarkIds))
        slack_.push_back(std::min(kRelationSlack_m, c.slack_m));
    }
    std::vector<double> g;
    constraints(start_.empty() ? nullptr : start_.data(), g, true);
    constraintCount_ = static_cast<unsigned>(g.size());
  }

  /// The constraints g <= 0 at x (the discrete plan when `counting`).
  void constraints(const double* x, std::vector<double>& g, bool counting) const {
    const std::vector<PlannedPlacement> s = counting ? steps_ : at(x);
    std::size_t slack = 0;
    for (const std::size_t i : placed_) {
      const CellDescription now = sceneAfter(i, s);
      const CellObject& part = *now.find(s[i].part);
      const Pose3& X = part.X_world_object;
      for (const auto& c : planner_.check(now, part, plan_.steps[i], s[i].placement.landmarkIds))
        g.push_back(slack_.empty() ? 0.0 : slack_[slack++] - c.slack_m);
      for (const auto& pair : pairs_)
        if (pair.step == i) {
          const CellObject& o = *now.find(pair.other);
          g.push_back(-separation(footprint(part.size_m, X, pair.required_m / 2), X,
                                  footprint(o.size_m, o.X_world_object, pair.required_m / 2), o.X_world_object));
        }
      const double wallMargin = rulesOf(i).wallMargin_m;
      if (const CellObject* box = now.find(s[i].placement.container)) {
        g.push_back(wallMargin - marginToInnerWalls(part.size_m, X, *box));
        g.push_back(toolClearance(part, *box) - distanceToWalls(*box, X.translation().head<2>()));
        continue;
      }
      for (const auto& c : now.objects)
        if (c.kind == CellObjectKind::Container) {
          g.push_back(-separation(footprint(part.size_m, X, wallMargin), X, footprint(c.size_m, c.X_world_object, 0.0),
                                  c.X_world_object));
          g.push_back(toolClearance(part, c) - distanceToWalls(c, X.translation().head<2>()));
        }
      const Eigen::Vector2d p = X.translation().head<2>() - now.tableCentre_m;
      g.push_back(std::abs(p.x()) + support(part, Eigen::Vector2d::UnitX()) - now.tableHalfExtents_m.x());
      g.push_back(std::abs(p.y()) + support(part, Eigen::Vector2d::UnitY()) - now.tableHalfExtents_m.y());
      if (!needsReach(i)) continue;
      const double r = (X.translation().head<2>() - now.X_world_base.translation().head<2>()).norm();
      g.push_back(o_.minReach_m - r);
      g.push_back(r - o_.maxReach_m);
    }
  }

  double toolClearance(const CellObject& part, const CellObject& container) const {
    return toolClearanceFrom(o_.toolClearance_m, o_.minClearance_m, part.size_m, part.X_world_object.translation().z(), container);
  }

  double objective(const double* x) const {
    double f = 0.0;
    for (std::size_t k = 0; k < 3 * placed_.size(); ++k)
      f += std::pow((x[k] - start_[k]) / (k % 3 == 2 ? kTurnScale_rad : kMoveScale_m), 2);
    const std::vector<PlannedPlacement> s = at(x);
    for (const std::size_t i : placed_) {
      const CellDescription now = sceneAfter(i, s);
      const CellObject& part = *now.find(s[i].part);
      if (const CellObject* box = now.find(s[i].placement.container); box && s[i].placement.tight)
        f += kGapWeight *
             std::pow(std::max(0.0, o_.wallMargin_m + kGapAbove_m - marginToInnerWalls(part.size_m, part.X_world_object, *box)) /
                          kGapScale_m,
                      2);
      for (const auto& pair : pairs_)
        if (pair.step == i && pair.required_m < o_.clearance_m) {
          const CellObject& o = *now.find(pair.other);
          const double target = o_.clearance_m + kGapAbove_m;
          const double sep = separation(footprint(part.size_m, part.X_world_object, target / 2), part.X_world_object,
                                        footprint(o.size_m, o.X_world_object, target / 2), o.X_world_object);
          f += kGapWeight * std::pow(std::min(0.0, sep) / kGapScale_m, 2);
        }
    }
    return f;
  }

  /// Every step still checks in the scene it is placed in, with the rules of the discrete plan.
  bool valid(const std::vector<PlannedPlacement>& s) const {
    for (const std::size_t i : placed_) {
      const CellDescription now = sceneAfter(i, s);
      const CellObject& part = *now.find(s[i].part);
      const Pose3& X = part.X_world_object;
      const PlacementContext::Options rules = rulesOf(i);
      const PlacementContext ctx(now, part, rules);
      const CellObject* box = now.find(s[i].placement.container);
      if (!planner_.holdsAt(now, part, plan_.steps[i], s[i].placement.landmarkIds, X) ||
          !(box ? ctx.fitsInside(*box, X) : ctx.fitsTable(X)) || !ctx.isFree(X))
        return false;
    }
    return true;
  }

  static double objectiveOf(unsigned, const double* x, double*, void* self) {
    return static_cast<const Refinement*>(self)->objective(x);
  }
  static void constraintsOf(unsigned m, double* result, unsigned, const double* x, double*, void* self) {
    std::vector<double> g;
    static_cast<const Refinement*>(self)->constraints(x, g, false);
    // COBYLA ends up to its tolerance outside a constraint: aim this far inside.
    for (unsigned k = 0; k < m; ++k) result[k] = (k < g.size() ? g[k] : 0.0) + kInside_m;
  }

  const PlacementPlanner& planner_;
  const PlacementContext::Options& o_;
  const CellDescription& scene_;
  const ExecutionPlan& plan_;
  std::vector<PlannedPlacement> steps_;
  std::vector<std::size_t> placed_;
  std::vector<Pair> pairs_;
  std::vector<double> slack_, start_;
  unsigned constraintCount_ = 0;
};

}  // namespace

void refineClearances(const PlacementPlanner& planner, const CellDescription& scene, const ExecutionPlan& plan,
                      std::vector<PlannedPlacement>& steps) {
  Refinement refinement(planner, scene, plan, steps);
  if (!refinement.applicable() || !refinement.solve()) return;
  steps = refinement.steps();
  // A step that now keeps the full clearances is no longer tight.
  for (std::size_t i = 0; i < steps.size(); ++i) {
    if (!steps[i].placement.X_world_object || !steps[i].placement.tight) continue;
    const CellDescription now = sceneAfterPlacements(scene, {steps.begin(), steps.begin() + i + 1});
    Placement full = steps[i].placement;
    full.tight = false;
    steps[i].placement.tight = !planner.stillAllowed(now, *now.find(steps[i].part), plan.steps[i], full);
  }
}

}  // namespace srp::execution
