#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>

#include "srp/core/ObjectCatalogue.h"
#include "srp/core/Scene.h"

namespace srp::experiment {

/**
 * Which synthetic demonstration to render (`srp::synth`): scene, plan, seed,
 * size. Two requests with the same fields name the same demo.
 */
struct DemoRequest
{
  std::filesystem::path scenePath;  ///< scene JSON; empty: the default scene (defaultScenePathIn(simDir))
  /// Plan in the `srp parse --json` step format (may carry "instruction");
  /// null: instruction 1 of the thesis (srp::synth::defaultPlanJson()).
  nlohmann::json plan;
  std::uint32_t seed = 1;   ///< randomisation seed (placements, camera jitter, speed, ...)
  int maxFrames = -1;       ///< stop after this many frames; -1: the whole demo
  int width_px = 0;         ///< 0: the scene camera's size; otherwise intrinsics scaled
  int height_px = 0;
  bool sensorRealism = true;  ///< SensorModel noise and invalid depth (the default of srp synth-demo)
};

/// A rendered demo on disk.
struct CachedDemo
{
  std::filesystem::path rawlogPath;       ///< MRPT rawlog of CObservation3DRangeScan frames
  std::filesystem::path groundTruthPath;  ///< srp::synth::DemoGroundTruth JSON (load it with DemoGroundTruth::load)
  std::string instruction;                ///< the plan's "instruction" text ("" when the plan has none)
  int frameCount = 0;
  bool renderedNow = false;               ///< false: found in the cache
  double renderTime_s = 0.0;              ///< wall time of the rendering (0 when cached)
  std::string key;                        ///< the request's cache key (DemoCache::keyOf)
  core::Scene scene;                      ///< the scene the demo shows, from the read the key was made of
  core::ObjectCatalogue catalogue;        ///< its catalogue (kb::loadCatalogue)
};

/// A cached demo programmed by `srp::programming::programTask` (as `srp
/// program` does: Language -> Environment -> Motion -> task model in SQLite).
struct ProgrammedDemo
{
  CachedDemo demo;
  std::filesystem::path databasePath;  ///< SQLite task database holding the one task model
  int taskModelId = 0;
  nlohmann::json program;              ///< the ProgramResult (`srp program --json` form)
  bool programmedNow = false;          ///< false: found in the cache
  double programTime_s = 0.0;          ///< wall time of programTask (0 when cached)
};

/**
 * Renders each requested synthetic demonstration once and hands out its
 * files afterwards, so the experiments of one `srp experiment all` run share
 * them: demo `seed` lives in `<rootDir>/<seed>/<key>.rawlog` (+ `.gt.json`),
 * where `<key>` is a hash of the request (scene file contents, plan, frames,
 * size, sensor model), and `<key>.done.json` marks a complete rendering (an
 * interrupted one is rendered again).
 *
 * \code
 *   DemoCache cache(options.outDir / "demos", options.simDir);
 *   DemoRequest request;  request.seed = 3;
 *   const CachedDemo demo = cache.get(request);
 *   auto gt = srp::synth::DemoGroundTruth::load(demo.groundTruthPath.string());
 * \endcode
 */
class DemoCache
{
public:
  /// `rootDir`: where demos are kept (created on first use); `simDir`: the
  /// repo's sim/ (default scene); empty: `sim/` of srp's data folder (core::DataPaths).
  explicit DemoCache(std::filesystem::path rootDir, std::filesystem::path simDir = {});

  /// The demo of `request`, rendered now if not cached, with its key, scene and
  /// catalogue (the scene file is read once). `progress(frame, frames)`
  /// is called while rendering. Throws FileError naming a missing scene or
  /// catalogue, InvalidInputError for a plan the scene cannot carry out.
  CachedDemo get(const DemoRequest& request, const std::function<void(int, int)>& progress = {}) const;

  /// The demo of `request` programmed with its plan's "instruction" (rendered
  /// and programmed now if not cached): `<key>.task.db` beside the rawlog,
  /// `<key>.program.json` marking a complete run by this build of the program
  /// (programBuildIdentity(); another build programs again). `progress(stage, done, total)`
  /// reports rendering ("render") and the pipeline's stages. Throws
  /// InvalidInputError when the plan has no "instruction".
  ProgrammedDemo programmed(const DemoRequest& request,
                            const std::function<void(const std::string&, std::size_t, std::size_t)>& progress = {}) const;

  /// The cache key of a request (16 hex digits).
  std::string keyOf(const DemoRequest& request) const;

  const std::filesystem::path& rootDir() const { return rootDir_; }

private:
  std::filesystem::path scenePathOf(const DemoRequest& request) const;

  std::filesystem::path rootDir_;
  std::filesystem::path simDir_;
};

struct ExperimentOptions;

/// The default scene of a run: `<simDir>/scenes/default.json`; an empty
/// `simDir`: core::defaultScenePath() (sim/ of srp's data folder). The one
/// place the experiments resolve it (demo cache, studies, execution).
std::filesystem::path defaultScenePathIn(const std::filesystem::path& simDir);

/// Image size of the shared demos (the scene camera's intrinsics scaled).
constexpr int kStandardWidth_px = 320;
constexpr int kStandardHeight_px = 240;

/// The demo every chapter-8 experiment shares, so `all` renders it once: the
/// default scene, thesis instruction 1, seed `options.firstSeed + index`, the
/// whole demo at kStandardWidth_px x kStandardHeight_px; with `options.quick`
/// the first step alone ("Pick up the cuboid from the blue box and place it in
/// the gray box.", about 250 frames).
DemoRequest standardDemoRequest(const ExperimentOptions& options, int index);

/// The shared demo cache of a run: `<options.outDir>/demos`.
DemoCache demoCacheFor(const ExperimentOptions& options);

}  // namespace srp::experiment
