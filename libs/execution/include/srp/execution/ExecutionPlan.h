#pragma once
/// \file ExecutionPlan.h
/// \brief The ordered pick & place plan the Execution Module runs: per target
/// object its name and colour, its source and target spatial relations, and what
/// the demonstration showed about where it ended up.
///
/// Built from the Language Module's TaskPlan (a new instruction) or from a stored
/// task model (Products / SourceLocations / TargetLocations); see PlanConversion.h.

#include <Eigen/Core>

#include "srp/core/SpatialRelations.h"
#include "srp/language/TaskPlan.h"
#include <optional>
#include <string>
#include <vector>

namespace srp::execution {

/// An object named in the instruction ("box" + colour "blue"; "cuboid"; "the
/// second red cube"; "the cube behind the star"): the Language Module's ObjectRef,
/// one type for the whole stack (name, colour, ordinal, superlative, relations).
/// SceneGrounder resolves it to one instance of the scene.
using ObjectReference = srp::language::ObjectRef;

/// A spatial relation: "in" / "into" / "from" / "next to" / "beside" / "adjacent to" / "near" /
/// "on top of" / "left of" / "right of" / "in front of" / "behind" / "between" / "corner" ...
/// and its landmark (the Language Module's LocationRef): `secondLandmark` is B of
/// "between A and B" (A is `landmark`), `corner` the view words of "in the front
/// left corner of X" ("front left", see srp/core/ViewFrame.h), "" otherwise.
using SpatialRelation = srp::language::LocationRef;

struct ExecutionStep {
  ObjectReference object;
  std::vector<SpatialRelation> source;  ///< where it is now (may be empty: anywhere); grounding uses them
  std::vector<SpatialRelation> target;  ///< where it must go (must not be empty)
  /// Demonstrated final offset of the object from its neighbour landmark (world x, y
  /// [m]), used to choose the side for "next to"; nullopt: no demonstration.
  std::optional<Eigen::Vector2d> demoOffsetFromNeighbour_m;
  /// Demonstrated final position of the object in its container's frame (x, y [m]),
  /// preferred for "in X"; nullopt: the container's centre is preferred.
  std::optional<Eigen::Vector2d> demoPositionInContainer_m;
};

struct ExecutionPlan {
  std::vector<ExecutionStep> steps;
};

// The relation words, shared with the demo generator (srp/core/SpatialRelations.h).
using srp::core::isContainmentRelation;
using srp::core::isNeighbourRelation;

}  // namespace srp::execution
