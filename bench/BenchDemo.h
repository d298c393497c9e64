#pragma once
// The synthetic demo the benchmarks share: srp::synth's default scene, thesis
// instruction 1, default sensor noise, 640x480, its first `frames` frames,
// rendered by this build into the temp folder once per process (1-2 s) and
// removed at exit: a demo cached across runs had been rendered by an older
// sensor model and made perception look 35 % faster than it is.
#include <unistd.h>

#include <filesystem>
#include <map>
#include <string>

#include "srp/core/Scene.h"
#include "srp/kb/KnowledgeBase.h"
#include "srp/synth/DemoGenerator.h"
#include "srp/synth/PickPlacePlan.h"

namespace srp::bench {

/// Path of the demo's rawlog (its ground truth beside it as .gt.json).
inline std::string syntheticBenchDemo(int frames) {
  struct Rendered {
    std::map<int, std::filesystem::path> files;
    ~Rendered() {
      for (const auto& [n, f] : files) {
        std::error_code ec;
        std::filesystem::remove(f, ec);
        std::filesystem::remove(std::filesystem::path(f).replace_extension(".gt.json"), ec);
      }
    }
  };
  static Rendered rendered;
  if (const auto it = rendered.files.find(frames); it != rendered.files.end()) return it->second.string();
  const auto file = std::filesystem::temp_directory_path() /
                    ("srp_bench_demo_" + std::to_string(frames) + "_" + std::to_string(::getpid()) + ".rawlog");
  const auto scene = core::Scene::load(std::string(SRP_SIM_DIR) + "/scenes/default.json");
  synth::SynthDemoOptions o;
  o.demo.seed = static_cast<std::uint32_t>(scene.seed);
  o.maxFrames = frames;
  synth::generateSyntheticDemo(scene, kb::loadCatalogue(scene.cataloguePath), synth::defaultPlanJson(), o,
                               file.string());
  rendered.files[frames] = file;
  return file.string();
}

}  // namespace srp::bench
