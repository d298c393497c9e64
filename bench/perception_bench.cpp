// Environment module speed on 640x480 RGB-D frames, one core: the real
// RealSense recording (datasets/real/visp-rbt-cube, cluttered desk) with the
// whole knowledge base as object models. Target >= 30 FPS, stretch >= 120 FPS.
#include <benchmark/benchmark.h>

#include "srp/perception/DemoPerception.h"
#include "srp/perception/MarkerFreeHandDetector.h"
#include "srp/perception/MarkerHandDetector.h"
#include "srp/perception/ObjectDetector.h"
#include "srp/perception/RgbdFolder.h"

namespace {

using namespace srp::perception;

const std::vector<srp::rawlog::RgbdFrame>& frames() {
  static const auto f = readRgbdFolder(std::string(SRP_DATASETS_DIR) + "/real/visp-rbt-cube");
  return f;
}

const srp::core::ObjectCatalogue& catalogue() {
  static const auto c = srp::core::ObjectCatalogue::load(srp::core::ObjectCatalogue::defaultPath());
  return c;
}

void BM_MarkerHand(benchmark::State& state) {
  MarkerHandDetector::Options o;
  o.tagSize_m = 0.0955;
  o.tagId = 0;
  MarkerHandDetector detector(o);
  std::size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(detector.detect(frames()[i++ % frames().size()]));
  state.counters["FPS"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_MarkerHand)->Unit(benchmark::kMillisecond);

void BM_MarkerFreeHand(benchmark::State& state) {
  MarkerFreeHandDetector detector({2});
  for (const auto& f : frames()) detector.detect(f);  // background learnt
  std::size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(detector.detect(frames()[i++ % frames().size()]));
  state.counters["FPS"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_MarkerFreeHand)->Unit(benchmark::kMillisecond);

void BM_ObjectsAllClasses(benchmark::State& state) {
  const ObjectDetector detector(ObjectDetector::modelsFromCatalogue(catalogue()));
  detector.detect(frames()[0]);
  const Plane plane = *detector.lastPlane();
  std::size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(detector.detect(frames()[i++ % frames().size()], &plane));
  state.counters["FPS"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_ObjectsAllClasses)->Unit(benchmark::kMillisecond);

// The whole module per frame (start-up, i.e. building the models, excluded):
// marker hand + all six classes, with the support plane fitted once.
void BM_WholeModulePerFrame(benchmark::State& state) {
  PerceptionOptions o;
  o.marker.tagSize_m = 0.0955;  // a board tag stands in for the glove's
  o.marker.tagId = 0;
  DemoPerceiver perceiver(catalogue(), o);
  std::size_t i = 0;
  double t_s = 0.0;
  for (auto _ : state) {
    auto f = frames()[i++ % frames().size()];
    f.t_s = (t_s += 1.0 / 30.0);
    perceiver.add(f);
  }
  state.counters["FPS"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_WholeModulePerFrame)->Unit(benchmark::kMillisecond);

// Start-up: models and nearest-surface grids of the six catalogue classes.
void BM_StartUp(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(ObjectDetector(ObjectDetector::modelsFromCatalogue(catalogue())));
}
BENCHMARK(BM_StartUp)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
