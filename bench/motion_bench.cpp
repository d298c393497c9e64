// Motion module timings (issue 6): imitate + rollout of a 3D 100-sample
// segment (target < 0.2 ms), and segmentation of a 60 s, 30 FPS demo with 4
// objects (target < 50 ms), single thread. Reference library (dfki-ric
// movement_primitives, pure Python, datasets/reference/dmp/README.md):
// imitate ~0.23 ms + open_loop ~0.92 ms for a 21-sample segment.
#include <benchmark/benchmark.h>

#include <cmath>
#include <opencv2/core.hpp>

#include "srp/motion/Dmp.h"
#include "srp/motion/Segmenter.h"
#include "srp/motion/SyntheticPickPlace.h"

namespace {

using namespace srp::motion;

struct Segment {
  Eigen::VectorXd t;
  Eigen::MatrixXd Y;
};

Segment hundredSamples() {
  Segment s;
  s.t.resize(100);
  s.Y.resize(100, 3);
  for (int i = 0; i < 100; ++i) {
    s.t(i) = i / 30.0;
    const double u = i / 99.0, m = u * u * u * (10 - 15 * u + 6 * u * u);
    s.Y.row(i) << 0.1 + 0.3 * m, -0.2 + 0.25 * m + 0.02 * std::sin(9 * u), 0.8 - 0.12 * std::sin(M_PI * m);
  }
  return s;
}

void BM_DmpImitateAndRollout_Default(benchmark::State& state) {
  const Segment s = hundredSamples();
  for (auto _ : state) {
    Dmp dmp = Dmp::imitate(s.t, s.Y, Dmp::Options{});
    benchmark::DoNotOptimize(dmp.rollout().y.data());
  }
}
BENCHMARK(BM_DmpImitateAndRollout_Default)->Unit(benchmark::kMicrosecond);

void BM_DmpImitateAndRollout_DefaultFixedLambda(benchmark::State& state) {
  const Segment s = hundredSamples();
  Dmp::Options c;
  c.lambda = 1e-6;
  for (auto _ : state) {
    Dmp dmp = Dmp::imitate(s.t, s.Y, c);
    benchmark::DoNotOptimize(dmp.rollout().y.data());
  }
}
BENCHMARK(BM_DmpImitateAndRollout_DefaultFixedLambda)->Unit(benchmark::kMicrosecond);

void BM_DmpImitateAndRollout_Reference(benchmark::State& state) {
  const Segment s = hundredSamples();
  for (auto _ : state) {
    Dmp dmp = Dmp::imitate(s.t, s.Y, Dmp::Options::reference(0.1));
    benchmark::DoNotOptimize(dmp.rollout(1.0 / 30.0).y.data());
  }
}
BENCHMARK(BM_DmpImitateAndRollout_Reference)->Unit(benchmark::kMicrosecond);

void BM_Segment60sDemo4Objects(benchmark::State& state) {
  srp::motion::SyntheticPickPlaceGenerator::Options c;
  c.reachDuration_s = 4.0;  // stretched so the 4 pick & place steps fill 60 s
  c.moveDuration_s = 5.0;
  c.idleBetween_s = 4.5;
  c.handAbsent_s = 2.0;
  const auto demo = srp::motion::SyntheticPickPlaceGenerator(c).generate();
  state.counters["frames"] = static_cast<double>(demo.hand.size());
  for (auto _ : state) {
    const auto seg = Segmenter().segment(demo.hand, demo.objects, demo.planOrder);
    benchmark::DoNotOptimize(seg.objects.data());
  }
}
BENCHMARK(BM_Segment60sDemo4Objects)->Unit(benchmark::kMillisecond);

}  // namespace

int main(int argc, char** argv) {
  cv::setNumThreads(1);  // one core, as the issue asks
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  return 0;
}
