#pragma once
// Continuous refinement of a joint placement plan (private to srp::execution; see
// JointPlacementPlanner.h, step 4).

#include <vector>

#include "srp/execution/CellDescription.h"
#include "srp/execution/ExecutionPlan.h"
#include "srp/execution/PlacementPlanner.h"
#include "srp/execution/PlannedPlacement.h"

namespace srp::execution {

/// When a planned step is tight (PlacementContext::Options::tight(): nearer parts or walls than
/// clearance_m / wallMargin_m), moves
/// the planned parts (x, y and yaw; the support kept) with NLopt's COBYLA to raise every
/// gap below clearance_m (and a tight part's wall margin below wallMargin_m) towards it,
/// each part moving and turning as little as it can (at
/// most 2 cm per coordinate, 0.2 rad),
/// subject to every step's relations (their slack kept at least at min(1 mm, before)),
/// the clearances, walls, table and reach in the scene each step is placed in. The
/// result replaces `steps` only when every step still checks (PlacementPlanner::holdsAt
/// and the context's rules). Plans with stacking or a part moved twice are left alone.
void refineClearances(const PlacementPlanner& planner, const CellDescription& scene, const ExecutionPlan& plan,
                      std::vector<PlannedPlacement>& steps);

}  // namespace srp::execution
