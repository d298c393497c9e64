#include "srp/synth/PickPlacePlan.h"

#include "srp/core/SpatialRelations.h"

#include <algorithm>
#include <map>

#include "srp/core/Error.h"
#include "srp/core/Json.h"

namespace srp::synth {
namespace {

std::string optionalString(const nlohmann::json& j, const std::string& key) {
  if (!j.contains(key) || j.at(key).is_null()) return "";
  if (!j.at(key).is_string()) throw srp::core::InvalidInputError("field '" + key + "' must be a string or null");
  return j.at(key).get<std::string>();
}

/// Grounds a noun phrase {"name", "color"} to a scene object id: the class the catalogue grounds it
/// to, the instance of that colour when instances have colours, one not `moved` yet when
/// `preferUnmoved`.
std::string groundNounPhrase(const nlohmann::json& phrase, const std::string& where, bool preferUnmoved,
                             const srp::core::Scene& scene, const srp::core::ObjectCatalogue& catalogue,
                             const std::vector<std::string>& moved) {
  using srp::core::InvalidInputError;
  const auto& nameField = srp::core::requireField(phrase, "name", where);
  if (!nameField.is_string()) throw InvalidInputError(where + ": field 'name' must be a string");
  const std::string noun = nameField.get<std::string>();
  const std::string colour = optionalString(phrase, "color");
  const auto* cls = catalogue.ground(noun, colour);
  if (!cls)
    throw InvalidInputError(where + ": '" + (colour.empty() ? "" : colour + " ") + noun +
                            "' is not in the knowledge base (datasets/kb/catalogue.json)");
  // Several instances of the class: the colour picks among them (the scene's
  // per-instance "color"), when any instance has it.
  const bool byInstanceColour =
      !colour.empty() && std::any_of(scene.objects.begin(), scene.objects.end(), [&](const srp::core::SceneObject& o) {
        return o.className == cls->name && srp::core::instanceColour(o, *cls) == colour;
      });
  const srp::core::SceneObject* chosen = nullptr;
  for (const auto& o : scene.objects) {
    if (o.className != cls->name) continue;
    if (byInstanceColour && srp::core::instanceColour(o, *cls) != colour) continue;
    const bool isMoved = std::find(moved.begin(), moved.end(), o.id) != moved.end();
    if (!chosen || (preferUnmoved && !isMoved && std::find(moved.begin(), moved.end(), chosen->id) != moved.end()))
      chosen = &o;
  }
  if (!chosen) throw InvalidInputError(where + ": no '" + cls->name + "' in scene '" + scene.name + "'");
  return chosen->id;
}

}  // namespace

std::vector<PickPlaceStep> groundPlan(const nlohmann::json& plan, const srp::core::Scene& scene,
                                      const srp::core::ObjectCatalogue& catalogue, const std::string& context) {
  using srp::core::InvalidInputError;
  // Accept a bare array of steps as well as {"steps": [...]}.
  const auto& steps = plan.is_array() ? plan : srp::core::requireField(plan, "steps", context);
  if (!steps.is_array() || steps.empty()) throw InvalidInputError(context + ": 'steps' must be a non-empty array");

  // Which container each part is in, tracked as steps move them.
  std::map<std::string, std::string> containerOf;
  auto findContainerOf = [&](const srp::core::SceneObject& part) -> std::string {
    for (const auto& o : scene.objects) {
      const auto* c = catalogue.find(o.className);
      if (!c || c->kind != srp::core::ObjectKind::Container) continue;
      const Eigen::Vector3d p = o.X_world_object.inverse() * part.X_world_object.translation();
      if (std::abs(p.x()) < 0.5 * c->dimensions_m.x() && std::abs(p.y()) < 0.5 * c->dimensions_m.y() &&
          p.z() > -0.01 && p.z() < c->dimensions_m.z())
        return o.id;
    }
    return "";
  };
  for (const auto& o : scene.objects) {
    const auto* c = catalogue.find(o.className);
    if (c && c->kind == srp::core::ObjectKind::Part) containerOf[o.id] = findContainerOf(o);
  }

  std::vector<std::string> moved;
  // Grounds a noun phrase {"name", "color"} to a scene object id.
  auto groundPhrase = [&](const nlohmann::json& phrase, const std::string& where, bool preferUnmoved) {
    return groundNounPhrase(phrase, where, preferUnmoved, scene, catalogue, moved);
  };
  auto isContainer = [&](const std::string& id) {
    const auto* o = scene.findObject(id);
    const auto* c = o ? catalogue.find(o->className) : nullptr;
    return c && c->kind == srp::core::ObjectKind::Container;
  };

  std::vector<PickPlaceStep> grounded;
  for (std::size_t i = 0; i < steps.size(); ++i) {
    const std::string where = context + " step " + std::to_string(i + 1);
    const auto& s = steps[i];
    PickPlaceStep step;
    step.objectId = groundPhrase(srp::core::requireField(s, "object", where), where + ": object", true);
    if (isContainer(step.objectId))
      throw InvalidInputError(where + ": object: '" + step.objectId + "' is a container; the demonstrator moves parts");
    step.sourceId = containerOf[step.objectId];
    if (s.contains("source") && s.at("source").is_array())
      for (const auto& r : s.at("source")) {
        const std::string id = groundPhrase(srp::core::requireField(r, "landmark", where + ": source"),
                                            where + ": source landmark", false);
        if (isContainer(id) && id != step.sourceId && !step.sourceId.empty())
          throw InvalidInputError(where + ": source: the " + step.objectId + " is in '" + step.sourceId +
                                  "', not in '" + id + "'");
      }
    const auto& target = srp::core::requireField(s, "target", where);
    if (!target.is_array() || target.empty())
      throw InvalidInputError(where + ": 'target' must be a non-empty array of {relation, landmark}");
    for (const auto& r : target) {
      const std::string relation = optionalString(r, "relation");
      const std::string id =
          groundPhrase(srp::core::requireField(r, "landmark", where + ": target"), where + ": target landmark", false);
      if (isContainer(id)) {
        step.targetId = id;
      } else if (srp::core::isNeighbourRelation(relation)) {
        step.referenceId = id;
      } else {
        throw InvalidInputError(where + ": target: relation '" + relation + "' with '" + id +
                                "' is not supported (use 'in <container>' or 'next to <object>')");
      }
    }
    if (step.targetId.empty() && !step.referenceId.empty()) step.targetId = containerOf[step.referenceId];
    if (step.targetId.empty())
      throw InvalidInputError(where + ": target: no container to place the " + step.objectId + " in");
    if (step.referenceId == step.objectId)
      throw InvalidInputError(where + ": target: the " + step.objectId + " cannot be placed next to itself");
    containerOf[step.objectId] = step.targetId;
    moved.push_back(step.objectId);
    grounded.push_back(step);
  }
  return grounded;
}

nlohmann::json defaultPlanJson() {
  auto phrase = [](const char* name, const char* colour) {
    return nlohmann::json{{"name", name}, {"color", colour ? nlohmann::json(colour) : nlohmann::json(nullptr)}};
  };
  auto step = [&](const char* object, const char* beside) {
    nlohmann::json target = nlohmann::json::array();
    if (beside) target.push_back({{"relation", "next to"}, {"landmark", phrase(beside, nullptr)}});
    target.push_back({{"relation", "in"}, {"landmark", phrase("box", "gray")}});
    return nlohmann::json{{"object", phrase(object, nullptr)},
                          {"source", nlohmann::json::array({{{"relation", "from"}, {"landmark", phrase("box", "blue")}}})},
                          {"target", target}};
  };
  return {{"instruction", "Begin by picking up the cuboid from the blue box and placing it in the gray box. Next, "
                          "carefully lift the star and position it next to the cuboid in the gray box. Then, move the "
                          "parallelogram, placing it beside the star in the gray box. Finally, pick up the octagon and "
                          "place it adjacent to the parallelogram in the gray box."},
          {"steps", nlohmann::json::array({step("cuboid", nullptr), step("star", "cuboid"),
                                           step("parallelogram", "star"), step("octagon", "parallelogram")})}};
}

}  // namespace srp::synth
