#include "srp/synth/DemoGroundTruth.h"

#include <algorithm>
#include <nlohmann/json.hpp>

#include "srp/core/Error.h"
#include "srp/core/Json.h"

namespace srp::synth {
namespace {

using nlohmann::json;
using srp::core::requireField;

json vec(const Eigen::VectorXd& v) {
  json a = json::array();
  for (Eigen::Index i = 0; i < v.size(); ++i) a.push_back(v[i]);
  return a;
}

Eigen::Vector3d vec3(const json& j, const std::string& context) {
  if (!j.is_array() || j.size() != 3) throw srp::core::InvalidInputError(context + ": expected [x, y, z]");
  return {j[0].get<double>(), j[1].get<double>(), j[2].get<double>()};
}

std::string str(const json& j, const std::string& key) {
  return j.contains(key) && j.at(key).is_string() ? j.at(key).get<std::string>() : "";
}

}  // namespace

srp::core::Pose3 DemoGroundTruth::X_world_camera_at(int index) const {
  if (index < 0 || index >= static_cast<int>(frames.size()))
    throw srp::core::InvalidInputError("ground truth: frame " + std::to_string(index) + " out of range (0.." +
                                       std::to_string(frames.size()) + ")");
  const auto& own = frames[static_cast<std::size_t>(index)].X_world_camera;
  return own ? *own : X_world_camera;
}

bool DemoGroundTruth::cameraMoves() const {
  return std::any_of(frames.begin(), frames.end(), [](const GroundTruthFrame& f) { return f.X_world_camera.has_value(); });
}

srp::core::Pose3 DemoGroundTruth::X_camera_object(int index, const std::string& id) const {
  const srp::core::Pose3 X_world_camera_k = X_world_camera_at(index);
  const auto it = frames[index].X_world_objects.find(id);
  if (it == frames[index].X_world_objects.end())
    throw srp::core::InvalidInputError("ground truth: no object '" + id + "'");
  return X_world_camera_k.inverse() * it->second;
}

const GroundTruthEvent* DemoGroundTruth::eventFor(const std::string& objectId) const {
  for (const auto& e : events)
    if (e.objectId == objectId) return &e;
  return nullptr;
}

json DemoGroundTruth::toJson() const {
  using srp::core::poseToJson;
  json j;
  j["schema_version"] = kSchemaVersion;
  j["generator"] = "srp synth-demo";
  j["scene_name"] = sceneName;
  j["rawlog"] = rawlogFile;
  j["seed"] = seed;
  j["fps"] = fps;
  j["speed_factor"] = speedFactor;
  j["instruction"] = instruction;
  j["sensor_realism"] = sensorRealism;
  j["frame_count"] = frames.size();
  j["camera"] = {{"intrinsics", intrinsics},
                 {"X_world_camera", poseToJson(X_world_camera)},
                 {"X_world_base", poseToJson(X_world_base)},
                 {"X_base_camera", poseToJson(X_base_camera())}};
  j["hand"] = {{"tag_family", tagFamily}, {"tag_id", tagId}, {"tag_size_m", tagSize_m},
               {"X_hand_tag", poseToJson(X_hand_tag)},
               {"frame", "palm centre; x to the fingers, z out of the back of the hand"}};
  j["objects"] = json::array();
  for (const auto& o : objects)
    j["objects"].push_back({{"id", o.id}, {"class", o.className}, {"class_id", o.classId},
                            {"X_world_object_initial", poseToJson(o.X_world_object_initial)},
                            {"X_world_object_final", poseToJson(o.X_world_object_final)}});
  j["events"] = json::array();
  for (const auto& e : events)
    j["events"].push_back({{"object", e.objectId}, {"step", e.step}, {"grasp_frame", e.graspFrame},
                           {"release_frame", e.releaseFrame}, {"source", e.sourceId}, {"target", e.targetId},
                           {"reference", e.referenceId}, {"X_hand_object", poseToJson(e.X_hand_object)}});
  j["frames"] = json::array();
  for (const auto& f : frames) {
    json jf = {{"index", f.index}, {"t_s", f.t_s}, {"phase", f.phase}, {"step", f.step}, {"grip", f.grip},
               {"hand_in_view", f.handInView}, {"hand_pixels", f.handPixels}, {"tag_in_view", f.tagInView},
               {"tag_visible_fraction", f.tagVisibleFraction},
               {"X_world_hand", poseToJson(f.X_world_hand)}, {"p_camera_palm_m", vec(f.p_camera_palm_m)},
               {"X_camera_tag", poseToJson(f.X_camera_tag)},
               {"carried", f.carriedObject.empty() ? json(nullptr) : json(f.carriedObject)}};
    jf["tag_corners_px"] = json::array();
    for (const auto& c : f.tagCorners_px) jf["tag_corners_px"].push_back({c.x(), c.y()});
    jf["objects"] = json::object();
    for (const auto& [id, X] : f.X_world_objects) jf["objects"][id] = poseToJson(X);
    if (f.handOccludedObjects) jf["hand_occluded_objects"] = *f.handOccludedObjects;
    if (f.X_world_camera) jf["X_world_camera"] = poseToJson(*f.X_world_camera);
    jf["valid_depth_fraction"] = {
        {"hand", f.handValidDepthFraction ? json(*f.handValidDepthFraction) : json(nullptr)},
        {"objects", f.objectsValidDepthFraction ? json(*f.objectsValidDepthFraction) : json(nullptr)}};
    j["frames"].push_back(std::move(jf));
  }
  return j;
}

DemoGroundTruth DemoGroundTruth::fromJson(const json& j, const std::string& ctx) {
  using srp::core::poseFromJson;
  DemoGroundTruth gt;
  const int version = requireField(j, "schema_version", ctx).get<int>();
  if (version > kSchemaVersion)
    throw srp::core::InvalidInputError(ctx + ": schema_version " + std::to_string(version) +
                                       " is newer than this build reads (" + std::to_string(kSchemaVersion) + ")");
  gt.sceneName = str(j, "scene_name");
  gt.rawlogFile = str(j, "rawlog");
  gt.instruction = str(j, "instruction");
  gt.seed = j.value("seed", 0u);
  gt.fps = requireField(j, "fps", ctx).get<double>();
  gt.speedFactor = j.value("speed_factor", 1.0);
  gt.sensorRealism = j.value("sensor_realism", true);
  const auto& cam = requireField(j, "camera", ctx);
  gt.intrinsics = requireField(cam, "intrinsics", ctx + ": camera").get<srp::core::CameraIntrinsics>();
  gt.X_world_camera = poseFromJson(requireField(cam, "X_world_camera", ctx + ": camera"), ctx + ": camera.X_world_camera");
  gt.X_world_base = poseFromJson(requireField(cam, "X_world_base", ctx + ": camera"), ctx + ": camera.X_world_base");
  const auto& hand = requireField(j, "hand", ctx);
  gt.tagFamily = str(hand, "tag_family");
  gt.tagId = requireField(hand, "tag_id", ctx + ": hand").get<int>();
  gt.tagSize_m = requireField(hand, "tag_size_m", ctx + ": hand").get<double>();
  gt.X_hand_tag = poseFromJson(requireField(hand, "X_hand_tag", ctx + ": hand"), ctx + ": hand.X_hand_tag");
  for (const auto& o : requireField(j, "objects", ctx)) {
    GroundTruthObject g;
    g.id = requireField(o, "id", ctx + ": objects[]").get<std::string>();
    const std::string oc = ctx + ": object '" + g.id + "'";
    g.className = requireField(o, "class", oc).get<std::string>();
    g.classId = o.value("class_id", -1);
    g.X_world_object_initial = poseFromJson(requireField(o, "X_world_object_initial", oc), oc + ".X_world_object_initial");
    g.X_world_object_final = poseFromJson(requireField(o, "X_world_object_final", oc), oc + ".X_world_object_final");
    gt.objects.push_back(g);
  }
  for (const auto& e : requireField(j, "events", ctx)) {
    GroundTruthEvent g;
    g.objectId = requireField(e, "object", ctx + ": events[]").get<std::string>();
    const std::string ec = ctx + ": event of '" + g.objectId + "'";
    g.step = requireField(e, "step", ec).get<int>();
    g.graspFrame = requireField(e, "grasp_frame", ec).get<int>();
    g.releaseFrame = requireField(e, "release_frame", ec).get<int>();
    g.sourceId = str(e, "source");
    g.targetId = str(e, "target");
    g.referenceId = str(e, "reference");
    g.X_hand_object = poseFromJson(requireField(e, "X_hand_object", ec), ec + ".X_hand_object");
    gt.events.push_back(g);
  }
  const auto& frames = requireField(j, "frames", ctx);
  gt.frames.reserve(frames.size());
  for (const auto& jf : frames) {
    GroundTruthFrame f;
    f.index = requireField(jf, "index", ctx + ": frames[]").get<int>();
    const std::string fc = ctx + ": frame " + std::to_string(f.index);
    f.t_s = requireField(jf, "t_s", fc).get<double>();
    f.phase = str(jf, "phase");
    f.step = jf.value("step", -1);
    f.grip = jf.value("grip", 0.0);
    f.handInView = requireField(jf, "hand_in_view", fc).get<bool>();
    f.handPixels = jf.value("hand_pixels", 0);
    f.tagInView = jf.value("tag_in_view", false);
    f.tagVisibleFraction = jf.value("tag_visible_fraction", 0.0);
    f.X_world_hand = poseFromJson(requireField(jf, "X_world_hand", fc), fc + ".X_world_hand");
    f.p_camera_palm_m = vec3(requireField(jf, "p_camera_palm_m", fc), fc + ".p_camera_palm_m");
    f.X_camera_tag = poseFromJson(requireField(jf, "X_camera_tag", fc), fc + ".X_camera_tag");
    const auto& corners = requireField(jf, "tag_corners_px", fc);
    for (std::size_t c = 0; c < 4 && c < corners.size(); ++c)
      f.tagCorners_px[c] = Eigen::Vector2d(corners[c][0].get<double>(), corners[c][1].get<double>());
    if (jf.contains("carried") && jf.at("carried").is_string()) f.carriedObject = jf.at("carried").get<std::string>();
    for (const auto& [id, X] : requireField(jf, "objects", fc).items())
      f.X_world_objects[id] = poseFromJson(X, fc + ".objects." + id);
    if (jf.contains("hand_occluded_objects"))
      f.handOccludedObjects = jf.at("hand_occluded_objects").get<std::set<std::string>>();
    if (jf.contains("X_world_camera")) f.X_world_camera = poseFromJson(jf.at("X_world_camera"), fc + ".X_world_camera");
    if (jf.contains("valid_depth_fraction")) {
      const auto& v = jf.at("valid_depth_fraction");
      if (v.contains("hand") && v.at("hand").is_number()) f.handValidDepthFraction = v.at("hand").get<double>();
      if (v.contains("objects") && v.at("objects").is_number())
        f.objectsValidDepthFraction = v.at("objects").get<double>();
    }
    gt.frames.push_back(std::move(f));
  }
  return gt;
}

void DemoGroundTruth::save(const std::string& path) const { srp::core::writeJsonFile(path, toJson()); }

DemoGroundTruth DemoGroundTruth::load(const std::string& path) {
  const json j = srp::core::readJsonFile(path);
  try {
    return fromJson(j, path);
  } catch (const json::exception& e) {
    throw srp::core::FileError(path, std::string("malformed ground truth: ") + e.what());
  }
}

}  // namespace srp::synth
