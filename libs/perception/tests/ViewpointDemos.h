#pragma once
// Rendered demonstrations from the viewpoint families of srp::synth
// (Viewpoint.h: egocentric, side, top-down, front, oblique, near-corner, table-level, facing) with the hand
// carrying parts of several sizes, and the marker-free palm scored against their ground truth.
// Shared by MarkerFreeHandViewpoints_test and bench/marker_free_hand_bench.
//
// Which family is for what: the detector's settings are chosen on the
// egocentric, side and facing families; top-down, front, oblique, near-corner and table-level are checked,
// never tuned on (perception README, "The marker-free hand in other views").
#include <Eigen/Core>
#include <filesystem>
#include <string>
#include <vector>

#include "HandEvaluation.h"
#include "srp/calib/RgbdImporter.h"
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
  /// A head-mounted RGB-D sensor of the Intel RealSense SR300's kind instead of one registered camera:
  /// 16:9 colour width_px wide (fx 0.74 width_px: 68 x 42 deg) and 4:3 depth a third as wide from its
  /// own camera (fx 0.72 of its width: 69 x 55 deg), 25 mm beside the colour camera and turned by
  /// 0.3 deg (the datasheet's fields of view; the extrinsic is not a measured unit's), written as an
  /// image folder and registered by `srp import` (calib::importRecording): colour 1920x1080 with
  /// 640x480 depth re-projected into it at width_px 1920, holes where the depth camera does not see
  /// (width_px / 3 must be a multiple of 4 for MRPT's renderer).
  bool sr300 = false;
  /// The scene's own light, or another lamp (WarmLight, ColdLight): its direction of travel in the world
  /// (before the seed's randomisation) and its colour (SynthDemoOptions::lightRgb).
  enum class Light { Scene, Warm, Cold } light = Light::Scene;
  /// The hand dressed with sensor wires and tape (synth::HandModel::SensorWires, its default sizes and
  /// colours: 2 mm dark wires along the back of the digits and the hand, 12 mm white tape patches on
  /// the fingertips and the back of the hand, an 18 mm band of tape at the wrist).
  bool sensorWires = false;
  std::string name() const {
    char s[192];
    std::snprintf(s, sizeof s, "%s_v%d_x%.1f_%s_%dpx_s%u%s%s%s%s%s%s", synth::viewpointFamilyName(family).c_str(),
                  variant, partScale, bareForearm ? "bare" : "sleeve", width_px, seed, headSway ? "_sway" : "",
                  heldOnly.empty() ? "" : "_held-", heldOnly.c_str(), sr300 ? "_sr300" : "",
                  light == Light::Warm   ? "_light"
                  : light == Light::Cold ? "_coldlight"
                                         : "",
                  sensorWires ? "_wires" : "");
    return s;
  }
};

/// ViewpointDemoSpec::Light::Warm: a warm lamp (R 1.0, G 0.9, B 0.78 of the scene's white, as a camera
/// balanced for daylight sees a ~4000 K lamp) shining from the robot's side of the table (-y) and from
/// +x, 40 deg above the table (the scene's light: from above, nearly straight down).
struct WarmLight {
  Eigen::Vector3d direction_world = Eigen::Vector3d(-0.5, 0.6, -0.65);
  Eigen::Vector3d rgb = Eigen::Vector3d(1.0, 0.9, 0.78);
};

/// ViewpointDemoSpec::Light::Cold: a cold lamp (R 0.85, G 0.93, B 1.0 of the scene's white, as a camera
/// balanced for a warm lamp sees daylight) shining from the demonstrator's side of the table (+y) and from
/// -x, 35 deg above the table: the other side than WarmLight.
struct ColdLight {
  Eigen::Vector3d direction_world = Eigen::Vector3d(0.5, -0.6, -0.55);
  Eigen::Vector3d rgb = Eigen::Vector3d(0.85, 0.93, 1.0);
};

/// Six demonstrations of `family`: variants 0-5 (azimuth -20/0/+20 deg, distance -10/0 %, sides), parts
/// 1x, 1.5x and 2x the catalogue's, sleeve in 0-2, bare forearm in 3-5, seeds `firstSeed`..+5 (11-16 by
/// default). The families added as fresh checks (near-corner, table-level) are lit by WarmLight, the
/// development family facing by ColdLight (ViewpointDemoSpec::light).
inline std::vector<ViewpointDemoSpec> familySpecs(synth::ViewpointFamily family, int width_px = 640,
                                                  std::uint32_t firstSeed = 11) {
  std::vector<ViewpointDemoSpec> out;
  constexpr double kScales[] = {1.0, 1.5, 2.0};
  for (int v = 0; v < 6; ++v) {
    ViewpointDemoSpec s;
    s.family = family;
    s.variant = v;
    s.partScale = kScales[v % 3];
    s.bareForearm = v >= 3;
    s.seed = firstSeed + static_cast<std::uint32_t>(v);
    s.width_px = width_px;
    if (family == synth::ViewpointFamily::NearCorner || family == synth::ViewpointFamily::TableLevel)
      s.light = ViewpointDemoSpec::Light::Warm;
    if (family == synth::ViewpointFamily::Facing) s.light = ViewpointDemoSpec::Light::Cold;
    out.push_back(s);
  }
  return out;
}

/// ViewpointDemoSpec::sr300's colour camera at `width_px` (16:9) and its depth camera.
inline core::CameraIntrinsics sr300Colour(int width_px) {
  const double w = width_px, h = std::round(w * 9.0 / 16.0);
  return {0.74 * w, 0.74 * w, w / 2 - 0.5, h / 2 - 0.5, width_px, static_cast<int>(h)};
}
inline synth::SynthDepthCamera sr300Depth(int colourWidth_px) {
  const double w = std::round(colourWidth_px / 3.0), h = std::round(w * 3.0 / 4.0);
  synth::SynthDepthCamera d;
  d.intrinsics = {0.72 * w, 0.72 * w, w / 2 - 0.5 + 0.004 * w, h / 2 - 0.5 - 0.003 * h, static_cast<int>(w),
                  static_cast<int>(h)};
  d.X_colour_depth.translation() = Eigen::Vector3d(0.025, 0.0003, 0.0005);
  d.X_colour_depth.linear() =
      (Eigen::AngleAxisd(0.004, Eigen::Vector3d::UnitY()) * Eigen::AngleAxisd(-0.003, Eigen::Vector3d::UnitX()))
          .toRotationMatrix();
  return d;
}

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
  o.hand.sensorWires.enabled = spec.sensorWires;
  if (spec.sr300) {
    scene.intrinsics = sr300Colour(spec.width_px);
    o.depthCamera = sr300Depth(spec.width_px);
  } else {
    o.width_px = spec.width_px;
    o.height_px = spec.width_px * 3 / 4;
  }
  if (spec.light == ViewpointDemoSpec::Light::Warm) {
    const WarmLight light;
    scene.lighting.direction_world = light.direction_world;
    o.lightRgb = light.rgb;
  } else if (spec.light == ViewpointDemoSpec::Light::Cold) {
    const ColdLight light;
    scene.lighting.direction_world = light.direction_world;
    o.lightRgb = light.rgb;
  }
  o.maxFrames = spec.maxFrames;
  o.rawlogEncoderThreads = 1;
  o.headSway.enabled = spec.headSway;
  o.carryOnly = !spec.heldOnly.empty();
  const nlohmann::json plan = spec.heldOnly.empty() ? carryPlan(spec.partScale) : heldPlan(spec.heldOnly);
  if (!spec.sr300) {
    synth::generateSyntheticDemo(scene, catalogue, plan, o, rawlog);
    return rawlog;
  }
  // An image folder as the sensor records it (its ground truth, name.gt.json, is the rawlog's), imported.
  const std::string images = (std::filesystem::path(folder) / (spec.name() + ".images")).string();
  synth::generateSyntheticDemo(scene, catalogue, plan, o, images);
  calib::importRecording(images, rawlog);
  std::filesystem::remove_all(images);
  return rawlog;
}

}  // namespace srp::perception::testing
