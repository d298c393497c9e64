// Notebook: the hand trajectory of a demonstration (thesis fig. 8.3)
// ===================================================================
//
// What the figure shows
//   Thesis fig. 8.3 plots the palm's x, y, z in the camera frame over a
//   demonstration, as Faster-RCNN detections plus depth gave them; the depth z
//   varies most, because the hand moves towards and away from the camera.
//   Here the demonstration is synthetic (srp::synth: the thesis' scene, the
//   first step of instruction 1 - the cuboid from the blue box into the gray
//   box - rendered as RGB-D frames with the sensor model's noise and depth
//   holes), the hand is found by the AprilTag on the glove
//   (srp::perception::MarkerHandDetector), and, unlike the thesis, we know the
//   truth, so the figure puts the two side by side:
//     top left   palm x, y, z over time: lines = ground truth, dots = detected;
//                dashed lines at the grasp and release frames (ground truth);
//     top right  the path seen from the camera (x, y), grasp and release marked;
//     bottom left the 3D error of each detection [mm], the demo's phases shaded;
//     bottom right the share of valid depth pixels on the hand per frame: low,
//                as on the thesis' L515 (section 8.3.3); the tag's size still
//                gives the palm's distance.
//
// Output (folder = first argument, default out/notebooks/hand_trajectory)
//   hand_trajectory.png (copied to notebooks_cpp/hand_trajectory/figure.png),
//   hand_trajectory.txt (the numbers below), demo.gt.json (the rawlog is deleted
//   after use: ~100 MB).
//
// Run
//   cmake --build build --target notebook_hand_trajectory
//   build/notebooks_cpp/notebook_hand_trajectory [out_dir]
//   (CTest: ctest --test-dir build -R notebook.hand_trajectory; 12 s of CPU, ~50 s
//   wall on the shared 2-core machine under load.)
//
// Checks (exit 1 otherwise): the tag is detected in >= 95 % of the frames
// where it is readable, the median palm error is below 5 mm, and no hand is
// reported in a frame without one.

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "../common/Notebook.h"
#include "srp/core/Error.h"
#include "srp/core/Scene.h"
#include "srp/kb/KnowledgeBase.h"
#include "srp/perception/MarkerHandDetector.h"
#include "srp/plot/Figure.h"
#include "srp/rawlog/RawlogReader.h"
#include "srp/synth/DemoGenerator.h"
#include "srp/synth/PickPlacePlan.h"

namespace {

using srp::plot::Colour;
using srp::plot::Marker;

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<std::size_t>(p * static_cast<double>(v.size())))];
}

// Colours of the demo's phases (the ground truth's names).
Colour phaseColour(const std::string& phase) {
  if (phase == "reach") return Colour::tab(0);
  if (phase == "grasp") return Colour::tab(3);
  if (phase == "move") return Colour::tab(2);
  if (phase == "release") return Colour::tab(4);
  return Colour::gray();  // idle, retract
}

int run(int argc, char** argv) {
  const std::filesystem::path out = srp::notebook::outputFolder(argc, argv, "hand_trajectory");

  // Step 1: a short demonstration. The thesis' scene (sim/scenes/default.json)
  // and the first step of instruction 1: one pick & place, about 9 s at
  // 30 FPS. The sensor model is on: depth noise and, as on the thesis' L515,
  // depth holes on the moving hand.
  const auto scene = srp::core::Scene::load(std::string(SRP_SIM_DIR) + "/scenes/default.json");
  const auto catalogue = srp::kb::loadCatalogue(scene.cataloguePath);
  nlohmann::json plan = srp::synth::defaultPlanJson();
  plan["steps"] = nlohmann::json::array({plan["steps"][0]});  // the cuboid only

  srp::synth::SynthDemoOptions demoOptions;
  demoOptions.demo.seed = static_cast<std::uint32_t>(scene.seed);
  const std::string rawlogPath = (out / "demo.rawlog").string();
  std::cerr << "rendering the demonstration ...\n";
  const auto demo = srp::synth::generateSyntheticDemo(scene, catalogue, plan, demoOptions, rawlogPath);
  const auto truth = srp::synth::DemoGroundTruth::load(demo.groundTruthPath);

  // Step 2: detect the hand in every frame. The glove's tag (tag36h11 id 0,
  // 5 cm) gives the palm centre 13.6 mm under the tag, in 3D from the tag's
  // size even where the depth image has a hole; the ground truth file states
  // the glove's geometry, so we configure the detector from it.
  srp::perception::MarkerHandDetector::Options markerOptions;
  markerOptions.tagSize_m = truth.tagSize_m;
  markerOptions.tagId = truth.tagId;
  markerOptions.p_tag_palm_m = truth.X_hand_tag.inverse().translation();
  srp::perception::MarkerHandDetector detector(markerOptions);

  std::vector<std::optional<Eigen::Vector3d>> detected;
  {
    srp::rawlog::RawlogReader reader(rawlogPath);
    while (auto frame = reader.next()) {
      const auto hand = detector.detect(*frame);
      detected.push_back(hand ? std::optional<Eigen::Vector3d>(hand->p_camera_palm_m) : std::nullopt);
    }
  }
  std::filesystem::remove(rawlogPath);  // ~100 MB of noisy images; the ground truth stays

  // Step 3: compare with the truth, frame by frame.
  std::vector<double> t_s, tx, ty, tz;                       // ground truth, frames with the hand in view
  std::vector<double> dt_s, dx, dy, dz, error_mm;  // detections and their errors
  int handFrames = 0, tagFrames = 0, foundOfTag = 0, falseDetections = 0;
  for (std::size_t i = 0; i < truth.frames.size() && i < detected.size(); ++i) {
    const auto& f = truth.frames[i];
    if (f.handInView) {
      ++handFrames;
      t_s.push_back(f.t_s);
      tx.push_back(f.p_camera_palm_m.x()), ty.push_back(f.p_camera_palm_m.y()), tz.push_back(f.p_camera_palm_m.z());
    }
    if (f.tagInView) ++tagFrames;
    if (!detected[i]) continue;
    if (!f.handInView) ++falseDetections;
    if (f.tagInView) ++foundOfTag;
    const Eigen::Vector3d& p = *detected[i];
    dt_s.push_back(f.t_s);
    dx.push_back(p.x()), dy.push_back(p.y()), dz.push_back(p.z());
    error_mm.push_back(1e3 * (p - f.p_camera_palm_m).norm());
  }
  const auto& event = truth.events.at(0);
  const double graspT_s = truth.frames.at(event.graspFrame).t_s, releaseT_s = truth.frames.at(event.releaseFrame).t_s;
  const auto range = [](const std::vector<double>& v) {
    return v.empty() ? 0.0 : *std::max_element(v.begin(), v.end()) - *std::min_element(v.begin(), v.end());
  };
  const double rate = tagFrames > 0 ? static_cast<double>(foundOfTag) / tagFrames : 0.0;
  const double median_mm = percentile(error_mm, 0.5), p95_mm = percentile(error_mm, 0.95);
  double validDepthSum = 0.0;
  int validDepthFrames = 0;
  for (const auto& f : truth.frames)
    if (f.handValidDepthFraction) validDepthSum += *f.handValidDepthFraction, ++validDepthFrames;
  const double meanHandValidDepth = validDepthFrames > 0 ? validDepthSum / validDepthFrames : 0.0;

  // Step 4: the numbers, as text.
  char text[1024];
  std::snprintf(text, sizeof text,
                "demo: %zu frames at %.0f FPS (%.1f s), %dx%d, seed %u, cuboid from the blue box into the gray box\n"
                "hand in view in %d frames, tag readable in %d, detected in %d of those (%.1f %%), "
                "%d detections in frames without a hand\n"
                "palm error (3D, detected vs truth): median %.1f mm, p95 %.1f mm, max %.1f mm over %zu detections\n"
                "grasp at frame %d (t = %.2f s), release at frame %d (t = %.2f s) (ground truth events)\n"
                "range of the palm in the camera frame: x %.0f mm, y %.0f mm, z %.0f mm\n"
                "valid depth on the visible hand: %.1f %% of its pixels (frame mean; thesis: below 50 %%)\n",
                truth.frames.size(), truth.fps, truth.frames.size() / truth.fps, truth.intrinsics.width_px,
                truth.intrinsics.height_px, truth.seed, handFrames, tagFrames, foundOfTag, 100.0 * rate,
                falseDetections, median_mm, p95_mm,
                error_mm.empty() ? 0.0 : *std::max_element(error_mm.begin(), error_mm.end()), error_mm.size(),
                event.graspFrame, graspT_s, event.releaseFrame, releaseT_s, 1e3 * range(tx), 1e3 * range(ty),
                1e3 * range(tz), 100.0 * meanHandValidDepth);
  std::cout << text;
  std::ofstream(out / "hand_trajectory.txt") << text;

  // Step 5: the figure.
  srp::plot::Figure fig(1500, 1000, 2, 2);
  fig.title = "Hand (palm centre) trajectory of a synthetic demo: AprilTag glove detections vs ground truth";
  {
    auto& ax = fig.axes(0, 0);
    ax.title = "Palm position in the camera frame (cf. thesis fig. 8.3)";
    ax.xLabel = "t [s]";
    ax.yLabel = "position [m]";
    const char* names[] = {"x", "y", "z"};
    const std::vector<double>* truthCols[] = {&tx, &ty, &tz};
    const std::vector<double>* detCols[] = {&dx, &dy, &dz};
    for (int d = 0; d < 3; ++d) {
      ax.line(t_s, *truthCols[d], std::string(names[d]) + " truth", Colour::tab(d), 1.5);
      ax.scatter(dt_s, *detCols[d], std::string(names[d]) + " detected", Colour::tab(d), Marker::Circle, 2.5);
    }
    ax.verticalLine(graspT_s, "grasp", Colour{0, 0, 0});
    ax.verticalLine(releaseT_s, "release", Colour{0, 0, 0});
  }
  {
    auto& ax = fig.axes(0, 1);
    ax.title = "Seen from the camera (x right, y down in the image)";
    ax.xLabel = "x [m]";
    ax.yLabel = "y [m]";
    ax.equalAspect = true;
    ax.line(tx, ty, "truth", Colour::gray(), 1.5);
    ax.scatter(dx, dy, "detected", Colour::tab(0), Marker::Circle, 2.5);
    const auto at = [&](int frame) { return truth.frames.at(frame).p_camera_palm_m; };
    ax.scatter({at(event.graspFrame).x()}, {at(event.graspFrame).y()}, "grasp", Colour::tab(3), Marker::Cross, 8);
    ax.scatter({at(event.releaseFrame).x()}, {at(event.releaseFrame).y()}, "release", Colour::tab(2), Marker::Cross, 8);
  }
  {
    auto& ax = fig.axes(1, 0);
    ax.title = "3D error of the detected palm, the demo's phases shaded";
    ax.xLabel = "t [s]";
    ax.yLabel = "error [mm]";
    // One band per run of frames in the same phase; each phase named once in the legend.
    std::vector<std::string> named;
    for (std::size_t i = 0; i < truth.frames.size();) {
      std::size_t j = i;
      while (j + 1 < truth.frames.size() && truth.frames[j + 1].phase == truth.frames[i].phase) ++j;
      const std::string& phase = truth.frames[i].phase;
      const bool first = std::find(named.begin(), named.end(), phase) == named.end();
      if (phase != "idle") {
        ax.band(truth.frames[i].t_s, truth.frames[j].t_s + 1.0 / truth.fps, first ? phase : "", phaseColour(phase), 0.18);
        if (first) named.push_back(phase);
      }
      i = j + 1;
    }
    ax.scatter(dt_s, error_mm, "", Colour{0, 0, 0}, Marker::Circle, 2.0);
    ax.horizontalLine(median_mm, "median", Colour::tab(3));
  }
  {
    // The thesis (section 8.3.3) found valid camera depth on fewer than half of
    // the hand samples; the sensor model reproduces that. The tag's size gives
    // the palm's distance where the depth image has a hole.
    auto& ax = fig.axes(1, 1);
    ax.title = "Valid depth pixels on the visible hand (sensor model)";
    ax.xLabel = "t [s]";
    ax.yLabel = "valid depth [%]";
    ax.yLimits = std::make_pair(0.0, 105.0);
    std::vector<double> t, valid;
    for (const auto& f : truth.frames)
      if (f.handValidDepthFraction) t.push_back(f.t_s), valid.push_back(100.0 * *f.handValidDepthFraction);
    ax.scatter(t, valid, "per frame", Colour::tab(4), Marker::Circle, 2.5);
    ax.horizontalLine(100.0 * meanHandValidDepth, "mean", Colour::tab(3));
  }
  const std::filesystem::path png = out / "hand_trajectory.png";
  fig.save(png.string());
  std::cout << "wrote " << png.string() << "\n";

  // Step 6: the checks that keep this page honest.
  srp::notebook::Checks checks;
  constexpr double kMinDetectionRate = 0.95, kMaxMedianError_mm = 5.0;
  checks.pngWritten(png);
  checks.require(detected.size() == truth.frames.size(), "one detection result per ground-truth frame");
  checks.require(tagFrames > 30, "the tag is readable in more than 30 frames");
  checks.require(rate >= kMinDetectionRate, "tag detected in >= 95 % of the frames where it is readable");
  checks.require(median_mm < kMaxMedianError_mm, "median palm error below 5 mm");
  checks.require(falseDetections == 0, "no hand reported in a frame without a hand");
  return checks.exitCode();
}

}  // namespace

int main(int argc, char** argv) { return srp::notebook::run("hand_trajectory", argc, argv, run); }
