// Cost of srp::rawlog::DepthRegistration per frame (issue 23): real RealSense
// depth (datasets/real/visp-rbt-cube frame 0, 640x480, with holes) seen as the
// depth camera of a two-camera sensor (15 mm, 0.3 degree) registered onto a
// colour camera of 640x480 (same field of view) or 1280x720 (twice the focal
// length). Arg: colour width.
#include <benchmark/benchmark.h>

#include <opencv2/imgcodecs.hpp>

#include "srp/rawlog/DepthRegistration.h"

namespace {

void BM_RegisterDepth(benchmark::State& state) {
  const cv::Mat raw = cv::imread(std::string(SRP_DATASETS_DIR) + "/real/visp-rbt-cube/depth_0000.png", cv::IMREAD_UNCHANGED);
  if (raw.empty()) {
    state.SkipWithError("datasets/real/visp-rbt-cube/depth_0000.png missing");
    return;
  }
  cv::Mat depth;
  raw.convertTo(depth, CV_32FC1, 0.001);
  const srp::core::CameraIntrinsics Kd{607.18, 607.23, 321.39, 241.92, 640, 480};
  const double s = state.range(0) / 640.0;
  const srp::core::CameraIntrinsics Kc{607.18 * s, 607.23 * s, 321.39 * s, 241.92 * s, static_cast<int>(state.range(0)),
                                       static_cast<int>(state.range(0) == 640 ? 480 : 720)};
  srp::core::Pose3 X_colour_depth = srp::core::Pose3::Identity();
  X_colour_depth.translation() = Eigen::Vector3d(-0.015, 0.0002, 0.0004);
  X_colour_depth.linear() = Eigen::AngleAxisd(0.005, Eigen::Vector3d::UnitY()).toRotationMatrix();
  const srp::rawlog::DepthRegistration reg({Kd, {}}, {Kc, {}}, X_colour_depth);
  for (auto _ : state) benchmark::DoNotOptimize(reg.registerDepth(depth));
}
BENCHMARK(BM_RegisterDepth)->Arg(640)->Arg(1280)->Unit(benchmark::kMillisecond)->MinTime(2.0);

}  // namespace

BENCHMARK_MAIN();
