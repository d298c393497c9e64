#include "srp/taskdb/TaskModel.h"

#include "srp/core/Error.h"
#include "srp/core/Json.h"
#include "srp/core/SafeText.h"
#include "srp/core/ObjectClassJson.h"

namespace srp::taskdb {

using nlohmann::json;

const ProductRow* TaskModel::findProduct(int objectId) const {
  for (const auto& p : products)
    if (p.objectId == objectId) return &p;
  return nullptr;
}

const GroundedProductRow* TaskModel::findGrounded(int classId) const {
  for (const auto& g : groundedProducts)
    if (g.classId == classId) return &g;
  return nullptr;
}

namespace {

template <typename T>
json opt(const std::optional<T>& v) {
  return v ? json(*v) : json(nullptr);
}
template <typename T>
std::optional<T> optFrom(const json& j, const char* key) {
  if (!j.contains(key) || j.at(key).is_null()) return std::nullopt;
  return j.at(key).get<T>();
}
json vec(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }
Eigen::Vector3d vecFrom(const json& j) { return {j.at(0).get<double>(), j.at(1).get<double>(), j.at(2).get<double>()}; }

}  // namespace

json toJson(const TaskModelInfo& i) {
  return {{"id", i.id},
          {"name", i.name},
          {"version", i.version},
          {"created_utc", i.createdUtc},
          {"instruction", i.instruction},
          {"frame", i.frame},
          {"frame_rate_hz", i.frameRate_hz},
          {"intrinsics", i.intrinsics ? json(*i.intrinsics) : json(nullptr)},
          {"X_base_camera", i.X_base_camera ? core::poseToJson(*i.X_base_camera) : json(nullptr)}};
}

json toJson(const PerceivedScene& s) {
  json objects = json::array();
  for (const auto& o : s.objects) {
    json jo{{"object_id", o.objectId}, {"class_id", o.classId}, {"class", o.className},
            {"X_table_object", core::poseToJson(o.X_table_object)}};
    if (o.colour) jo["color"] = *o.colour;
    if (o.rgb) jo["rgb"] = vec(*o.rgb);
    objects.push_back(jo);
  }
  json classes = json::array();
  for (const auto& c : s.observedClasses) classes.push_back(core::objectClassToJson(c));
  return {{"catalogue", s.catalogue},
          {"table_size_m", {s.tableSize_m.x(), s.tableSize_m.y()}},
          {"X_table_camera", core::poseToJson(s.X_table_camera)},
          {"objects", objects},
          {"observed_classes", classes}};
}

PerceivedScene perceivedSceneFromJson(const json& j, const std::string& ctx) {
  PerceivedScene s;
  try {
    s.catalogue = core::requireField(j, "catalogue", ctx).get<std::string>();
    const json& size = core::requireField(j, "table_size_m", ctx);
    if (!size.is_array() || size.size() != 2)
      throw core::InvalidInputError(ctx + ": field 'table_size_m' must be two numbers (metres)");
    s.tableSize_m = {size[0].get<double>(), size[1].get<double>()};
    if (!s.tableSize_m.allFinite() || (s.tableSize_m.array() <= 0.0).any())
      throw core::InvalidInputError(ctx + ": field 'table_size_m' must be two positive numbers (metres)");
    s.X_table_camera = core::poseFromJson(core::requireField(j, "X_table_camera", ctx), ctx + ": X_table_camera");
    for (const auto& o : j.value("objects", json::array())) {
      SceneObjectRow r;
      r.objectId = core::requireField(o, "object_id", ctx + ": objects").get<std::string>();
      const std::string octx = ctx + ": object '" + r.objectId + "'";
      r.classId = core::requireField(o, "class_id", octx).get<int>();
      r.className = core::requireField(o, "class", octx).get<std::string>();
      r.X_table_object = core::poseFromJson(core::requireField(o, "X_table_object", octx), octx + ": X_table_object");
      if (o.contains("color")) r.colour = o.at("color").get<std::string>();
      if (o.contains("rgb")) r.rgb = vecFrom(o.at("rgb"));
      if (!r.X_table_object.matrix().allFinite() || (r.rgb && !r.rgb->allFinite()))
        throw core::InvalidInputError(octx + ": a non-finite number");
      s.objects.push_back(r);
    }
    const json classes = j.value("observed_classes", json::array());
    for (std::size_t i = 0; i < classes.size(); ++i)
      s.observedClasses.push_back(core::objectClassFromJson(classes[i], ctx + ": observed_classes[" + std::to_string(i) + "]"));
    if (!s.X_table_camera.matrix().allFinite()) throw core::InvalidInputError(ctx + ": X_table_camera is not finite");
  } catch (const json::exception& e) {
    throw core::InvalidInputError(ctx + ": not a perceived scene (" + e.what() + ")");
  }
  return s;
}

json toJson(const TaskModel& m) {
  json j;
  j["schema_version"] = 1;
  j["task_model"] = toJson(m.info);
  for (const auto& p : m.products)
    j["products"].push_back({{"object_id", p.objectId}, {"object_name", p.objectName},
                             {"source_location_id", opt(p.sourceLocationId)},
                             {"target_location_id", opt(p.targetLocationId)}, {"color", opt(p.colour)},
                             {"token_id", opt(p.tokenId)}, {"sentence_id", opt(p.sentenceId)},
                             {"class_id", opt(p.classId)}});
  // Instance ids only when set: files of single-instance tasks keep their form.
  auto addInstance = [](json& row, const std::string& instanceId) {
    if (!instanceId.empty()) row["instance_id"] = instanceId;
  };
  for (std::size_t k = 0; k < m.products.size(); ++k) addInstance(j["products"][k], m.products[k].instanceId);
  for (const auto& s : m.sourceLocations)
    j["source_locations"].push_back({{"location_id", s.locationId}, {"trajector_object_id", s.trajectorObjectId},
                                     {"description", s.description}});
  for (const auto& t : m.targetLocations)
    j["target_locations"].push_back({{"location_id", t.locationId}, {"indicator_object_id", t.indicatorObjectId},
                                     {"description", t.description}});
  j["target_object_ids"] = m.targetObjectIds;
  for (const auto& g : m.groundedProducts)
    j["grounded_products"].push_back({{"class_id", g.classId}, {"object_name", g.objectName},
                                      {"source_location_id", opt(g.sourceLocationId)},
                                      {"target_location_id", opt(g.targetLocationId)}, {"color", opt(g.colour)}});
  for (std::size_t k = 0; k < m.groundedProducts.size(); ++k)
    addInstance(j["grounded_products"][k], m.groundedProducts[k].instanceId);
  for (const auto& p : m.productPoses)
    j["product_poses"].push_back({{"class_id", p.classId}, {"time_id", p.timeId}, {"p_m", vec(p.p_m)},
                                  {"q_wxyz", {p.q.w(), p.q.x(), p.q.y(), p.q.z()}}, {"reach", p.reach},
                                  {"grasp", p.grasp}, {"move", p.move}, {"release", p.release},
                                  {"detected", p.detected}, {"confidence", opt(p.confidence)}});
  for (std::size_t k = 0; k < m.productPoses.size(); ++k) addInstance(j["product_poses"][k], m.productPoses[k].instanceId);
  for (const auto& h : m.handPositions)
    j["hand_positions"].push_back({{"time_id", h.timeId}, {"p_m", vec(h.p_m)}, {"detected", h.detected}});
  for (const auto& s : m.skills)
    j["skills"].push_back({{"class_id", s.classId}, {"skill", core::toString(s.skill)},
                           {"start_time_id", s.startTimeId}, {"end_time_id", s.endTimeId},
                           {"parameters", s.parameters}});
  for (std::size_t k = 0; k < m.skills.size(); ++k) addInstance(j["skills"][k], m.skills[k].instanceId);
  for (const char* key : {"products", "source_locations", "target_locations", "grounded_products", "product_poses",
                          "hand_positions", "skills"})
    if (!j.contains(key)) j[key] = json::array();
  if (m.scene) j["perceived_scene"] = toJson(*m.scene);
  return j;
}

TaskModel taskModelFromJson(const json& j, const std::string& ctx) {
  TaskModel m;
  try {
    const int version = core::requireField(j, "schema_version", ctx).get<int>();
    if (version != 1)
      throw core::InvalidInputError(ctx + ": task model schema_version " + std::to_string(version) +
                                    " is not supported (expected 1)");
    const json& i = core::requireField(j, "task_model", ctx);
    m.info.id = i.value("id", 0);
    m.info.name = core::requireField(i, "name", ctx + ": task_model").get<std::string>();
    core::requireSafeName(m.info.name, ctx + ": task_model field 'name'");
    m.info.version = i.value("version", 1);
    m.info.createdUtc = i.value("created_utc", "");
    m.info.instruction = i.value("instruction", "");
    m.info.frame = i.value("frame", "camera");
    m.info.frameRate_hz = i.value("frame_rate_hz", 30.0);
    if (i.contains("intrinsics") && !i.at("intrinsics").is_null())
      m.info.intrinsics = i.at("intrinsics").get<core::CameraIntrinsics>();
    if (i.contains("X_base_camera") && !i.at("X_base_camera").is_null())
      m.info.X_base_camera = core::poseFromJson(i.at("X_base_camera"), ctx + ": task_model.X_base_camera");
    for (const auto& p : j.value("products", json::array()))
      m.products.push_back({p.at("object_id").get<int>(), p.at("object_name").get<std::string>(),
                            optFrom<int>(p, "source_location_id"), optFrom<int>(p, "target_location_id"),
                            optFrom<std::string>(p, "color"), optFrom<int>(p, "token_id"),
                            optFrom<int>(p, "sentence_id"), optFrom<int>(p, "class_id"),
                            p.value("instance_id", std::string())});
    for (const auto& s : j.value("source_locations", json::array()))
      m.sourceLocations.push_back({s.at("location_id").get<int>(), s.at("trajector_object_id").get<int>(),
                                   s.at("description").get<std::string>()});
    for (const auto& t : j.value("target_locations", json::array()))
      m.targetLocations.push_back({t.at("location_id").get<int>(), t.at("indicator_object_id").get<int>(),
                                   t.at("description").get<std::string>()});
    m.targetObjectIds = j.value("target_object_ids", std::vector<int>{});
    for (const auto& g : j.value("grounded_products", json::array()))
      m.groundedProducts.push_back({g.at("class_id").get<int>(), g.at("object_name").get<std::string>(),
                                    optFrom<int>(g, "source_location_id"), optFrom<int>(g, "target_location_id"),
                                    optFrom<std::string>(g, "color"), g.value("instance_id", std::string())});
    for (const auto& p : j.value("product_poses", json::array())) {
      ProductPoseRow r;
      r.classId = p.at("class_id").get<int>();
      r.timeId = p.at("time_id").get<int>();
      r.p_m = vecFrom(p.at("p_m"));
      const auto& q = p.at("q_wxyz");
      r.q = Eigen::Quaterniond(q.at(0).get<double>(), q.at(1).get<double>(), q.at(2).get<double>(), q.at(3).get<double>());
      r.reach = p.value("reach", false);
      r.grasp = p.value("grasp", false);
      r.move = p.value("move", false);
      r.release = p.value("release", false);
      r.detected = p.value("detected", true);
      r.confidence = optFrom<double>(p, "confidence");
      r.instanceId = p.value("instance_id", std::string());
      m.productPoses.push_back(r);
    }
    for (const auto& h : j.value("hand_positions", json::array()))
      m.handPositions.push_back({h.at("time_id").get<int>(), vecFrom(h.at("p_m")), h.value("detected", true)});
    for (const auto& s : j.value("skills", json::array()))
      m.skills.push_back({s.at("class_id").get<int>(), core::skillTypeFromString(s.at("skill").get<std::string>()),
                          s.at("start_time_id").get<int>(), s.at("end_time_id").get<int>(),
                          s.value("parameters", json::object()), s.value("instance_id", std::string())});
    if (j.contains("perceived_scene")) m.scene = perceivedSceneFromJson(j.at("perceived_scene"), ctx + ": perceived_scene");
  } catch (const json::exception& e) {
    throw core::InvalidInputError(ctx + ": not a task model (" + e.what() + ")");
  }
  return m;
}

}  // namespace srp::taskdb
