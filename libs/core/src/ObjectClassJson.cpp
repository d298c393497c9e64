#include "srp/core/ObjectClassJson.h"

#include <cmath>

#include "srp/core/Error.h"
#include "srp/core/Json.h"
#include "srp/core/SafeText.h"

namespace srp::core {
namespace {

constexpr double kMaxDimension_m = 10.0;
constexpr double kFootprintSlack_m = 1e-3;  // a footprint point may sit this far outside the class' x/y extent

nlohmann::json vec(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

double number(const nlohmann::json& j, const std::string& context) {
  if (!j.is_number()) throw InvalidInputError(context + " must be a number");
  const double v = j.get<double>();
  if (!std::isfinite(v)) throw InvalidInputError(context + " is not a finite number");
  return v;
}

Eigen::Vector3d vec3(const nlohmann::json& j, const std::string& context) {
  if (!j.is_array() || j.size() != 3) throw InvalidInputError(context + " must be an array of 3 numbers");
  return {number(j[0], context), number(j[1], context), number(j[2], context)};
}

}  // namespace

nlohmann::json objectClassToJson(const ObjectClass& c) {
  nlohmann::json j{{"name", c.name},
                   {"class_id", c.classId},
                   {"noun", c.noun},
                   {"kind", toString(c.kind)},
                   {"shape", c.shape},
                   {"dimensions_m", vec(c.dimensions_m)},
                   {"mass_kg", c.mass_kg},
                   {"grasp_axis", vec(c.graspAxis_object)},
                   {"observed", c.observed}};
  if (!c.colourName.empty()) j["color_name"] = c.colourName;
  if (c.hasColour) j["rgb"] = vec(c.rgb);
  if (c.kind == ObjectKind::Container || c.wallThickness_m > 0.0) j["wall_thickness_m"] = c.wallThickness_m;
  if (!c.meshPath.empty()) j["mesh"] = c.meshPath;
  if (!c.footprint_object.empty()) {
    nlohmann::json fp = nlohmann::json::array();
    for (const auto& p : c.footprint_object) fp.push_back({p.x(), p.y()});
    j["footprint_m"] = fp;
  }
  return j;
}

ObjectClass objectClassFromJson(const nlohmann::json& j, const std::string& context) {
  if (!j.is_object()) throw InvalidInputError(context + ": an object class must be a JSON object");
  ObjectClass c;
  try {
    c.name = requireField(j, "name", context).get<std::string>();
    requireSafeName(c.name, context + ": field 'name'");
    const std::string ctx = context + " ('" + c.name + "')";
    const auto& id = requireField(j, "class_id", ctx);
    if (!id.is_number_integer()) throw InvalidInputError(ctx + ": field 'class_id' must be a whole number");
    c.classId = id.get<int>();
    c.noun = j.value("noun", c.name);
    c.colourName = j.value("color_name", "");
    requireSafeName(c.noun, ctx + ": field 'noun'");
    if (!c.colourName.empty()) requireSafeName(c.colourName, ctx + ": field 'color_name'");
    const std::string kind = requireField(j, "kind", ctx).get<std::string>();
    if (kind == "part") c.kind = ObjectKind::Part;
    else if (kind == "container") c.kind = ObjectKind::Container;
    else throw InvalidInputError(ctx + ": field 'kind' must be \"part\" or \"container\", not \"" + kind + "\"");
    c.shape = requireField(j, "shape", ctx).get<std::string>();
    if (c.shape.empty()) throw InvalidInputError(ctx + ": field 'shape' is empty (a class without a mesh needs a shape)");
    c.dimensions_m = vec3(requireField(j, "dimensions_m", ctx), ctx + ": field 'dimensions_m'");
    if ((c.dimensions_m.array() <= 0.0).any() || (c.dimensions_m.array() > kMaxDimension_m).any())
      throw InvalidInputError(ctx + ": field 'dimensions_m' must be three sizes in (0, 10] m");
    c.mass_kg = number(requireField(j, "mass_kg", ctx), ctx + ": field 'mass_kg'");
    if (!(c.mass_kg > 0.0)) throw InvalidInputError(ctx + ": field 'mass_kg' must be positive");
    c.hasColour = j.contains("rgb");
    if (c.hasColour) {
      c.rgb = vec3(j.at("rgb"), ctx + ": field 'rgb'");
      if ((c.rgb.array() < 0.0).any() || (c.rgb.array() > 1.0).any())
        throw InvalidInputError(ctx + ": field 'rgb' must be three numbers in [0, 1]");
    }
    c.wallThickness_m = j.contains("wall_thickness_m") ? number(j.at("wall_thickness_m"), ctx + ": field 'wall_thickness_m'") : 0.0;
    if (c.wallThickness_m < 0.0) throw InvalidInputError(ctx + ": field 'wall_thickness_m' must not be negative");
    if (c.kind == ObjectKind::Container &&
        !(c.wallThickness_m > 0.0 && 2 * c.wallThickness_m < c.dimensions_m.head<2>().minCoeff() &&
          c.wallThickness_m < c.dimensions_m.z()))
      throw InvalidInputError(ctx + ": field 'wall_thickness_m' must be positive and thinner than half the container");
    if (j.contains("grasp_axis")) {
      const Eigen::Vector3d a = vec3(j.at("grasp_axis"), ctx + ": field 'grasp_axis'");
      if (!(a.norm() > 1e-9)) throw InvalidInputError(ctx + ": field 'grasp_axis' must not be zero");
      c.graspAxis_object = a.normalized();
    }
    if (j.contains("mesh")) c.meshPath = j.at("mesh").get<std::string>();
    if (c.shape == "hull") {
      const auto& fp = requireField(j, "footprint_m", ctx);
      if (!fp.is_array() || fp.size() < 3)
        throw InvalidInputError(ctx + ": field 'footprint_m' must list at least 3 [x, y] points (metres)");
      for (const auto& q : fp) {
        if (!q.is_array() || q.size() != 2)
          throw InvalidInputError(ctx + ": field 'footprint_m' must hold [x, y] pairs of numbers (metres)");
        const Eigen::Vector2d p(number(q[0], ctx + ": field 'footprint_m'"), number(q[1], ctx + ": field 'footprint_m'"));
        if ((p.cwiseAbs() - c.dimensions_m.head<2>() / 2).maxCoeff() > kFootprintSlack_m)
          throw InvalidInputError(ctx + ": field 'footprint_m' has a point outside the class' x/y extent (dimensions_m)");
        c.footprint_object.push_back(p);
      }
    }
    c.observed = j.value("observed", false);
  } catch (const nlohmann::json::exception& e) {
    throw InvalidInputError(context + ": bad object class field (" + e.what() + ")");
  }
  return c;
}

}  // namespace srp::core
