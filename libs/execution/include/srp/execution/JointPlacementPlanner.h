#pragma once
/// \file JointPlacementPlanner.h
/// \brief Plans where every step of an instruction puts its part, all steps together and
/// before anything moves, so that a part placed first leaves room for the relations
/// asked later ("the cuboid in the gray box, then the star left of it in the gray box";
/// "two parts in the box, then a third between them").
///
/// Each step's target relations are a constraint on its part's pose; a later step's
/// relations constrain the earlier parts (its landmarks, the room it needs). The search:
/// 1. Candidates per step: PlacementPlanner::candidates() in the scene as the earlier
///    steps leave it (a grid with yaw choices per relation, PlacementRelations.h), best
///    first: the demonstration's placement, then nearer to it, short motions.
/// 2. Depth-first over the steps in plan order, each candidate followed by forward
///    checking: every later step whose landmarks are known by then must still have a
///    candidate in the scene as it would be (parts that later steps move are left out, a
///    relaxation, so a step it rules out is impossible). Branch and bound on the number of
///    steps placed: the first plan placing every step ends the search; otherwise the plan
///    placing the most, a step that no joint plan can satisfy being refused with the reason.
///    A candidate that failed rules out its neighbours nearer than `spread_m` at its level.
/// 3. Margins first: a first search keeps clearance_m and wallMargin_m everywhere; only
///    when it cannot place every step, a second one also takes tight places (down to
///    minClearance_m, PlacementContext::Options::tight()).
/// 4. Refinement: when the chosen plan has tight places, the planned parts are moved
///    continuously (x, y, yaw; NLopt, COBYLA) to raise the gaps below clearance_m and
///    wallMargin_m towards them, each part moving as little as possible, every relation
///    kept; the refined plan is used only when every relation and rule still checks.
/// Frames: world = table frame, z up, metres.

#include <cstddef>
#include <string>
#include <vector>

#include "srp/execution/CellDescription.h"
#include "srp/execution/ExecutionPlan.h"
#include "srp/execution/PlacementPlanner.h"
#include "srp/execution/PlannedPlacement.h"

namespace srp::execution {

class JointPlacementPlanner {
 public:
  struct Options {
    /// Candidate poses tried (forward-checked) over one search, at most; the search keeps
    /// its best plan when it runs out.
    int maxTrials = 3000;
    /// After a candidate failed, candidates of the same step nearer than this (same yaw)
    /// are not tried [m].
    double spread_m = 0.01;
    bool refine = true;  ///< continuous refinement of tight clearances (NLopt)
  };

  JointPlacementPlanner();
  explicit JointPlacementPlanner(PlacementContext::Options placement);
  JointPlacementPlanner(PlacementContext::Options placement, Options options);

  /// One PlannedPlacement per step of `plan`, planned in `scene` as it is before any step
  /// runs (the steps' parts are grounded there, a later step's in the scene the earlier
  /// planned placements leave).
  std::vector<PlannedPlacement> plan(const CellDescription& scene, const ExecutionPlan& plan) const;

  const PlacementPlanner& planner() const { return planner_; }
  const Options& options() const { return options_; }

 private:
  PlacementPlanner planner_;
  Options options_;
};

}  // namespace srp::execution
