#include "srp/core/ObjectCatalogue.h"

#include <filesystem>
#include <set>

#include "srp/core/DataPaths.h"
#include "srp/core/Error.h"
#include "srp/core/Json.h"

namespace srp::core {
namespace {

Eigen::Vector3d vec3(const nlohmann::json& j, const std::string& context) {
  if (!j.is_array() || j.size() != 3)
    throw InvalidInputError(context + ": expected an array of 3 numbers");
  return {j[0].get<double>(), j[1].get<double>(), j[2].get<double>()};
}

}  // namespace

ObjectCatalogue::ObjectCatalogue(std::vector<ObjectClass> classes) : classes_(std::move(classes)) {
  std::set<std::string> names;
  std::set<int> ids;
  for (const auto& c : classes_) {
    if (!names.insert(c.name).second) throw InvalidInputError("catalogue: duplicate class name '" + c.name + "'");
    if (!ids.insert(c.classId).second)
      throw InvalidInputError("catalogue: duplicate class_id " + std::to_string(c.classId) + " ('" + c.name + "')");
  }
}

std::string ObjectCatalogue::defaultPath() { return DataPaths::file("datasets/kb/catalogue.json").string(); }

ObjectCatalogue ObjectCatalogue::load(const std::string& path) {
  const nlohmann::json j = readJsonFile(path);
  const int version = requireField(j, "schema_version", path).get<int>();
  if (version != 1)
    throw FileError(path, "catalogue schema_version " + std::to_string(version) +
                              " is not supported by this build (expected 1)");
  const std::filesystem::path folder = std::filesystem::path(path).parent_path();
  std::vector<ObjectClass> classes;
  try {
    for (const auto& e : requireField(j, "classes", path)) {
      ObjectClass c;
      const std::string ctx0 = path + ": class";
      c.name = requireField(e, "name", ctx0).get<std::string>();
      const std::string ctx = path + ": class '" + c.name + "'";
      c.classId = requireField(e, "class_id", ctx).get<int>();
      c.noun = e.value("noun", c.name);
      c.colourName = e.value("color_name", "");
      const std::string kind = requireField(e, "kind", ctx).get<std::string>();
      if (kind == "part") c.kind = ObjectKind::Part;
      else if (kind == "container") c.kind = ObjectKind::Container;
      else throw InvalidInputError(ctx + ": field 'kind' must be \"part\" or \"container\", not \"" + kind + "\"");
      if (e.contains("mesh")) c.meshPath = (folder / e.at("mesh").get<std::string>()).lexically_normal().string();
      // A class given by its CAD file alone: shape, size, colour and mass may
      // be left out (size and mass then come from the mesh, kb::loadCatalogue).
      const bool meshOnly = !c.meshPath.empty() && !e.contains("shape");
      c.shape = meshOnly ? std::string() : requireField(e, "shape", ctx).get<std::string>();
      c.hasColour = e.contains("rgb") || !meshOnly;
      if (c.hasColour) c.rgb = vec3(requireField(e, "rgb", ctx), ctx + " field 'rgb'");
      if (!meshOnly || e.contains("dimensions_m")) {
        c.dimensions_m = vec3(requireField(e, "dimensions_m", ctx), ctx + " field 'dimensions_m'");
        if ((c.dimensions_m.array() <= 0.0).any())
          throw InvalidInputError(ctx + ": field 'dimensions_m' must be positive");
      }
      c.wallThickness_m = e.value("wall_thickness_m", 0.0);
      c.mass_kg = meshOnly ? e.value("mass_kg", 0.0) : requireField(e, "mass_kg", ctx).get<double>();
      if (c.shape == "hull") {
        const auto& fp = requireField(e, "footprint_m", ctx);
        if (!fp.is_array() || fp.size() < 3)
          throw InvalidInputError(ctx + ": field 'footprint_m' must list at least 3 [x, y] points (metres)");
        for (const auto& q : fp) {
          if (!q.is_array() || q.size() != 2 || !q[0].is_number() || !q[1].is_number())
            throw InvalidInputError(ctx + ": field 'footprint_m' must hold [x, y] pairs of numbers (metres)");
          const Eigen::Vector2d v(q[0].get<double>(), q[1].get<double>());
          if (!v.allFinite()) throw InvalidInputError(ctx + ": field 'footprint_m' holds a non-finite number");
          c.footprint_object.push_back(v);
        }
      }
      c.observed = e.value("observed", false);
      if (e.contains("grasp_axis")) c.graspAxis_object = vec3(e.at("grasp_axis"), ctx + " field 'grasp_axis'").normalized();
      classes.push_back(std::move(c));
    }
  } catch (const nlohmann::json::exception& e) {
    throw FileError(path, std::string("bad catalogue entry: ") + e.what());
  }
  return ObjectCatalogue(std::move(classes));
}

const ObjectClass* ObjectCatalogue::find(const std::string& name) const {
  for (const auto& c : classes_)
    if (c.name == name) return &c;
  return nullptr;
}

const ObjectClass* ObjectCatalogue::findById(int classId) const {
  for (const auto& c : classes_)
    if (c.classId == classId) return &c;
  return nullptr;
}

const ObjectClass* ObjectCatalogue::ground(const std::string& noun, const std::string& colour) const {
  if (!colour.empty())
    if (const ObjectClass* c = find(colour + " " + noun)) return c;
  if (const ObjectClass* c = find(noun)) return c;
  const ObjectClass* match = nullptr;
  int count = 0;
  for (const auto& c : classes_) {
    if (c.noun != noun) continue;
    if (!colour.empty() && c.colourName == colour) return &c;
    match = &c;
    ++count;
  }
  return (count == 1 && colour.empty()) ? match : nullptr;
}

const ObjectClass& ObjectCatalogue::at(const std::string& name) const {
  if (const ObjectClass* c = find(name)) return *c;
  std::string known;
  for (const auto& c : classes_) known += (known.empty() ? "" : ", ") + c.name;
  throw InvalidInputError("unknown object class '" + name + "' (the catalogue knows: " + known + ")");
}

std::string toString(ObjectKind kind) { return kind == ObjectKind::Part ? "part" : "container"; }

}  // namespace srp::core
