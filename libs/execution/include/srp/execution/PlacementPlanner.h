#pragma once
/// \file PlacementPlanner.h
/// \brief Computes where a part
/// must be put so that the target relations hold (thesis ch. 7.4: the target pose
/// estimated from the landmark's pose and the spatial relation). Landmarks are
/// found by SceneGrounder (one instance, or the reason naming the candidates).
///
/// "in X": inside X's inner footprint (walls and a margin excluded), clear of the
/// parts already there, nearest to the demonstrated position in X when known, else
/// to the inner corner nearest to where the part comes from (leaving room for neighbours). "next to Y": beside Y, on the side
/// the demonstration used when known (else the side with the most room), with a
/// gap, inside the container when an "in" relation is also given, clear of other
/// parts. The placed pose has the container's (or table's) yaw and rests on the
/// container floor or the table. Frames: world = table frame, z up; metres.

#include <optional>
#include <string>
#include <vector>

#include "srp/execution/CellDescription.h"
#include "srp/execution/ExecutionPlan.h"
#include "srp/execution/SceneGrounder.h"

namespace srp::execution {

struct PlacementOptions {
  double neighbourGap_m = 0.015;  ///< gap between footprints of neighbours
  double wallMargin_m = 0.008;    ///< free space between a placed part and a wall
  double clearance_m = 0.008;     ///< minimum gap to any other part
  double gridStep_m = 0.005;      ///< candidate spacing for "in X"
  GroundingOptions grounding;     ///< how landmarks are found (SceneGrounder) and the view frame
};

/// The result of placement: a pose, or the reason there is none.
struct Placement {
  std::optional<srp::core::Pose3> X_world_object;
  std::string container;  ///< name of the containing object, "" for the table
  std::string neighbour;  ///< name of the neighbour landmark, "" if none
  std::string reason;     ///< why there is no placement
};

class PlacementPlanner {
 public:
  explicit PlacementPlanner(PlacementOptions options = {}) : options_(options) {}

  /// True when the footprint centre of `part` lies inside `container`'s inner footprint.
  static bool isInside(const CellObject& part, const CellObject& container);

  /// Target pose for `part` satisfying `target` in `scene` (which holds the other
  /// parts at their current poses; `part` itself is ignored as an obstacle).
  Placement place(const CellDescription& scene, const CellObject& part, const ExecutionStep& step) const;

  const PlacementOptions& options() const { return options_; }

 private:
  bool isFree(const CellDescription& scene, const CellObject& part, const srp::core::Pose3& X) const;
  PlacementOptions options_;
};

}  // namespace srp::execution
