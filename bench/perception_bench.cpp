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

// The whole module: marker hand + all classes, per frame (start-up excluded).
void BM_WholeModulePerFrame(benchmark::State& state) {
  PerceptionOptions o;
  o.marker.tagSize_m = 0.0955;
  o.marker.tagId = 0;
  for (auto _ : state) benchmark::DoNotOptimize(perceiveFrames(frames(), catalogue(), o));
  state.counters["FPS"] = benchmark::Counter(static_cast<double>(state.iterations() * frames().size()),
                                             benchmark::Counter::kIsRate);
}
BENCHMARK(BM_WholeModulePerFrame)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
