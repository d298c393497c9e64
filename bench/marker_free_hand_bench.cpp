// The marker-free hand detector on rendered synthetic demos with ground truth,
// timed per frame on one core:
// - still camera: srp::synth's default scene, thesis instruction 1, default sensor noise; prints the
//   detection rate and palm centre error (as the perception test), then times detect() over hand
//   frames of that demo (background from its first frames, as a stream);
// - moving camera: an egocentric head-mounted camera that sways (synth::HeadSway), the hand holding the
//   cuboid in every frame (ViewpointDemos.h, egocentric variant 0, sleeve, seed 41: the development
//   demo of the egocentric-held family); every frame is previewed first, as `srp perceive` does, so
//   each frame's background is the whole-recording one warped into that frame's camera.
//
//   marker_free_hand_bench                      renders both demos to the temp folder (~1 min)
//   marker_free_hand_bench --demo demo.rawlog   the still case on a `srp synth-demo` output (demo.gt.json next to it)
//   marker_free_hand_bench --moving-demo m.rawlog  the moving case on that recording (its .gt.json next to it)
//   other arguments go to Google Benchmark (e.g. --benchmark_min_time=2s,
//   --benchmark_filter=Moving)
#include <benchmark/benchmark.h>

#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "../libs/perception/tests/HandEvaluation.h"
#include "../libs/perception/tests/ViewpointDemos.h"
#include "BenchDemo.h"
#include "ThreadCpuTime.h"

namespace {

using namespace srp;
using perception::MarkerFreeHandDetector;

std::vector<rawlog::RgbdFrame> gBackground, gHandFrames, gMovingFrames;

void BM_MarkerFreeHandSyntheticFrame(benchmark::State& state) {
  MarkerFreeHandDetector detector({});
  for (const auto& f : gBackground) detector.detect(f);
  std::size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(detector.detect(gHandFrames[i++ % gHandFrames.size()]));
  state.counters["FPS"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_MarkerFreeHandSyntheticFrame)->Unit(benchmark::kMillisecond);

void BM_MarkerFreeHandMovingCameraFrame(benchmark::State& state) {
  MarkerFreeHandDetector detector({});
  for (const auto& f : gMovingFrames) detector.preview(f);
  // The preview's background and skin model, once per recording (reported, not in the per-frame time).
  const double t0_s = srp::bench::threadCpu_s();
  detector.detect(gMovingFrames[0]);
  const double firstDetect_ms = 1e3 * (srp::bench::threadCpu_s() - t0_s);
  if (!detector.followsCamera()) {
    state.SkipWithError("the preview did not find the camera moving: not the moving-camera path");
    return;
  }
  std::size_t i = 1;
  for (auto _ : state) benchmark::DoNotOptimize(detector.detect(gMovingFrames[i++ % gMovingFrames.size()]));
  state.counters["FPS"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["first_detect_ms"] = firstDetect_ms;
  state.counters["frames"] = static_cast<double>(gMovingFrames.size());
}
BENCHMARK(BM_MarkerFreeHandMovingCameraFrame)->Unit(benchmark::kMillisecond);

}  // namespace

int main(int argc, char** argv) {
  std::string demo, movingDemo;
  std::vector<char*> rest{argv[0]};
  for (int i = 1; i < argc; ++i) {
    if (std::string(argv[i]) == "--demo" && i + 1 < argc) demo = argv[++i];
    else if (std::string(argv[i]) == "--moving-demo" && i + 1 < argc) movingDemo = argv[++i];
    else rest.push_back(argv[i]);
  }
  if (demo.empty()) {
    std::fprintf(stderr, "rendering the first 200 frames of the default demo ...\n");
    demo = srp::bench::syntheticBenchDemo(200);
  }
  const int backgroundFrames = MarkerFreeHandDetector::Options{}.backgroundFrames;
  const auto ev = perception::testing::evaluateMarkerFreeHand(
      demo, {},
      [&](const rawlog::RgbdFrame& f, const MarkerFreeHandDetector&, const synth::GroundTruthFrame& truth,
          const std::optional<Eigen::Vector3d>&) {
        // Every 3rd frame with the hand in view, at most 60 (memory), for the timing.
        if (truth.index < backgroundFrames) gBackground.push_back(f);
        else if (truth.handInView && truth.index % 3 == 0 && gHandFrames.size() < 60) gHandFrames.push_back(f);
      });
  ev.print(demo);
  if (gHandFrames.empty()) return 1;

  // The moving camera: rendered into the temp folder, removed at exit.
  std::filesystem::path renderedFolder;
  if (movingDemo.empty()) {
    std::fprintf(stderr, "rendering the egocentric head-sway demo holding the cuboid ...\n");
    perception::testing::ViewpointDemoSpec spec;
    spec.family = synth::ViewpointFamily::Egocentric;
    spec.seed = 41;
    spec.headSway = true;
    spec.heldOnly = "cuboid";
    renderedFolder = std::filesystem::temp_directory_path() /
                     ("srp_bench_moving_" + std::to_string(::getpid()));
    movingDemo = perception::testing::renderViewpointDemo(spec, renderedFolder.string());
  }
  const auto moving = perception::testing::evaluateMarkerFreeHand(
      movingDemo, {},
      [&](const rawlog::RgbdFrame& f, const MarkerFreeHandDetector&, const synth::GroundTruthFrame&,
          const std::optional<Eigen::Vector3d>&) { gMovingFrames.push_back(f); },
      true);
  moving.print(movingDemo);
  if (!renderedFolder.empty()) std::filesystem::remove_all(renderedFolder);
  if (gMovingFrames.size() < 2) return 1;

  int n = static_cast<int>(rest.size());
  benchmark::Initialize(&n, rest.data());
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
