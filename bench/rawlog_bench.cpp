// Rawlog decoding on 640x480 RGB-D frames of the synthetic default demo
// (srp::synth, default scene and sensor noise, first kFrames frames, rendered
// by this build at start, bench/BenchDemo.h):
// - BM_Decode/<read-ahead>: wall time per frame of RawlogReader::next() alone,
//   synchronous (0) and with the background read-ahead (4);
// - BM_DecodeAndWork/<read-ahead>: the same with a consumer that spends
//   kWork_ms of CPU on each frame, as perception does (~15 ms at 64 FPS): with
//   read-ahead on two free cores the time per frame drops from decode + work
//   to about max(decode, work).
#include <benchmark/benchmark.h>

#include <chrono>
#include "BenchDemo.h"
#include "ThreadCpuTime.h"
#include "srp/rawlog/RawlogReader.h"

namespace {

constexpr int kFrames = 60;
constexpr double kWork_ms = 15.0;

/// Spends `ms` of this thread's CPU time (a stand-in for perception's work on a frame).
void spendCpu(double ms) {
  const double end = srp::bench::threadCpu_s() + 1e-3 * ms;
  volatile double x = 0.0;
  while (srp::bench::threadCpu_s() < end)
    for (int i = 0; i < 1000; ++i) x = x + 1e-9 * i;
}

void readAll(benchmark::State& state, double work_ms) {
  const std::string path = srp::bench::syntheticBenchDemo(kFrames);  // rendered once per process
  const int readAhead = static_cast<int>(state.range(0));
  int frames = 0;
  const auto t0 = std::chrono::steady_clock::now();
  for (auto _ : state) {
    srp::rawlog::RawlogReader reader(path, readAhead);
    int n = 0;
    while (auto f = reader.next()) {
      benchmark::DoNotOptimize(f->depth_m.data);
      if (work_ms > 0) spendCpu(work_ms);
      ++n;
    }
    frames += n;
  }
  const double wall_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  state.counters["wall_ms_per_frame"] = wall_ms / frames;
  state.counters["frames"] = frames / static_cast<double>(state.iterations());
}

void BM_Decode(benchmark::State& state) { readAll(state, 0.0); }
void BM_DecodeAndWork(benchmark::State& state) { readAll(state, kWork_ms); }

}  // namespace

BENCHMARK(BM_Decode)->Arg(0)->Arg(4)->UseRealTime()->Unit(benchmark::kMillisecond)->MinTime(2.0);
BENCHMARK(BM_DecodeAndWork)->Arg(0)->Arg(4)->UseRealTime()->Unit(benchmark::kMillisecond)->Iterations(3);

BENCHMARK_MAIN();
