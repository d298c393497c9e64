#pragma once
/// \file DuplicatePartsDemo.h
/// \brief A pick & place demo in a scene with two parts of one class that
/// differ by colour (a red and a blue cuboid): the demonstrator moves one of
/// them into a container past the other, so that perception must keep the
/// two apart through occlusion by the hand and through the carry (issue 19).

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>

#include "srp/core/ObjectCatalogue.h"
#include "srp/core/Scene.h"

namespace srp::synth {

struct DuplicatePartsOptions {
  std::string className = "cuboid";     ///< the class of both parts
  std::string colours[2] = {"red", "blue"};  ///< colour words of the two instances (core::rgbOfColourName)
  std::string targetId = "gray box";    ///< container (an id of the base scene) the moved part goes into
  /// The moved part starts in this window of the table (world x, y, m) ...
  double startXMin_m = -0.22, startXMax_m = -0.08, startYMin_m = -0.14, startYMax_m = -0.04;
  /// ... and the other part lies on the way from it to the container: at this
  /// fraction of the way (drawn uniformly) and this far to the side of the
  /// straight line (either side), so the hand passes near it or over it.
  double wayMin = 0.3, wayMax = 0.55;
  double sideMin_m = 0.0, sideMax_m = 0.04;
};

struct DuplicatePartsDemo {
  srp::core::Scene scene;
  nlohmann::json plan;   ///< srp parse --json step format (PickPlacePlan.h), with "instruction"
  std::string movedId;   ///< the instance the demonstrator moves ("cuboid_red")
  std::string otherId;   ///< the instance that stays
};

/// The base scene (camera, table, lighting, containers kept; its parts
/// removed) with two parts of `options.className`, ids "<class>_<colour>"
/// (spaces as '_'), placed and turned at random from `seed`, and the plan
/// "pick up the <colour> <class> and place it in the <target>" for one of
/// them (the first colour's for even seeds, the second's for odd ones).
/// Deterministic in `seed`. Throws
/// InvalidInputError when the class or the target is unknown, or the
/// scene does not validate.
DuplicatePartsDemo makeDuplicatePartsDemo(const srp::core::Scene& base, const srp::core::ObjectCatalogue& catalogue,
                                          std::uint32_t seed, const DuplicatePartsOptions& options = {});

}  // namespace srp::synth
