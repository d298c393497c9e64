#pragma once
/// \file PlacementTarget.h
/// \brief What a step's target relations ask of the part, with every landmark grounded
/// to one instance of the scene (SceneGrounder): the relation that places the part,
/// its landmarks, the container it goes in (named, or the landmarks' own) and what the
/// demonstration showed. Instances are kept by id, so one target can be evaluated in
/// several versions of a scene (the joint planner moves earlier steps' parts).

#include <Eigen/Core>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "srp/execution/ExecutionPlan.h"
#include "srp/execution/PlacementContext.h"

namespace srp::execution {

/// The relation that fixes a placed part's pose.
enum class PlacementKind {
  In,         ///< "in / into / on X" (X a container)
  Corner,     ///< "in the <front|back> <left|right> corner of X"
  OnTop,      ///< "on / onto / on top of Y" (Y a part): stacked
  NextTo,     ///< "next to / beside / adjacent to / near Y"
  Direction,  ///< "left of / right of / in front of / behind Y" (view frame)
  Between,    ///< "between A and B"
};

struct PlacementTarget {
  PlacementKind kind = PlacementKind::In;
  /// The container the part goes in (instance id; "" = the table): the one named,
  /// else the one holding the landmark(s) (the part may then go beside it on the
  /// table when it has no room: containerNamed false).
  std::string container;
  bool containerNamed = false;
  std::string landmark;        ///< Y of OnTop / NextTo / Direction, A of Between (id)
  std::string secondLandmark;  ///< B of Between (id)
  Eigen::Vector2d direction = Eigen::Vector2d::Zero();  ///< Direction: unit vector on the table
  std::string directionText;                            ///< Direction: "left of", ...
  std::vector<Eigen::Vector2d> cornerDirections;        ///< Corner: the two view directions
  std::string corner;                                   ///< Corner: "front left", ...
  /// The step's demonstration hints (ExecutionStep).
  std::optional<Eigen::Vector2d> demoOffsetFromNeighbour_m;
  std::optional<Eigen::Vector2d> demoPositionInContainer_m;
  /// Per step.target: the landmark instance ids (second: B of "between"), for check().
  std::vector<std::pair<std::string, std::string>> landmarkIds;
};

/// The placing relation a relation phrase names: "on"/"onto"/"on top of" give OnTop (In
/// when its landmark turns out to be a container); nullopt for an unknown phrase.
std::optional<PlacementKind> placementKindOf(const SpatialRelation& relation);

/// Grounds the landmarks of `step`'s target relations in ctx.scene() and works out the
/// placing relation and the container; nullopt with `reason` set when a landmark is
/// missing or ambiguous, the relation unknown, or the relations contradict.
std::optional<PlacementTarget> resolveTarget(const PlacementContext& ctx, const ExecutionStep& step,
                                             std::string& reason);

}  // namespace srp::execution
