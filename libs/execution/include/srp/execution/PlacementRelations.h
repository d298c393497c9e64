#pragma once
/// \file PlacementRelations.h
/// \brief One function per placing relation: the candidate poses of a part for a
/// resolved target (PlacementTarget), best first, each allowed by the context
/// (PlacementContext: clearances, walls, table, reach). PlacementPlanner takes the first
/// whose relations check; JointPlacementPlanner searches them for all steps at once.
///
/// Order of the candidates (the first is what a one-step planner would choose):
/// - In / Corner: a grid (gridStep_m) over the container's inner footprint minus the
///   wall margin, nearest to the demonstrated position in the container, else to the
///   inner corner nearest to where the part comes from (a named corner: that corner,
///   only its quadrant); the part along the container's axes, then the other turns
///   (PlacementContext::Options::turnStep_rad: 90 degrees).
/// - OnTop: centred on the lower part, its yaw (one pose).
/// - NextTo: beside the landmark with neighbourGap_m between the footprints, on the
///   demonstration's side first (else the side facing the container's centre), slid
///   along that side to stay inside the container; then slid further along the side,
///   then gaps down to clearance_m and up to neighbourGap_m + neighbourTolerance_m / 2,
///   then the other turns.
/// - Direction: neighbourGap_m beyond the landmark's footprint along the view direction d,
///   then further out (up to 12 cm in a container, 30 cm on the table) and sideways,
///   within 45 degrees of d; then the other turns; then gaps down to
///   clearance_m (1 mm steps); on the table (when the container was implied by the
///   landmark, not named) only when the container has no place.
/// - Between: between the landmarks along the line of their centres (sideways up to the
///   larger one's half-width), the middle of the free space between their footprints
///   first, the part's narrower side along the line (then the other turns), clearance_m
///   from both; in the landmarks' container, then on the table.
/// placementCandidates() lists these, then (`tight`) those the rules of
/// PlacementContext::Options::tight() add: minClearance_m to parts and walls, a finer grid, yaw
/// choices every 15 degrees.

#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include "srp/core/Pose.h"
#include "srp/execution/PlacementContext.h"
#include "srp/execution/PlacementTarget.h"

namespace srp::execution {

/// One allowed pose of the part.
struct PlacementCandidate {
  srp::core::Pose3 X_world_object = srp::core::Pose3::Identity();
  std::string container;  ///< the container it rests in ("" on the table or stacked)
  std::string stackedOn;  ///< OnTop: the lower part's id
  /// Allowed only by the tight rules (PlacementContext::Options::tight()): less margin.
  bool tight = false;
};

/// The candidates of one relation, best first; `reason` says why there are none.
struct PlacementCandidates {
  std::vector<PlacementCandidate> poses;
  std::string reason;
};

constexpr std::size_t kAllCandidates = std::numeric_limits<std::size_t>::max();

/// The candidates for `target` (dispatches on target.kind), at most `limit`; with
/// `tight`, after those the tight ones.
PlacementCandidates placementCandidates(const PlacementContext& ctx, const PlacementTarget& target,
                                        std::size_t limit = kAllCandidates, bool tight = true);

/// In and Corner: inside the target container.
PlacementCandidates placeIn(const PlacementContext& ctx, const PlacementTarget& target, std::size_t limit);
/// OnTop: stacked on the landmark part (refused when another part already lies on it).
PlacementCandidates placeOnTop(const PlacementContext& ctx, const PlacementTarget& target, std::size_t limit);
/// NextTo: beside the landmark.
PlacementCandidates placeNextTo(const PlacementContext& ctx, const PlacementTarget& target, std::size_t limit);
/// Direction: left of / right of / in front of / behind the landmark.
PlacementCandidates placeInDirection(const PlacementContext& ctx, const PlacementTarget& target, std::size_t limit);
/// Between: between the two landmarks.
PlacementCandidates placeBetween(const PlacementContext& ctx, const PlacementTarget& target, std::size_t limit);

}  // namespace srp::execution
