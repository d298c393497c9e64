// Environment module speed on 640x480 RGB-D frames, one core, CPU time per
// frame (target >= 30 FPS, stretch >= 120 FPS), on two datasets:
// (a) the synthetic default demo (srp::synth, default scene, thesis
//     instruction 1, default sensor noise), its first kSynthFrames frames (the
//     first pick & place: idle, reach, grasp, carry, release, retract),
//     rendered by this build at start (bench/BenchDemo.h);
// (b) the real RealSense recording (datasets/real/visp-rbt-cube, 10 frames of
//     a cluttered desk, hand-held camera) with the whole knowledge base as
//     object models.
// The whole module is DemoPerceiver::add as `srp perceive` and `srp program`
// run it (marker hand + objects); one benchmark iteration = one pass over the
// demo with a fresh perceiver; only add() is timed (thread CPU time), so
// start-up (models) and rawlog decoding are not counted (BM_StartUp).
#include <benchmark/benchmark.h>

#include "BenchDemo.h"
#include "ThreadCpuTime.h"
#include "srp/kb/KnowledgeBase.h"
#include "srp/perception/DemoPerception.h"
#include "srp/perception/MarkerFreeHandDetector.h"
#include "srp/perception/MarkerHandDetector.h"
#include "srp/perception/ObjectDetector.h"
#include "srp/perception/RgbdFolder.h"
#include "srp/rawlog/RawlogReader.h"

namespace {

using namespace srp::perception;

constexpr int kSynthFrames = 200;

const std::vector<srp::rawlog::RgbdFrame>& realFrames() {
  static const auto f = readRgbdFolder(std::string(SRP_DATASETS_DIR) + "/real/visp-rbt-cube", 10);  // frames 0-9, as before the folder held 50
  return f;
}

const srp::core::ObjectCatalogue& catalogue() {
  static const auto c = srp::kb::loadCatalogue(srp::core::ObjectCatalogue::defaultPath());
  return c;
}

void BM_WholeModule_SyntheticDemo(benchmark::State& state) {
  PerceptionOptions o;  // marker defaults = synth-demo's glove
  o.plan = {{"cuboid", false}, {"star", false}, {"parallelogram", false}, {"octagon", false},
            {"blue box", true}, {"gray box", true}};  // what `srp program` grounds for instruction 1
  const std::string path = srp::bench::syntheticBenchDemo(kSynthFrames);  // rendered once per process
  int frames = 0;
  for (auto _ : state) {
    DemoPerceiver perceiver(catalogue(), o);
    srp::rawlog::RawlogReader reader(path);
    double cpu_s = 0.0;
    while (auto f = reader.next()) {
      const double t0 = srp::bench::threadCpu_s();
      perceiver.add(*f);
      cpu_s += srp::bench::threadCpu_s() - t0;
    }
    frames += perceiver.framesAdded();
    state.SetIterationTime(cpu_s / perceiver.framesAdded());  // per frame
  }
  state.counters["frames"] = frames / static_cast<double>(state.iterations());
  state.counters["FPS"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_WholeModule_SyntheticDemo)->UseManualTime()->Unit(benchmark::kMillisecond)->Iterations(2);

void BM_WholeModule_RealDesk(benchmark::State& state) {
  PerceptionOptions o;
  o.marker.tagSize_m = 0.0955;  // a board tag stands in for the glove's
  o.marker.tagId = 0;
  for (auto _ : state) {
    DemoPerceiver perceiver(catalogue(), o);
    double cpu_s = 0.0;
    double t_s = 0.0;
    for (auto f : realFrames()) {
      f.t_s = (t_s += 1.0 / 30.0);
      const double t0 = srp::bench::threadCpu_s();
      perceiver.add(f);
      cpu_s += srp::bench::threadCpu_s() - t0;
    }
    state.SetIterationTime(cpu_s / perceiver.framesAdded());
  }
  state.counters["FPS"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_WholeModule_RealDesk)->UseManualTime()->Unit(benchmark::kMillisecond);

void BM_MarkerHand(benchmark::State& state) {
  MarkerHandDetector::Options o;
  o.tagSize_m = 0.0955;
  o.tagId = 0;
  MarkerHandDetector detector(o);
  std::size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(detector.detect(realFrames()[i++ % realFrames().size()]));
  state.counters["FPS"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_MarkerHand)->Unit(benchmark::kMillisecond);

void BM_MarkerFreeHand(benchmark::State& state) {
  MarkerFreeHandDetector detector({2});
  for (const auto& f : realFrames()) detector.detect(f);  // background learnt
  std::size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(detector.detect(realFrames()[i++ % realFrames().size()]));
  state.counters["FPS"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_MarkerFreeHand)->Unit(benchmark::kMillisecond);

// One frame from scratch, no tracking (what every frame cost before ObjectTracker).
void BM_ObjectsOneFrameFullSearch(benchmark::State& state) {
  const ObjectDetector detector(ObjectDetector::modelsFromCatalogue(catalogue()));
  detector.detect(realFrames()[0]);
  const Plane plane = *detector.lastPlane();
  std::size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(detector.detect(realFrames()[i++ % realFrames().size()], &plane));
  state.counters["FPS"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_ObjectsOneFrameFullSearch)->Unit(benchmark::kMillisecond);

// Start-up: models and nearest-surface grids of the six catalogue classes.
void BM_StartUp(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(ObjectDetector(ObjectDetector::modelsFromCatalogue(catalogue())));
}
BENCHMARK(BM_StartUp)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
