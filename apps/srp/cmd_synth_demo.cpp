// `srp synth-demo`: scene + instruction plan -> synthetic RGB-D demo rawlog + ground truth.
#include <algorithm>
#include <filesystem>
#include <iostream>
#include <optional>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "CommandRegistry.h"
#include "CommonOptions.h"
#include "ProgressLine.h"
#include "srp/core/DefaultScene.h"
#include "srp/core/Error.h"
#include "srp/core/Json.h"
#include "srp/core/ObjectCatalogue.h"
#include "srp/core/OutputFile.h"
#include "srp/core/Scene.h"
#include "srp/kb/KnowledgeBase.h"
#include "srp/synth/DemoGenerator.h"
#include "srp/synth/PickPlacePlan.h"
#include "srp/synth/Viewpoint.h"

namespace {

struct SynthDemoArgs {
  std::string scenePath;  ///< empty: the shipped default scene
  std::string planPath;
  std::string outPath = "demo.rawlog";
  std::string contactSheet, depthCamera;
  std::string viewpoint;  ///< empty: the scene's camera
  std::vector<double> lightRgb;        ///< empty: white
  std::vector<double> lightDirection;  ///< empty: the scene's
  long long seed = -1;
  int width = 0, height = 0, maxFrames = -1, colourNoiseBlock = -1, depthNoiseBlock = -1;
  double speed = 1.0;
  bool clean = false, noRandomise = false, motionBlur = false, json = false, overwrite = false;
  bool headSway = false, carryOnly = false, sensorWires = false;
};

namespace fs = std::filesystem;

/// The demo is generated into a folder beside the output and moved into place
/// when it is complete: a failed or killed run leaves no partial rawlog that
/// reads as a shorter demo, and an earlier demo stays as it was.
class StagedDemo {
  static fs::path withoutTrailingSlash(const fs::path& p) { return p.has_filename() ? p : p.parent_path(); }

 public:
  StagedDemo(const std::string& outPath, bool folderOutput)
      : target_(withoutTrailingSlash(fs::path(outPath).lexically_normal())),
        stage_(target_.parent_path() / ("." + target_.filename().string() + ".srp-stage")),
        staged_(stage_.temporaryPath() / target_.filename()) {
    if (folderOutput) fs::create_directory(staged_);
  }
  /// Where the generator writes the rawlog (or the two-camera folder).
  std::string stagedPath() const { return staged_.string(); }
  /// Moves the rawlog (or folder) and its ground truth into place, both or neither.
  void commit(const std::string& stagedGroundTruth) {
    const fs::path gt = target_.parent_path() / fs::path(stagedGroundTruth).filename();
    const fs::path old = fs::path(stage_.temporaryPath()) / ".previous";
    std::error_code ec;
    if (fs::exists(target_)) fs::rename(target_, old, ec);  // kept until the new demo is in place
    if (ec) throw srp::core::FileError(target_.string(), "cannot move the previous output aside (" + ec.message() + ")");
    fs::rename(staged_, target_, ec);
    if (!ec) fs::rename(stagedGroundTruth, gt, ec);
    if (ec) {
      std::error_code ignored;
      fs::remove_all(target_, ignored);
      if (fs::exists(old)) fs::rename(old, target_, ignored);
      throw srp::core::FileError(target_.string(), "cannot move the new demo into place (" + ec.message() + ")");
    }
  }
  std::string finalPath(const std::string& stagedFile) const {
    return (target_.parent_path() / fs::path(stagedFile).filename()).string();
  }

 private:
  fs::path target_;
  srp::core::AtomicOutputFolder stage_;  // removed with whatever is left in it
  fs::path staged_;
};

/// --light-rgb and --light-direction over the scene's white light from its own direction.
void applyLight(const SynthDemoArgs& a, srp::core::Scene& scene, srp::synth::SynthDemoOptions& options) {
  if (!a.lightRgb.empty()) options.lightRgb = Eigen::Vector3d(a.lightRgb[0], a.lightRgb[1], a.lightRgb[2]);
  if (a.lightDirection.empty()) return;
  const Eigen::Vector3d d(a.lightDirection[0], a.lightDirection[1], a.lightDirection[2]);
  srp::core::require(d.allFinite() && d.z() < 0.0,
                     "--light-direction: the light must travel down onto the table (z < 0 in the table's frame, "
                     "z up), e.g. -0.5,0.6,-0.65; got " +
                         std::to_string(d.x()) + "," + std::to_string(d.y()) + "," + std::to_string(d.z()));
  scene.lighting.direction_world = d;
}

void run(const SynthDemoArgs& a) {
  const std::string groundTruth = fs::path(a.outPath).lexically_normal().replace_extension(".gt.json").string();
  srp::core::checkOutputPaths(
      {{"-o", a.outPath}, {"ground truth", groundTruth}, {"--contact-sheet", a.contactSheet}},
      {{"--scene", a.scenePath}, {"--plan", a.planPath}, {"--depth-camera", a.depthCamera}}, a.overwrite);
  auto scene = srp::core::Scene::load(a.scenePath.empty() ? srp::core::defaultScenePath() : a.scenePath);
  const auto catalogue = srp::kb::loadCatalogue(scene.cataloguePath);
  const nlohmann::json plan = a.planPath.empty() ? srp::synth::defaultPlanJson() : srp::core::readJsonFile(a.planPath);
  srp::synth::SynthDemoOptions options;
  if (!a.viewpoint.empty()) {
    const auto [family, variant] = srp::synth::viewpointFromText(a.viewpoint);
    const auto view =
        srp::synth::makeViewpoint(family, variant, srp::synth::workCentre_world(scene, catalogue));
    scene.X_world_camera = view.X_world_camera;
    options.demo.demonstratorSide_world = view.demonstratorSide_world;
  }
  applyLight(a, scene, options);
  options.demo.seed = static_cast<std::uint32_t>(a.seed >= 0 ? a.seed : scene.seed);
  options.demo.randomise = !a.noRandomise;
  options.demo.speedFactor = a.speed;
  options.sensor.enabled = !a.clean;
  options.sensor.motionBlur = a.motionBlur;
  if (a.colourNoiseBlock > 0) options.sensor.colourNoiseBlock_px = a.colourNoiseBlock;
  if (a.depthNoiseBlock > 0) options.sensor.depthNoiseBlock_px = a.depthNoiseBlock;
  options.width_px = a.width;
  options.height_px = a.height;
  options.maxFrames = a.maxFrames;
  options.headSway.enabled = a.headSway;
  options.carryOnly = a.carryOnly;
  options.hand.sensorWires.enabled = a.sensorWires;
  std::optional<srp::core::AtomicOutputFile> contactSheet;
  if (!a.contactSheet.empty()) {
    contactSheet.emplace(a.contactSheet);
    options.contactSheetPath = contactSheet->temporaryPath().string();
  }
  if (!a.depthCamera.empty()) {
    // {"intrinsics": {fx, fy, cx, cy, width, height}, "X_colour_depth": {"translation": [m], "quaternion": [w, x, y, z]}}
    const nlohmann::json j = srp::core::readJsonFile(a.depthCamera);
    const std::string context = "depth camera file '" + a.depthCamera + "'";
    srp::synth::SynthDepthCamera d;
    d.intrinsics = srp::core::requireField(j, "intrinsics", context).get<srp::core::CameraIntrinsics>();
    if (j.contains("X_colour_depth")) d.X_colour_depth = srp::core::poseFromJson(j.at("X_colour_depth"), context);
    options.depthCamera = d;
  }
  srp::app::ProgressLine line(srp::app::progressWanted(a.json));
  StagedDemo staged(a.outPath, options.depthCamera.has_value());
  auto result = srp::synth::generateSyntheticDemo(scene, catalogue, plan, options, staged.stagedPath(), [&line](int k, int n) {
    if (k % 30 == 0 || k + 1 == n) line.show("synth-demo: frame", static_cast<std::size_t>(k + 1), static_cast<std::size_t>(n));
  });
  line.finish();
  if (contactSheet && !result.contactSheetPath.empty()) contactSheet->commit();
  staged.commit(result.groundTruthPath);
  result.rawlogPath = a.outPath;
  result.groundTruthPath = staged.finalPath(result.groundTruthPath);
  if (!result.contactSheetPath.empty()) result.contactSheetPath = a.contactSheet;
  const double fps = result.frameCount / result.totalTime_s;
  const double n = std::max(1, result.frameCount);
  const double rawlogMBPerMin = result.duration_s > 0.0 ? result.rawlogBytes / 1e6 / (result.duration_s / 60.0) : 0.0;
  if (a.json) {
    std::cout << nlohmann::json{{"rawlog", result.rawlogPath},
                                {"ground_truth", result.groundTruthPath},
                                {"contact_sheet", result.contactSheetPath},
                                {"frames", result.frameCount},
                                {"duration_s", result.duration_s},
                                {"generation_fps", fps},
                                {"render_s", result.renderTime_s},
                                {"sensor_s", result.sensorTime_s},
                                {"write_s", result.writeTime_s},
                                {"total_s", result.totalTime_s},
                                {"cpu_ms_per_frame",
                                 {{"render", 1e3 * result.renderCpuTime_s / n},
                                  {"sensor", 1e3 * result.sensorCpuTime_s / n},
                                  {"write", 1e3 * result.writeCpuTime_s / n},
                                  {"all", 1e3 * result.processCpuTime_s / n}}},
                                {"rawlog_bytes", result.rawlogBytes},
                                {"rawlog_MB_per_min", rawlogMBPerMin},
                                {"mean_hand_valid_depth", result.meanHandValidDepth},
                                {"mean_object_valid_depth", result.meanObjectValidDepth}}
                     .dump(2)
              << "\n";
    return;
  }
  std::cout << "rawlog:       " << result.rawlogPath << " (" << result.frameCount << " frames, " << result.duration_s
            << " s)\nground truth: " << result.groundTruthPath << "\n";
  if (!result.contactSheetPath.empty()) std::cout << "contact sheet: " << result.contactSheetPath << "\n";
  std::cout << "generated at " << fps << " frames/s; CPU per frame: render " << 1e3 * result.renderCpuTime_s / n
            << " ms, sensor " << 1e3 * result.sensorCpuTime_s / n << " ms, rawlog " << 1e3 * result.writeCpuTime_s / n
            << " ms; rawlog " << result.rawlogBytes / 1e6 << " MB (" << rawlogMBPerMin << " MB per minute)\n";
  if (!a.clean)
    std::cout << "valid depth: hand " << 100.0 * result.meanHandValidDepth << " %, moved parts "
              << 100.0 * result.meanObjectValidDepth << " %\n";
}

void setupSynthDemo(CLI::App& cmd) {
  auto args = std::make_shared<SynthDemoArgs>();
  cmd.add_option("--scene", args->scenePath, "scene JSON (default: the shipped sim/scenes/default.json of srp's data folder)");
  cmd.add_option("--plan", args->planPath,
                 "plan JSON in the `srp parse --json` step format (default: instruction 1 of the thesis)");
  cmd.add_option("-o,--out", args->outPath,
                 "output rawlog; the ground truth goes next to it as <name>.gt.json (both written whole or not at all)");
  cmd.add_option("--seed", args->seed, "randomisation seed (default: the scene's)");
  cmd.add_flag("--no-randomise", args->noRandomise, "use the scene exactly as given, nominal speed");
  cmd.add_option("--speed", args->speed, "demonstrator speed factor (>1 faster)")->check(CLI::Range(0.05, 20.0));
  cmd.add_flag("--clean", args->clean, "no sensor noise or invalid pixels");
  cmd.add_flag("--motion-blur", args->motionBlur, "blend each colour frame with the previous one");
  cmd.add_option("--colour-noise-block", args->colourNoiseBlock,
                 "colour noise drawn per block of N x N pixels (default 4; smaller: larger rawlog)")
      ->check(CLI::PositiveNumber);
  cmd.add_option("--depth-noise-block", args->depthNoiseBlock,
                 "depth noise and dropout drawn per block of N x N pixels (default 1: per pixel; 2: smaller rawlog)")
      ->check(CLI::PositiveNumber);
  cmd.add_option("--width", args->width, "image width (default: the scene camera's)")->check(CLI::Range(16, 16384));
  cmd.add_option("--height", args->height, "image height (default: the scene camera's)")->check(CLI::Range(16, 16384));
  cmd.add_option("--max-frames", args->maxFrames, "stop after this many frames")->check(CLI::PositiveNumber);
  cmd.add_option("--viewpoint", args->viewpoint,
                 "camera placement instead of the scene's: FAMILY or FAMILY:VARIANT, FAMILY one of egocentric (at "
                 "the demonstrator's head), side, top-down, front (across the table), oblique (a far corner), "
                 "near-corner (a corner on the demonstrator's side), table-level (beside the table, 0.2 m above it), "
                 "facing (across the table, 0.36 m above it, 30-45 deg off the demonstrator's direction); "
                 "variants turn the camera by -20/0/+20 deg and move it -10/0/+10 %");
  cmd.add_option("--light-rgb", args->lightRgb,
                 "the light's colour R,G,B: the scene's ambient and diffuse light scaled per channel (linear, "
                 "default 1,1,1; e.g. 1,0.9,0.78 a warm ~4000 K lamp seen by a camera balanced for daylight, as the "
                 "near-corner and table-level check renders; 0.85,0.93,1 a cold one, as the facing renders)")
      ->expected(3)
      ->delimiter(',')
      ->check(CLI::Range(0.0, 2.0));
  cmd.add_option("--light-direction", args->lightDirection,
                 "the light's direction of travel X,Y,Z in the table's frame (z up; default: the scene's, nearly "
                 "straight down; e.g. -0.5,0.6,-0.65 a lamp 40 deg above the table from the robot's side, as the "
                 "near-corner and table-level check renders; 0.5,-0.6,-0.55 from the demonstrator's side, 35 deg up, "
                 "as the facing renders); the seed still varies it slightly")
      ->expected(3)
      ->delimiter(',');
  cmd.add_flag("--head-sway", args->headSway,
               "a head-mounted camera: the camera sways smoothly about its pose (up to 3 deg of nod and turn, 1.5 "
               "deg of roll, 2 cm along each axis, at 0.1-0.8 Hz, as a working person's head; drawn from --seed); "
               "each frame's camera pose is in the ground truth");
  cmd.add_flag("--carry-only", args->carryOnly,
               "keep only the frames with a part in the hand, renumbered from 0: the clip starts with the hand "
               "holding the part (one continuous carry with a one-step plan)");
  cmd.add_flag("--sensor-wires", args->sensorWires,
               "dress the hand with a glove-less sensor rig: 2 mm dark wires along the back of the digits and the "
               "hand, 12 mm white tape on the fingertips and the back of the hand, a band of tape at the wrist");
  cmd.add_option("--contact-sheet", args->contactSheet, "write a PNG of a few frames (colour and depth)");
  cmd.add_option("--depth-camera", args->depthCamera,
                 "JSON of a depth camera of its own ({\"intrinsics\": {fx, fy, cx, cy, width, height}, "
                 "\"X_colour_depth\": {\"translation\": [x, y, z] m, \"quaternion\": [w, x, y, z]}}): depth is "
                 "rendered by it and -o names an image folder for 'srp import' (unregistered RGB-D, as a "
                 "RealSense records it); example: sim/cameras/realsense_d435_depth.json");
  cmd.add_flag("--json", args->json, "print the result as JSON");
  srp::app::addOverwriteFlag(cmd, args->overwrite);
  cmd.callback([args]() { run(*args); });
}

const srp::app::CommandRegistrar kReg{"synth-demo",
                                      "Synthesise an RGB-D demonstration (rawlog + ground truth) from a scene and a plan",
                                      25, setupSynthDemo};

}  // namespace
