#pragma once
// The synthetic demo the benchmarks share: srp::synth's default scene, thesis
// instruction 1, default sensor noise, 640x480, its first `frames` frames,
// rendered into the temp folder on first use and reused by later runs.
#include <filesystem>
#include <string>

#include "srp/core/Scene.h"
#include "srp/synth/DemoGenerator.h"
#include "srp/synth/PickPlacePlan.h"

namespace srp::bench {

/// Path of the demo's rawlog (its ground truth beside it as .gt.json).
inline std::string syntheticBenchDemo(int frames) {
  const auto file = std::filesystem::temp_directory_path() / ("srp_bench_demo_" + std::to_string(frames) + ".rawlog");
  // The ground truth is written last: without it the rawlog may be partial.
  if (!std::filesystem::exists(std::filesystem::path(file).replace_extension(".gt.json"))) {
    const auto scene = core::Scene::load(std::string(SRP_SIM_DIR) + "/scenes/default.json");
    synth::SynthDemoOptions o;
    o.demo.seed = static_cast<std::uint32_t>(scene.seed);
    o.maxFrames = frames;
    synth::generateSyntheticDemo(scene, core::ObjectCatalogue::load(scene.cataloguePath), synth::defaultPlanJson(), o,
                                 file.string());
  }
  return file.string();
}

}  // namespace srp::bench
