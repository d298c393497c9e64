#pragma once
/// \file ObjectClassJson.h
/// \brief One object class as a self-contained JSON object: how a class seen in
/// a demonstration without a CAD file (ObjectClass::observed, shape "hull" or
/// "open_box") travels with the task model that observed it and with scene
/// files, outside any catalogue file.
///
/// The keys are those of a catalogue entry (ObjectCatalogue.h): "name",
/// "class_id", "noun", "color_name", "kind", "shape", "rgb", "dimensions_m",
/// "wall_thickness_m", "mass_kg", "grasp_axis", "footprint_m", "observed"; "mesh"
/// only for a class with a mesh file (absolute path). Metres, kilograms, linear RGB.
///
/// \code
///   srp::core::ObjectClass toy;  // built from a demonstration's points
///   toy.name = "toy"; toy.shape = "hull"; toy.observed = true; ...
///   const nlohmann::json j = srp::core::objectClassToJson(toy);
///   const srp::core::ObjectClass back = srp::core::objectClassFromJson(j, "scene.json: observed_classes[0]");
/// \endcode

#include <nlohmann/json.hpp>
#include <string>

#include "srp/core/ObjectCatalogue.h"

namespace srp::core {

/// The class as JSON (every field, doubles exactly).
nlohmann::json objectClassToJson(const ObjectClass& objectClass);

/// Reads a class written by objectClassToJson. Every number is checked: the
/// dimensions finite and in (0, 10] m, the mass finite and positive, the rgb in
/// [0, 1], a container's wall thinner than half its width, a "hull" footprint of
/// at least three finite points inside the class' x/y extent. Throws
/// InvalidInputError naming `context` and the field.
ObjectClass objectClassFromJson(const nlohmann::json& j, const std::string& context);

}  // namespace srp::core
