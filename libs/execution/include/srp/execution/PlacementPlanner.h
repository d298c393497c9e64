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
///   footprints, clearance_m from A and B when there is room, else in the middle down to
///   betweenMinClearance_m; refused when the space is narrower than the part's narrower
///   side plus two betweenMinClearance_m.
/// - a place on the table that lies wholly inside a container rests on its floor.
/// The yaw of a placed part is its container's, else its landmark's; "between" turns the
/// part's narrower side along A-B.
/// An impossible placement gives the reason and no pose.

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "srp/core/ViewFrame.h"
#include "srp/execution/CellDescription.h"
#include "srp/execution/ExecutionPlan.h"
#include "srp/execution/ExecutionReport.h"
#include "srp/execution/SceneGrounder.h"

namespace srp::execution {

struct PlacementOptions {
  double neighbourGap_m = 0.015;  ///< gap between footprints of neighbours
  double wallMargin_m = 0.008;    ///< free space between a placed part and a wall
  double clearance_m = 0.008;     ///< minimum gap to any other part
  /// "between A and B" in a gap narrower than the part + 2 x clearance_m: the part goes
  /// in the middle, at least this far from A and B (other parts keep clearance_m).
  double betweenMinClearance_m = 0.003;
  double gridStep_m = 0.005;      ///< candidate spacing for "in X"
  double minReach_m = 0.15;       ///< horizontal distance from the robot base, at least
  double maxReach_m = 0.80;       ///< and at most (UR5: 0.85 m)
  double neighbourTolerance_m = 0.015;  ///< extra gap allowed when checking "next to"
  double relationTolerance_m = 0.005;  ///< slack of the after-placement relation checks
  /// How landmarks are found (SceneGrounder) and the view (grounding.viewpoint) in
  /// which left/right/front/behind/corners are read, for grounding and placement alike.
  GroundingOptions grounding;
};

/// The result of placement: a pose, or the reason there is none.
struct Placement {
  std::optional<srp::core::Pose3> X_world_object;
  std::string container;  ///< name of the containing object, "" for the table
  std::string neighbour;  ///< name of the "next to" landmark, "" if none
  std::string stackedOn;  ///< name of the part it is stacked on, "" if none
  /// The instance ids the target relations' landmarks were grounded to, in
  /// step.target order (second: B of "between A and B", else ""), for check().
  std::vector<std::pair<std::string, std::string>> landmarkIds;
  std::string reason;     ///< why there is no placement
};

class PlacementPlanner {
 public:
  explicit PlacementPlanner(PlacementOptions options = {}) : options_(options) {}

  /// True when the footprint centre of `part` lies inside `container`'s inner footprint.
  static bool isInside(const CellObject& part, const CellObject& container);

  /// The view frame of `scene` under options().grounding.viewpoint (viewFrameOf).
  srp::core::ViewFrame viewFrame(const CellDescription& scene) const;

  /// Target pose for `part` satisfying `target` in `scene` (which holds the other
  /// parts at their current poses; `part` itself is ignored as an obstacle).
  Placement place(const CellDescription& scene, const CellObject& part, const ExecutionStep& step) const;

  /// Each target relation of `step` checked on `scene` (the scene after the
  /// placement; `part` at its final pose in it). A landmark missing from the scene
  /// gives a check that does not hold. `landmarkIds` (Placement::landmarkIds) names the
  /// instances placement used; without them the landmarks are grounded in `scene`
  /// (an ordinal may then count the moved part).
  std::vector<RelationCheck> check(const CellDescription& scene, const CellObject& part, const ExecutionStep& step,
                                   const std::vector<std::pair<std::string, std::string>>& landmarkIds = {}) const;

  const PlacementOptions& options() const { return options_; }

 private:
  /// No other part within clearance_m of `part` at X at its height; `near` (if not
  /// empty) are kept only `nearClearance_m` away ("between": its two landmarks).
  bool isFree(const CellDescription& scene, const CellObject& part, const srp::core::Pose3& X,
              const std::vector<std::string>& near = {}, double nearClearance_m = 0.0) const;
  PlacementOptions options_;
};

}  // namespace srp::execution
