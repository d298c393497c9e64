#pragma once
/// \file PlannedPlacement.h
/// \brief One step of a joint placement plan (JointPlacementPlanner.h): the part and
/// its placement, or why the step is refused. World = table frame, z up, metres.

#include <string>
#include <vector>

#include "srp/core/Pose.h"
#include "srp/execution/CellDescription.h"

#include "srp/execution/PlacementPlanner.h"

namespace srp::execution {

/// Where one step of a plan puts its part, or why it does not.
struct PlannedPlacement {
  std::string part;     ///< instance id of the step's part; "" when it could not be grounded
  Placement placement;  ///< the pose (and landmarks), or the reason
  /// No joint plan could place the step (or every place for it would block more later
  /// steps): refused before anything moves. False for a part that is not in the scene.
  bool refused = false;
};

/// `scene` with the part called `name` at `X_world_part` (unchanged when it has no such part).
CellDescription withPartAt(CellDescription scene, const std::string& name, const srp::core::Pose3& X_world_part);

/// The scene after `steps` with every planned part at its planned pose.
CellDescription sceneAfterPlacements(const CellDescription& scene, const std::vector<PlannedPlacement>& steps);

}  // namespace srp::execution
