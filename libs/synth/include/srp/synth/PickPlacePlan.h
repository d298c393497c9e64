#pragma once
/// \file PickPlacePlan.h
/// \brief The demonstrator's script: an instruction's plan (the `srp parse
/// --json` step format of the Language Module) grounded in a scene.

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "srp/core/ObjectCatalogue.h"
#include "srp/core/Scene.h"

namespace srp::synth {

/// One grounded pick & place step: move scene object `objectId` from the
/// container `sourceId` into the container `targetId`, beside `referenceId`
/// when the instruction says "next to/beside/adjacent to" (empty otherwise).
struct PickPlaceStep {
  std::string objectId;
  std::string sourceId;     ///< container the object is taken from (may be empty: on the table)
  std::string targetId;     ///< container it is placed in
  std::string referenceId;  ///< object it is placed beside, or empty
};

/// Grounds a plan JSON
/// `{"steps": [{"object": {"name": "cuboid", "color": null},
///              "source": [{"relation": "from", "landmark": {"name": "box", "color": "blue"}}],
///              "target": [{"relation": "in", "landmark": {"name": "box", "color": "gray"}}]}]}`
/// in a scene: nouns are grounded with ObjectCatalogue::ground(noun, colour),
/// then mapped to the scene object of that class (the first not yet moved).
/// Target relations "next to", "beside", "adjacent to", "near" name the
/// reference object; the container is then the explicit one or the one the
/// reference ends up in. Throws InvalidInputError naming the step and field
/// ("plan step 2: target: no container ...").
std::vector<PickPlaceStep> groundPlan(const nlohmann::json& plan, const srp::core::Scene& scene,
                                      const srp::core::ObjectCatalogue& catalogue,
                                      const std::string& context = "plan");

/// Instruction 1 of SPEC.md §4 in the plan format: cuboid, star,
/// parallelogram, octagon from the blue box into the gray box, each next to
/// the previous.
nlohmann::json defaultPlanJson();

}  // namespace srp::synth
