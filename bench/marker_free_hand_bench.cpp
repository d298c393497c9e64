// The marker-free hand detector on a rendered synthetic demo with ground truth
// (srp::synth, default scene, thesis instruction 1, default sensor noise):
// prints the detection rate and palm centre error (as the perception test),
// then times detect() per frame on one core over hand frames of that demo.
//
//   marker_free_hand_bench                      renders the first 200 frames to the temp folder
//   marker_free_hand_bench --demo demo.rawlog   a `srp synth-demo` output (demo.gt.json next to it)
//   other arguments go to Google Benchmark (e.g. --benchmark_min_time=2s)
#include <benchmark/benchmark.h>

#include <string>
#include <vector>

#include "../libs/perception/tests/HandEvaluation.h"
#include "BenchDemo.h"

namespace {

using namespace srp;
using perception::MarkerFreeHandDetector;

std::vector<rawlog::RgbdFrame> gBackground, gHandFrames;

void BM_MarkerFreeHandSyntheticFrame(benchmark::State& state) {
  MarkerFreeHandDetector detector({});
  for (const auto& f : gBackground) detector.detect(f);
  std::size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(detector.detect(gHandFrames[i++ % gHandFrames.size()]));
  state.counters["FPS"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_MarkerFreeHandSyntheticFrame)->Unit(benchmark::kMillisecond);

}  // namespace

int main(int argc, char** argv) {
  std::string demo;
  std::vector<char*> rest{argv[0]};
  for (int i = 1; i < argc; ++i) {
    if (std::string(argv[i]) == "--demo" && i + 1 < argc) demo = argv[++i];
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
  int n = static_cast<int>(rest.size());
  benchmark::Initialize(&n, rest.data());
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
