#pragma once
// Rendered demonstrations from the viewpoint families of srp::synth
// (Viewpoint.h: egocentric, side, top-down, front, oblique) with the hand carrying parts of
// several sizes, and the marker-free palm scored against their ground truth.
// Shared by MarkerFreeHandViewpoints_test and bench/marker_free_hand_bench.
//
// Which family is for what: the detector's settings are chosen on the
// egocentric and side families; top-down, front and oblique are checked, never tuned on
// (perception README, "The marker-free hand in other views").
#include <Eigen/Core>
#include <filesystem>
#include <string>
#include <vector>

#include "HandEvaluation.h"
#include "srp/core/Scene.h"
#include "srp/kb/KnowledgeBase.h"
#include "srp/synth/DemoGenerator.h"
#include "srp/synth/Viewpoint.h"

namespace srp::perception::testing {

/// One rendered carry demonstration.
struct ViewpointDemoSpec {
  synth::ViewpointFamily family = synth::ViewpointFamily::Egocentric;
  int variant = 0;           ///< Viewpoint.h's variants (azimuth, distance, side)
  double partScale = 1.0;    ///< the carried parts' size, times the catalogue's
  bool bareForearm = false;  ///< the sleeve in skin colour (a bare forearm) instead of the demonstrator's sleeve
  int width_px = 640;        ///< 640x480 or smaller (same field of view)
  int maxFrames = -1;        ///< -1: the whole demonstration
  std::uint32_t seed = 1;
  /// A head-mounted camera swaying about the viewpoint (synth::HeadSway, seeded by `seed`).
  bool headSway = false;
  /// Non-empty: a one-step plan carrying this part (cuboid, parallelogram) from the blue box into the
  /// gray box, recorded from its grasp to its release only (synth's carryOnly: the hand holds the
  /// part in every frame). Empty: carryPlan(partScale), the whole demonstration.
  std::string heldOnly;
  std::string name() const {
    char s[160];
    std::snprintf(s, sizeof s, "%s_v%d_x%.1f_%s_%dpx_s%u%s%s%s", synth::viewpointFamilyName(family).c_str(), variant,
                  partScale, bareForearm ? "bare" : "sleeve", width_px, seed, headSway ? "_sway" : "",
                  heldOnly.empty() ? "" : "_held-", heldOnly.c_str());
    return s;
  }
};

/// The plan: the cuboid, then the parallelogram, from the blue box into the gray box; parts
/// scaled by more than 1.5 leave no room for the second in the box: the cuboid alone.
inline nlohmann::json carryPlan(double partScale) {
  auto phrase = [](const char* name, const char* colour) {
    return nlohmann::json{{"name", name}, {"color", colour ? nlohmann::json(colour) : nlohmann::json(nullptr)}};
  };
  auto step = [&](const char* object) {
    return nlohmann::json{
        {"object", phrase(object, nullptr)},
        {"source", nlohmann::json::array({{{"relation", "from"}, {"landmark", phrase("box", "blue")}}})},
        {"target", nlohmann::json::array({{{"relation", "in"}, {"landmark", phrase("box", "gray")}}})}};
  };
  if (partScale > 1.5) return {{"steps", nlohmann::json::array({step("cuboid")})}};
  return {{"steps", nlohmann::json::array({step("cuboid"), step("parallelogram")})}};
}

/// One step: `part` from the blue box into the gray box.
inline nlohmann::json heldPlan(const std::string& part) {
  nlohmann::json plan = carryPlan(1.0);
  plan["steps"][0]["object"]["name"] = part;
  plan["steps"] = nlohmann::json::array({plan["steps"][0]});
  return plan;
}

/// Renders `spec` into `folder` (kept when already there) and returns the rawlog's path.
inline std::string renderViewpointDemo(const ViewpointDemoSpec& spec, const std::string& folder) {
  std::filesystem::create_directories(folder);
  const std::string rawlog = (std::filesystem::path(folder) / (spec.name() + ".rawlog")).string();
  if (std::filesystem::exists(rawlog) && std::filesystem::exists(synth::groundTruthPathFor(rawlog))) return rawlog;
  auto scene = core::Scene::load(std::string(SRP_SIM_DIR) + "/scenes/default.json");
  auto classes = kb::loadCatalogue(scene.cataloguePath).classes();
  for (auto& c : classes)
    if (c.kind == core::ObjectKind::Part && spec.partScale != 1.0) {
      c.dimensions_m *= spec.partScale;
      c.meshPath.clear();  // generated from the shape at the new size
    }
  const core::ObjectCatalogue catalogue(classes);
  // The camera looks at the middle of the two boxes.
  const synth::Viewpoint view =
      synth::makeViewpoint(spec.family, spec.variant, synth::workCentre_world(scene, catalogue));
  scene.X_world_camera = view.X_world_camera;
  synth::SynthDemoOptions o;
  o.demo.seed = spec.seed;
  o.demo.demonstratorSide_world = view.demonstratorSide_world;
  if (spec.bareForearm) o.hand.sleeveRgb = o.hand.skinRgb;
  o.width_px = spec.width_px;
  o.height_px = spec.width_px * 3 / 4;
  o.maxFrames = spec.maxFrames;
  o.rawlogEncoderThreads = 1;
  o.headSway.enabled = spec.headSway;
  o.carryOnly = !spec.heldOnly.empty();
  synth::generateSyntheticDemo(scene, catalogue, spec.heldOnly.empty() ? carryPlan(spec.partScale) : heldPlan(spec.heldOnly),
                               o, rawlog);
  return rawlog;
}

}  // namespace srp::perception::testing
