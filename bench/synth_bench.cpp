// Speed of the synthetic demonstration generator at 640x480: rendering, sensor
// realism, rawlog writing, and the whole pipeline (frames/s, rawlog MB/minute).
#include <benchmark/benchmark.h>

#include <filesystem>

#include "srp/core/ObjectCatalogue.h"
#include "srp/core/Scene.h"
#include "srp/kb/KnowledgeBase.h"
#include "srp/kb/ShapeMeshes.h"
#include "srp/rawlog/RawlogWriter.h"
#include "srp/synth/DemoGenerator.h"
#include "srp/synth/HandModel.h"
#include "srp/synth/SceneRenderer.h"
#include "srp/synth/SensorModel.h"

namespace {

srp::core::Scene defaultScene() { return srp::core::Scene::load(std::string(SRP_SIM_DIR) + "/scenes/default.json"); }

std::string tempPath(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("srp_synth_bench_" + name)).string();
}

// One frame of the default scene with the hand in view.
void BM_RenderFrame(benchmark::State& state) {
  const auto scene = defaultScene();
  const auto catalogue = srp::kb::loadCatalogue(scene.cataloguePath);
  srp::synth::SceneRenderer renderer(scene.intrinsics);
  renderer.setLighting(scene.lighting);
  renderer.addBody("table", srp::kb::makeBoxMesh({-0.6, -0.4, -0.03}, {0.6, 0.4, 0.0}), scene.tableRgb);
  renderer.addBody("floor", srp::kb::makeBoxMesh({-3, -3, -0.78}, {3, 3, -0.75}), {0.42, 0.4, 0.38});
  for (const auto& o : scene.objects) {
    const int b = renderer.addBody(o.id, srp::kb::loadClassMesh(catalogue.at(o.className)), catalogue.at(o.className).rgb);
    renderer.setBodyPose(b, o.X_world_object);
  }
  srp::synth::HandModel hand;
  const auto poses = hand.partPoses(0.5);
  const auto X_world_hand = srp::core::makePoseYPR({0.0, 0.15, 0.15}, -1.6, 0.1, 0.0);
  for (std::size_t i = 0; i < hand.parts().size(); ++i) {
    const int b = renderer.addBody(hand.parts()[i].name, hand.parts()[i].mesh_part, hand.parts()[i].triangleRgb);
    renderer.setBodyPose(b, X_world_hand * poses[i]);
  }
  for (auto _ : state) benchmark::DoNotOptimize(renderer.render(scene.X_world_camera));
  state.counters["frames_per_s"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_RenderFrame)->Unit(benchmark::kMillisecond)->UseRealTime();

srp::rawlog::RgbdFrame flatFrame(const srp::core::CameraIntrinsics& K) {
  srp::rawlog::RgbdFrame f;
  f.intrinsics = K;
  f.colour_bgr8 = cv::Mat(K.height_px, K.width_px, CV_8UC3, cv::Scalar(150, 170, 190));
  f.depth_m = cv::Mat(K.height_px, K.width_px, CV_32FC1, cv::Scalar(0.85f));
  return f;
}

void BM_SensorModel(benchmark::State& state) {
  const auto scene = defaultScene();
  srp::synth::SensorModel sensor({}, 1);
  const cv::Mat hand(scene.intrinsics.height_px, scene.intrinsics.width_px, CV_8UC1, cv::Scalar(0));
  for (auto _ : state) {
    auto f = flatFrame(scene.intrinsics);
    sensor.apply(f, hand, 0.3, cv::Mat(), cv::Mat(), 0.0, cv::Mat());
    benchmark::DoNotOptimize(f.depth_m.data);
  }
}
BENCHMARK(BM_SensorModel)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_RawlogWriteNoisyFrame(benchmark::State& state) {
  const auto scene = defaultScene();
  srp::synth::SensorModel sensor({}, 1);
  auto f = flatFrame(scene.intrinsics);
  sensor.apply(f, cv::Mat(), 0.0, cv::Mat(), cv::Mat(), 0.0, cv::Mat());
  const std::string path = tempPath("write.rawlog");
  srp::rawlog::RawlogWriter writer(path, 1e-3);
  for (auto _ : state) writer.write(f);
  writer.close();
  state.counters["MB_per_frame"] = std::filesystem::file_size(path) / 1e6 / state.iterations();
}
BENCHMARK(BM_RawlogWriteNoisyFrame)->Unit(benchmark::kMillisecond)->UseRealTime();

// The whole generator on the first 90 frames (3 s) of the bundled default demo.
void BM_SynthDemoPipeline(benchmark::State& state) {
  const auto scene = defaultScene();
  const auto catalogue = srp::kb::loadCatalogue(scene.cataloguePath);
  srp::synth::SynthDemoOptions options;
  options.maxFrames = 90;
  options.demo.idleStart_s = 0.2;  // hand in view for most of the measured frames
  options.sensor.enabled = state.range(0) != 0;
  const std::string path = tempPath("pipeline.rawlog");
  double frames = 0.0, bytes = 0.0, renderCpu = 0.0, sensorCpu = 0.0, writeCpu = 0.0, allCpu = 0.0;
  for (auto _ : state) {
    const auto r = srp::synth::generateSyntheticDemo(scene, catalogue, srp::synth::defaultPlanJson(), options, path);
    frames += r.frameCount;
    bytes += static_cast<double>(std::filesystem::file_size(path));
    renderCpu += r.renderCpuTime_s;
    sensorCpu += r.sensorCpuTime_s;
    writeCpu += r.writeCpuTime_s;
    allCpu += r.processCpuTime_s;
  }
  // Wall rate depends on the machine's load; CPU per frame does not (much).
  state.counters["frames_per_s"] = benchmark::Counter(frames, benchmark::Counter::kIsRate);
  state.counters["rawlog_MB_per_min"] = bytes / 1e6 / (frames / scene.fps / 60.0);
  state.counters["cpu_render_ms"] = 1e3 * renderCpu / frames;
  state.counters["cpu_sensor_ms"] = 1e3 * sensorCpu / frames;
  state.counters["cpu_write_ms"] = 1e3 * writeCpu / frames;
  state.counters["cpu_all_ms"] = 1e3 * allCpu / frames;
}
BENCHMARK(BM_SynthDemoPipeline)->Arg(1)->Arg(0)->ArgName("realism")->Unit(benchmark::kSecond)->UseRealTime()->Iterations(1);

}  // namespace

BENCHMARK_MAIN();
