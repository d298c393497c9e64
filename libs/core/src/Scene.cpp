#include "srp/core/Scene.h"

#include <filesystem>
#include <map>
#include <set>

#include "srp/core/DataPaths.h"
#include "srp/core/DefaultScene.h"
#include "srp/core/Error.h"
#include "srp/core/Json.h"
#include "srp/core/SafeText.h"
#include "srp/core/ObjectClassJson.h"

namespace srp::core {
namespace {

Eigen::Vector3d vec3(const nlohmann::json& j, const std::string& context) {
  if (!j.is_array() || j.size() != 3) throw InvalidInputError(context + ": expected 3 numbers");
  return {j[0].get<double>(), j[1].get<double>(), j[2].get<double>()};
}

}  // namespace

std::string instanceColour(const SceneObject& object, const ObjectClass& cls) {
  return object.colour.empty() ? cls.colourName : object.colour;
}

Eigen::Vector3d instanceRgb(const SceneObject& object, const ObjectClass& cls) {
  if (object.rgb) return *object.rgb;
  if (!object.colour.empty())
    if (const auto rgb = rgbOfColourName(object.colour)) return *rgb;
  return cls.rgb;
}

namespace {
const std::map<std::string, Eigen::Vector3d>& basicColours() {
  // Saturated enough to stay apart under the renderer's lighting and the
  // perception's colour segmentation; red/blue/gray as the catalogue's classes.
  static const std::map<std::string, Eigen::Vector3d> kColours{
      {"red", {0.85, 0.18, 0.14}},   {"green", {0.18, 0.68, 0.3}},  {"blue", {0.12, 0.28, 0.78}},
      {"yellow", {0.95, 0.85, 0.1}}, {"orange", {0.95, 0.52, 0.08}}, {"purple", {0.5, 0.2, 0.65}},
      {"pink", {0.95, 0.5, 0.7}},    {"brown", {0.45, 0.28, 0.12}},  {"black", {0.05, 0.05, 0.05}},
      {"white", {0.95, 0.95, 0.95}}, {"gray", {0.55, 0.55, 0.57}},   {"grey", {0.55, 0.55, 0.57}},
      {"cyan", {0.1, 0.75, 0.8}}};
  return kColours;
}
}  // namespace

std::optional<Eigen::Vector3d> rgbOfColourName(const std::string& colour) {
  const auto it = basicColours().find(colour);
  if (it == basicColours().end()) return std::nullopt;
  return it->second;
}

std::string nearestColourName(const Eigen::Vector3d& rgb, double maxDistance) {
  std::string best;
  double bestDistance = maxDistance;
  for (const auto& [name, c] : basicColours())
    if (name != "grey" && (c - rgb).norm() <= bestDistance) {
      best = name;
      bestDistance = (c - rgb).norm();
    }
  return best;
}

const SceneObject* Scene::findObject(const std::string& id) const {
  for (const auto& o : objects)
    if (o.id == id) return &o;
  return nullptr;
}

std::string defaultScenePath() { return DataPaths::file("sim/scenes/default.json").string(); }

Scene Scene::load(const std::string& path) {
  const nlohmann::json j = readJsonFile(path);
  return fromJson(j, path, std::filesystem::path(path).parent_path().string());
}

Scene Scene::fromJson(const nlohmann::json& j, const std::string& ctx, const std::string& baseFolder) {
  Scene s;
  try {
    const int version = requireField(j, "schema_version", ctx).get<int>();
    if (version != 1)
      throw InvalidInputError(ctx + ": scene schema_version " + std::to_string(version) +
                              " is not supported by this build (expected 1)");
    s.name = j.value("name", s.name);
    requireSafeName(s.name, ctx + ": field 'name'");
    s.seed = j.value("seed", 0);
    // Absolute, so a scene written elsewhere (toJson) still finds its catalogue.
    s.cataloguePath = j.contains("catalogue")
                          ? std::filesystem::absolute(std::filesystem::path(baseFolder) /
                                                      j.at("catalogue").get<std::string>())
                                .lexically_normal()
                                .string()
                          : ObjectCatalogue::defaultPath();
    const auto& table = requireField(j, "table", ctx);
    const auto& size = requireField(table, "size_m", ctx + ": table");
    if (!size.is_array() || size.size() != 2 || !(size[0].get<double>() > 0) || !(size[1].get<double>() > 0))
      throw InvalidInputError(ctx + ": field 'table.size_m' must be two positive numbers");
    s.tableSize_m = {size[0].get<double>(), size[1].get<double>()};
    if (table.contains("rgb")) s.tableRgb = vec3(table.at("rgb"), ctx + ": field 'table.rgb'");

    const auto& camera = requireField(j, "camera", ctx);
    try {
      s.intrinsics = requireField(camera, "intrinsics", ctx + ": camera").get<CameraIntrinsics>();
    } catch (const InvalidInputError& e) {
      throw InvalidInputError(ctx + ": " + e.what());  // name the file, not only the field
    }
    s.intrinsics.validate(ctx + ": camera.intrinsics");
    s.fps = camera.value("fps", 30.0);
    if (!(s.fps > 0)) throw InvalidInputError(ctx + ": field 'camera.fps' must be positive");
    s.X_world_camera = poseFromJson(requireField(camera, "X_world_camera", ctx + ": camera"),
                                    ctx + ": camera.X_world_camera");
    const auto& robot = requireField(j, "robot", ctx);
    s.X_world_base = poseFromJson(requireField(robot, "X_world_base", ctx + ": robot"), ctx + ": robot.X_world_base");
    if (j.contains("lighting")) {
      const auto& l = j.at("lighting");
      s.lighting.ambient = l.value("ambient", s.lighting.ambient);
      s.lighting.diffuse = l.value("diffuse", s.lighting.diffuse);
      if (l.contains("direction")) s.lighting.direction_world = vec3(l.at("direction"), ctx + ": field 'lighting.direction'");
    }
    const auto& objects = requireField(j, "objects", ctx);
    for (std::size_t i = 0; i < objects.size(); ++i) {
      const std::string octx = ctx + ": objects[" + std::to_string(i) + "]";
      SceneObject o;
      o.id = requireField(objects[i], "id", octx).get<std::string>();
      requireSafeName(o.id, octx + " field 'id'");
      o.className = requireField(objects[i], "class", octx + " ('" + o.id + "')").get<std::string>();
      requireSafeName(o.className, octx + " ('" + o.id + "') field 'class'");
      o.X_world_object = poseFromJson(requireField(objects[i], "X_world_object", octx + " ('" + o.id + "')"),
                                      octx + " ('" + o.id + "').X_world_object");
      o.colour = objects[i].value("color", std::string());
      if (!o.colour.empty()) requireSafeName(o.colour, octx + " ('" + o.id + "') field 'color'");
      if (objects[i].contains("rgb")) {
        o.rgb = vec3(objects[i].at("rgb"), octx + " ('" + o.id + "'): field 'rgb'");
        if ((o.rgb->array() < 0.0).any() || (o.rgb->array() > 1.0).any())
          throw InvalidInputError(octx + " ('" + o.id + "'): field 'rgb' must be three numbers in [0, 1]");
      }
      s.objects.push_back(std::move(o));
    }
    if (j.contains("observed_classes")) {
      const auto& classes = j.at("observed_classes");
      if (!classes.is_array()) throw InvalidInputError(ctx + ": field 'observed_classes' must be an array");
      for (std::size_t i = 0; i < classes.size(); ++i)
        s.observedClasses.push_back(
            objectClassFromJson(classes[i], ctx + ": observed_classes[" + std::to_string(i) + "]"));
    }
  } catch (const nlohmann::json::exception& e) {
    throw InvalidInputError(ctx + ": bad scene field (" + e.what() + ")");
  }
  return s;
}

nlohmann::json Scene::toJson() const {
  nlohmann::json objs = nlohmann::json::array();
  for (const auto& o : objects) {
    nlohmann::json jo{{"id", o.id}, {"class", o.className}, {"X_world_object", poseToJson(o.X_world_object)}};
    if (!o.colour.empty()) jo["color"] = o.colour;
    if (o.rgb) jo["rgb"] = {o.rgb->x(), o.rgb->y(), o.rgb->z()};
    objs.push_back(std::move(jo));
  }
  const auto& d = lighting.direction_world;
  nlohmann::json j{{"schema_version", 1},
          {"name", name},
          {"seed", seed},
          {"catalogue", cataloguePath},
          {"table", {{"size_m", {tableSize_m.x(), tableSize_m.y()}}, {"rgb", {tableRgb.x(), tableRgb.y(), tableRgb.z()}}}},
          {"camera", {{"intrinsics", intrinsics}, {"fps", fps}, {"X_world_camera", poseToJson(X_world_camera)}}},
          {"robot", {{"X_world_base", poseToJson(X_world_base)}}},
          {"lighting", {{"ambient", lighting.ambient}, {"diffuse", lighting.diffuse}, {"direction", {d.x(), d.y(), d.z()}}}},
          {"objects", objs}};
  if (!observedClasses.empty()) {
    nlohmann::json classes = nlohmann::json::array();
    for (const auto& c : observedClasses) classes.push_back(objectClassToJson(c));
    j["observed_classes"] = classes;
  }
  return j;
}

ObjectCatalogue Scene::withObservedClasses(const ObjectCatalogue& catalogue) const {
  if (observedClasses.empty()) return catalogue;
  std::vector<ObjectClass> classes = catalogue.classes();
  for (const auto& c : observedClasses) {
    const ObjectClass* byName = catalogue.find(c.name);
    const ObjectClass* byId = catalogue.findById(c.classId);
    if (byName || byId)
      throw InvalidInputError("scene '" + name + "': observed class '" + c.name + "' (class_id " +
                              std::to_string(c.classId) + ") clashes with the catalogue's class '" +
                              (byName ? byName->name : byId->name) + "' (field 'observed_classes')");
    classes.push_back(c);
  }
  return ObjectCatalogue(std::move(classes));
}

void Scene::validate(const ObjectCatalogue& base) const {
  const ObjectCatalogue catalogue = withObservedClasses(base);
  std::set<std::string> ids;
  for (const auto& o : objects) {
    if (!ids.insert(o.id).second) throw InvalidInputError("scene '" + name + "': duplicate object id '" + o.id + "'");
    const ObjectClass* cls = catalogue.find(o.className);
    if (!cls) {
      std::string known;
      for (const auto& c : catalogue.classes()) known += (known.empty() ? "" : ", ") + c.name;
      throw InvalidInputError("scene '" + name + "': object '" + o.id + "' has unknown class '" + o.className +
                              "' (field 'class'; the catalogue knows: " + known + ")");
    }
    if (!o.colour.empty() && !o.rgb && !rgbOfColourName(o.colour))
      throw InvalidInputError("scene '" + name + "': object '" + o.id + "' has colour '" + o.colour +
                              "' (field 'color') that has no known rgb; give \"rgb\": [r, g, b] too");
    // Every corner of the footprint must lie on the table top.
    const Eigen::Vector3d half(cls->dimensions_m.x() / 2, cls->dimensions_m.y() / 2, 0.0);
    for (int sx : {-1, 1})
      for (int sy : {-1, 1}) {
        const Eigen::Vector3d corner = o.X_world_object * Eigen::Vector3d(sx * half.x(), sy * half.y(), 0.0);
        if (std::abs(corner.x()) > tableSize_m.x() / 2 + 1e-9 || std::abs(corner.y()) > tableSize_m.y() / 2 + 1e-9)
          throw InvalidInputError("scene '" + name + "': object '" + o.id +
                                  "' lies outside the table (field 'X_world_object'; the table spans +-" +
                                  std::to_string(tableSize_m.x() / 2) + " x +-" + std::to_string(tableSize_m.y() / 2) + " m)");
      }
    if (o.X_world_object.translation().z() < -1e-9)
      throw InvalidInputError("scene '" + name + "': object '" + o.id + "' is below the table top (field 'X_world_object')");
  }
}

}  // namespace srp::core
