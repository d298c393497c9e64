#include "srp/execution/JointPlacementPlanner.h"

#include <algorithm>
#include <cmath>
#include <set>

#include "PlacementGeometry.h"
#include "PlacementRefinement.h"
#include "srp/execution/PlacementRelations.h"
#include "srp/execution/PlacementTarget.h"
#include "srp/execution/SceneGrounder.h"

namespace srp::execution {
namespace {

using namespace placement;

/// The step's part in `scene` (SceneGrounder, with the step's source locations), else nullptr and why.
const CellObject* groundPart(const CellDescription& scene, const ExecutionStep& step,
                             const SceneGrounder::Options& options, std::string& reason) {
  try {
    return &SceneGrounder(scene, options).ground(step.object, step.source, CellObjectKind::Part);
  } catch (const GroundingError& e) {
    reason = e.what();
    return nullptr;
  }
}

/// The depth-first branch-and-bound search over the steps' candidates (JointPlacementPlanner.h).
class Search {
 public:
  Search(const PlacementPlanner& planner, const JointPlacementPlanner::Options& options, const ExecutionPlan& plan,
         std::vector<std::string> movers, bool allowTight)
      : planner_(planner), options_(options), plan_(plan), movers_(std::move(movers)), allowTight_(allowTight) {}

  void run(const CellDescription& scene) {
    const std::size_t n = plan_.steps.size();
    current_.assign(n, {});
    impossible_.assign(n, false);
    // Steps no plan can satisfy: infeasible even with every earlier step's part taken away.
    for (std::size_t j = 0; j < n; ++j) impossible_[j] = feasibility(j, 0, scene, true) == 0;
    dfs(0, scene);
  }
  const std::vector<PlannedPlacement>& best() const { return best_; }
  int placed() const { return bestPlaced_; }

 private:
  struct Trial {
    std::size_t index;
    int laterFailures;
  };

  /// Can step j still be placed in `scene` (the steps before `from` planned in it)? The
  /// parts of the steps from `from` up to j are left out (they move before j: a
  /// relaxation). 1 yes, 0 no, -1 unknown (a landmark moves in between).
  int feasibility(std::size_t j, std::size_t from, const CellDescription& scene, bool removeFrom) const {
    if (movers_[j].empty()) return -1;
    const CellObject* part = scene.find(movers_[j]);
    if (!part) return -1;
    std::set<std::string> removed;
    for (std::size_t k = removeFrom ? from : from + 1; k < j; ++k)
      if (!movers_[k].empty() && movers_[k] != movers_[j]) removed.insert(movers_[k]);
    std::string reason;
    const PlacementContext full(scene, *part, planner_.options());
    const std::optional<PlacementTarget> target = resolveTarget(full, plan_.steps[j], reason);
    if (!target) return -1;
    for (const auto& [a, b] : target->landmarkIds)
      if (removed.count(a) || removed.count(b)) return -1;
    CellDescription relaxed = scene;
    relaxed.objects.erase(std::remove_if(relaxed.objects.begin(), relaxed.objects.end(),
                                         [&](const CellObject& o) { return removed.count(o.name) > 0; }),
                          relaxed.objects.end());
    // A candidate allowed by the rules is enough (its relations are not checked: still a relaxation).
    const PlacementContext ctx(relaxed, *relaxed.find(movers_[j]), planner_.options());
    for (const std::size_t limit : {std::size_t{1}, kAllCandidates}) {
      const PlacementCandidates found = placementCandidates(ctx, *target, limit, allowTight_);
      if (!found.poses.empty()) return 1;
      if (found.poses.size() < limit) break;
    }
    return 0;
  }

  /// How many later steps (not already impossible) lose every candidate with step i planned as in `next`.
  int laterFailures(std::size_t i, const CellDescription& next) const {
    int failures = 0;
    for (std::size_t j = i + 1; j < plan_.steps.size(); ++j)
      if (!impossible_[j] && feasibility(j, i, next, false) == 0) ++failures;
    return failures;
  }

  int possibleFrom(std::size_t i) const {
    return static_cast<int>(std::count(impossible_.begin() + static_cast<std::ptrdiff_t>(i), impossible_.end(), false));
  }

  bool stop() const { return complete_ || trials_ > options_.maxTrials; }

  void descend(std::size_t i, const CellDescription& next, const Placement& p) {
    current_[i].placement = p;
    current_[i].refused = false;
    ++placed_;
    dfs(i + 1, next);
    --placed_;
  }

  void dfs(std::size_t i, const CellDescription& scene) {
    if (stop() || placed_ + possibleFrom(i) <= bestPlaced_) return;
    if (i == plan_.steps.size()) {
      best_ = current_;
      bestPlaced_ = placed_;
      complete_ = refusals_ == 0;
      return;
    }
    PlannedPlacement& slot = current_[i];
    slot = PlannedPlacement{};
    const ExecutionStep& step = plan_.steps[i];
    const CellObject* part = groundPart(scene, step, planner_.options().grounding, slot.placement.reason);
    if (!part || impossible_[i]) {  // not in the scene (the executor says so), or no plan can place it
      if (part) slot.part = part->name, slot.refused = true;
      dfs(i + 1, scene);
      return;
    }
    slot.part = part->name;
    std::vector<Placement> candidates;
    std::size_t fetched = 0;
    bool more = true;
    auto candidateAt = [&](std::size_t k) -> const Placement* {
      while (k >= candidates.size() && more) {
        fetched = fetched == 0 ? 8 : fetched * 8;
        std::string reason;
        candidates = planner_.candidates(scene, *part, step, fetched, reason, allowTight_);
        more = candidates.size() >= fetched;
      }
      return k < candidates.size() ? &candidates[k] : nullptr;
    };
    std::vector<Trial> trials;
    std::vector<Pose3> failed;
    auto nearFailed = [&](const Pose3& X) {
      return std::any_of(failed.begin(), failed.end(), [&](const Pose3& F) {
        return (F.translation() - X.translation()).head<2>().norm() < options_.spread_m &&
               std::abs(std::remainder(yawOfPose(F) - yawOfPose(X), M_PI)) < 1e-6;
      });
    };
    // Candidates that keep every later step possible, best first.
    for (std::size_t k = 0; const Placement* c = candidateAt(k); ++k) {
      if ((c->tight && !allowTight_) || nearFailed(*c->X_world_object)) continue;
      if (++trials_ > options_.maxTrials) return;
      const CellDescription next = withPartAt(scene, part->name, *c->X_world_object);
      const int failures = laterFailures(i, next);
      trials.push_back({k, failures});
      if (failures == 0) descend(i, next, *c);
      if (stop()) return;
      failed.push_back(*c->X_world_object);
    }
    // Then those that give up later steps, while they can still beat the best plan.
    for (const Trial& t : trials) {
      if (t.laterFailures == 0 || placed_ + 1 + possibleFrom(i + 1) - t.laterFailures <= bestPlaced_) continue;
      descend(i, withPartAt(scene, part->name, *candidates[t.index].X_world_object), candidates[t.index]);
      if (stop()) return;
    }
    // Or refuse this step.
    slot.placement = Placement{};
    slot.refused = true;
    ++refusals_;
    dfs(i + 1, scene);
    --refusals_;
  }

  const PlacementPlanner& planner_;
  const JointPlacementPlanner::Options& options_;
  const ExecutionPlan& plan_;
  std::vector<std::string> movers_;
  bool allowTight_;
  std::vector<bool> impossible_;
  std::vector<PlannedPlacement> current_, best_;
  int placed_ = 0, refusals_ = 0, bestPlaced_ = -1, trials_ = 0;
  bool complete_ = false;
};

/// The reason of each refused step, in the scene the plan's earlier steps leave.
void explainRefusals(const PlacementPlanner& planner, const CellDescription& scene, const ExecutionPlan& plan,
                     std::vector<PlannedPlacement>& steps) {
  CellDescription now = scene;
  for (std::size_t i = 0; i < steps.size(); ++i) {
    PlannedPlacement& s = steps[i];
    if (s.refused) {
      std::string reason;
      const CellObject* part = now.find(s.part);
      const bool some = part && !planner.candidates(now, *part, plan.steps[i], 1, reason).empty();
      s.placement.reason = some ? "every free place for the " + s.part +
                                      " would take the room a later step's relation needs; no plan of the steps "
                                      "together places them all"
                                : reason + (i > 0 ? " (with the earlier steps planned together)" : "");
    }
    if (s.placement.X_world_object) now = withPartAt(now, s.part, *s.placement.X_world_object);
  }
}

}  // namespace

JointPlacementPlanner::JointPlacementPlanner() : JointPlacementPlanner(PlacementContext::Options{}, Options{}) {}
JointPlacementPlanner::JointPlacementPlanner(PlacementContext::Options placement)
    : JointPlacementPlanner(std::move(placement), Options{}) {}
JointPlacementPlanner::JointPlacementPlanner(PlacementContext::Options placement, Options options)
    : planner_(std::move(placement)), options_(options) {}

std::vector<PlannedPlacement> JointPlacementPlanner::plan(const CellDescription& scene, const ExecutionPlan& plan) const {
  // Each step's part as the initial scene grounds it (for the forward checks only).
  std::vector<std::string> movers;
  for (const auto& step : plan.steps) {
    std::string reason;
    const CellObject* part = groundPart(scene, step, planner_.options().grounding, reason);
    movers.push_back(part ? part->name : "");
  }
  Search keepClearance(planner_, options_, plan, movers, false);
  keepClearance.run(scene);
  std::vector<PlannedPlacement> result = keepClearance.best();
  // Steps it had to refuse (even those impossible with the full clearance): try tight places too.
  if (std::any_of(result.begin(), result.end(), [](const PlannedPlacement& s) { return s.refused; })) {
    Search tight(planner_, options_, plan, movers, true);
    tight.run(scene);
    if (tight.placed() > keepClearance.placed()) result = tight.best();
  }
  explainRefusals(planner_, scene, plan, result);
  if (options_.refine) refineClearances(planner_, scene, plan, result);
  return result;
}

}  // namespace srp::execution
