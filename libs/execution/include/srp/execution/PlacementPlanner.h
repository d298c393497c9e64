#pragma once
/// \file PlacementPlanner.h
/// \brief Computes where a part must be put so that the target relations hold
/// (thesis ch. 7.4: the target pose estimated from the landmark's pose and the
/// spatial relation), and checks after the placement whether they do. Landmarks
/// are found by SceneGrounder (one instance, or the reason naming the candidates).
///
/// Geometry rules (world = table frame, z up, metres; every placed part is upright,
/// rests on the table, a container floor or the part it is stacked on, keeps
/// `clearance_m` to every other part at its height, stays inside the container's
/// inner walls minus `wallMargin_m`, on the table; for stacking and the view and
/// "between" relations also within [minReach_m, maxReach_m] of the robot base,
/// horizontally, while "in" and "next to" leave reach to the inverse kinematics,
/// which refuses the step naming the unreachable tool pose):
/// - "in X" / "into X" / "on X" (X a container): inside X's inner footprint, nearest
///   to the demonstrated position in X when known, else to the inner corner nearest to
///   where the part comes from (leaving room for neighbours); an oblong part is turned
///   by 90 degrees when no place is free along X's axes (also for a named corner).
/// - "in the <front|back> <left|right> corner of X": inside X, nearest to that inner
///   corner, the corner named in the view frame (see srp/core/ViewFrame.h).
/// - "on Y" / "onto Y" / "on top of Y" (Y a part): stacked, centred on Y with Y's yaw,
///   bottom on Y's top face; refused when another part already lies on Y.
/// - "next to Y" / "beside" / "adjacent to" ...: beside Y on the side the demonstration
///   used when known (else the side with the most room), `neighbourGap_m` between the
///   footprints, inside Y's container if Y is in one.
/// - "left of" / "right of" / "in front of" / "behind" Y: beside Y along that view
///   direction d with `neighbourGap_m` between the footprints (further out or shifted
///   sideways when that place is taken, as long as the lateral offset stays below
///   the offset along d, i.e. within 45 degrees of d).
/// - "between A and B": on the segment A-B, centred in the free space between their
///   footprints, clearance_m from A and B; refused when no place between them keeps
///   minClearance_m from both (the reason gives the room along the line and what the
///   part's narrower side needs).
/// - a place on the table that lies wholly inside a container rests on its floor.
/// The yaw of a placed part is its container's, else its landmark's; "between" turns the
/// part's narrower side along A-B; other turns come after (PlacementRelations.h).
/// Where no place keeps clearance_m and wallMargin_m, a tight place keeps minClearance_m
/// (PlacementContext::Options::tight(): also a finer grid and more yaw choices). A placed part's
/// centre keeps toolClearance_m from every container wall the suction tool, lowered onto
/// the part's top, comes level with (PlacementContext::Options::toolClearance_m).
/// An impossible placement gives the reason and no pose.
///
/// Structure: PlacementTarget.h grounds the landmarks (resolveTarget), PlacementContext.h
/// holds the scene and the rules above, PlacementRelations.h has one function per
/// relation proposing candidate poses best first; place() takes the first candidate whose
/// relations check, and JointPlacementPlanner searches the candidates of every step of an
/// instruction together.

#include <cstddef>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "srp/core/ViewFrame.h"
#include "srp/execution/CellDescription.h"
#include "srp/execution/ExecutionPlan.h"
#include "srp/execution/ExecutionReport.h"
#include "srp/execution/PlacementContext.h"

namespace srp::execution {

/// The result of placement: a pose, or the reason there is none.
struct Placement {
  std::optional<srp::core::Pose3> X_world_object;
  std::string container;  ///< name of the containing object, "" for the table
  std::string neighbour;  ///< name of the "next to" landmark, "" if none
  std::string stackedOn;  ///< name of the part it is stacked on, "" if none
  /// The instance ids the target relations' landmarks were grounded to, in
  /// step.target order (second: B of "between A and B", else ""), for check().
  std::vector<std::pair<std::string, std::string>> landmarkIds;
  /// A tight place: nearer the other parts or the walls than clearance_m / wallMargin_m
  /// (at least minClearance_m, PlacementContext::Options::tight()), a placement with less margin.
  bool tight = false;
  std::string reason;     ///< why there is no placement
};

class PlacementPlanner {
 public:
  explicit PlacementPlanner(PlacementContext::Options options = {}) : options_(options) {}

  /// The view frame of `scene` under options().grounding.viewpoint (viewFrameOf).
  srp::core::ViewFrame viewFrame(const CellDescription& scene) const;

  /// Target pose for `part` satisfying `target` in `scene` (which holds the other
  /// parts at their current poses; `part` itself is ignored as an obstacle): the first
  /// candidate (PlacementRelations.h) whose relations check (check()).
  Placement place(const CellDescription& scene, const CellObject& part, const ExecutionStep& step) const;

  /// The candidates of place() whose relations check, best first, at most `limit` (with
  /// `tight`, the tight places after the others); empty with `reason` set when there is
  /// none. The joint planner's choices for one step.
  std::vector<Placement> candidates(const CellDescription& scene, const CellObject& part, const ExecutionStep& step,
                                    std::size_t limit, std::string& reason, bool tight = true) const;

  /// True when every target relation of `step` holds (check()) with `part` at X in
  /// `scene`, the landmarks being the instances `landmarkIds` names.
  bool holdsAt(const CellDescription& scene, const CellObject& part, const ExecutionStep& step,
               const std::vector<std::pair<std::string, std::string>>& landmarkIds, const srp::core::Pose3& X) const;

  /// The candidate of `scene` (the landmarks where they are now) nearest to `planned`
  /// (planned earlier, e.g. in the scene the joint planner expected): the same place,
  /// recomputed; nullopt when none lies within `tolerance_m` with the same yaw (modulo a
  /// half turn) or its relations do not check.
  std::optional<Placement> candidateNear(const CellDescription& scene, const CellObject& part, const ExecutionStep& step,
                                         const Placement& planned, double tolerance_m) const;

  /// True when `placement` (planned earlier, e.g. by JointPlacementPlanner) is still
  /// allowed for `part` in `scene`: its relations check and it keeps the walls, the table
  /// and the clearances (a tight place those of PlacementContext::Options::tight()).
  bool stillAllowed(const CellDescription& scene, const CellObject& part, const ExecutionStep& step,
                    const Placement& placement) const;

  /// Each target relation of `step` checked on `scene` (the scene after the
  /// placement; `part` at its final pose in it). A landmark missing from the scene
  /// gives a check that does not hold. `landmarkIds` (Placement::landmarkIds) names the
  /// instances placement used; without them the landmarks are grounded in `scene`
  /// (an ordinal may then count the moved part).
  std::vector<RelationCheck> check(const CellDescription& scene, const CellObject& part, const ExecutionStep& step,
                                   const std::vector<std::pair<std::string, std::string>>& landmarkIds = {}) const;

  const PlacementContext::Options& options() const { return options_; }

 private:
  PlacementContext::Options options_;
};

}  // namespace srp::execution
