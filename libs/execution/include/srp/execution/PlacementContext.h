#pragma once
/// \file PlacementContext.h
/// \brief The scene one part is placed in and the rules every placed pose keeps: the
/// other parts and the clearance to them, the containers' walls, the table top, the
/// arm's reach (PlacementContext::Options). The relations (PlacementRelations.h) propose poses;
/// the context says whether a pose is allowed.
///
/// Frames: world = table frame, z up, metres; a part's frame has its origin at the
/// centre of its bottom face. Every pose the context accepts is upright.

#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "srp/core/Pose.h"
#include "srp/core/ViewFrame.h"
#include "srp/execution/CellDescription.h"
#include "srp/execution/SceneGrounder.h"

namespace srp::execution {

class PlacementContext {
 public:
  /// The clearances, reach and search steps of placement (PlacementContext, PlacementPlanner,
  /// JointPlacementPlanner).
  struct Options {
    double neighbourGap_m = 0.015;  ///< gap between footprints of neighbours
    double wallMargin_m = 0.008;    ///< free space between a placed part and a wall
    double clearance_m = 0.008;     ///< minimum gap to any other part
    /// A tight place (tried only where no place keeps clearance_m and wallMargin_m) keeps at
    /// least this to the other parts and the walls.
    double minClearance_m = 0.002;
    /// A placed part's centre keeps this from every container wall (inner walls inside it,
    /// the outer outline outside) that the suction tool comes level with. The tool (the URDF's
    /// `suction_tool`: a cylinder of radius 20 mm, the suction cup, 12-18 mm, inside it) is
    /// lowered vertically onto the part's top with its axis through the part's centre
    /// (TaskExecutor's "lower" segment), so wherever the part's top lies less than
    /// minClearance_m above a wall's top, the tool passes beside that wall and keeps the
    /// SafetyChecker's 2 mm from it: 20 + 2 mm from the axis. Parts whose top lies higher
    /// (stacked, or beside a low tray) need only their footprint's clearances.
    double toolClearance_m = 0.022;
    double gridStep_m = 0.005;             ///< candidate spacing (halved for tight places)
    double turnStep_rad = M_PI / 2;        ///< yaw choices of a part: its reference yaw turned by this step
    double tightTurnStep_rad = M_PI / 12;  ///< and for tight places
    double minReach_m = 0.15;              ///< horizontal distance from the robot base, at least
    double maxReach_m = 0.80;              ///< and at most (UR5: 0.85 m)
    double neighbourTolerance_m = 0.015;   ///< extra gap allowed when checking "next to"
    double relationTolerance_m = 0.005;    ///< slack of the after-placement relation checks
    /// How landmarks are found (SceneGrounder) and the view (grounding.viewpoint) in
    /// which left/right/front/behind/corners are read, for grounding and placement alike.
    SceneGrounder::Options grounding;

    /// The rules of a tight place: clearance_m and wallMargin_m down to minClearance_m,
    /// half the grid step, the turns of tightTurnStep_rad.
    Options tight() const;
  };

  /// Keeps references: `scene`, `part` and `options` must outlive the context. `part`
  /// is the part being placed; it is no obstacle to itself.
  PlacementContext(const CellDescription& scene, const CellObject& part, const Options& options);

  const CellDescription& scene() const { return scene_; }
  const CellObject& part() const { return part_; }
  const Options& options() const { return options_; }
  /// Left/right/front/behind under options().grounding.viewpoint.
  const srp::core::ViewFrame& view() const { return view_; }

  /// The container whose inner walls hold the footprint centre of `o`, nullptr if none.
  const CellObject* containerOf(const CellObject& o) const;
  /// The part's whole footprint at X, plus wallMargin_m, inside `container`'s inner walls,
  /// its centre toolClearanceFrom(container, X) from them.
  bool fitsInside(const CellObject& container, const srp::core::Pose3& X) const;
  /// On the table top and clear of every container's outer walls by wallMargin_m (the
  /// centre by toolClearanceFrom(container, X)).
  bool fitsTable(const srp::core::Pose3& X) const;
  /// How far the part's centre must keep from `container`'s walls with the part at X (its
  /// bottom at X's height): toolClearance_m where the tool lowered onto it comes level with
  /// the walls, else 0.
  double toolClearanceFrom(const CellObject& container, const srp::core::Pose3& X) const;
  /// Horizontal distance of X from the robot base within [minReach_m, maxReach_m].
  bool inReach(const srp::core::Pose3& X) const;
  /// No other part within clearance_m of the part at X at X's height: parts stacked
  /// above or below do not count.
  bool isFree(const srp::core::Pose3& X) const;
  /// The turns (about z, radians) to try from a reference yaw: every turnStep_rad over
  /// half a turn (a quarter for a square footprint), the reference first.
  std::vector<double> turns() const;

  /// The part upright at (p_world, yaw) resting where it may: on `container`'s floor
  /// inside its walls, or (container nullptr) on the table top, or on the floor of a
  /// container its footprint falls wholly into; free of the other parts; within reach
  /// when `checkReach`. nullopt when no such rest exists.
  std::optional<srp::core::Pose3> rest(const Eigen::Vector2d& p_world, double yaw, const CellObject* container,
                                       bool checkReach) const;

 private:
  const CellDescription& scene_;
  const CellObject& part_;
  const Options& options_;
  srp::core::ViewFrame view_;
};

}  // namespace srp::execution
