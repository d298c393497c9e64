// `srp experiment hand`: thesis table 8.2 on seeded synthetic demos, for both
// hand detectors of the Environment module, plus the 3D palm error the thesis
// could not measure (it had no ground truth).
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>

#include "PerceptionStudy.h"
#include "srp/experiment/Experiments.h"
#include "srp/plot/Figure.h"

namespace srp::experiment {

namespace {

/// Thesis table 8.2: % of hand-visible frames detected per recorded video.
constexpr std::array<double, 5> kThesisFasterRcnn{1.0000, 0.9576, 0.9982, 0.9259, 0.9167};
constexpr std::array<double, 5> kThesisMediaPipe{0.9399, 0.0886, 0.1574, 0.0994, 0.1250};

struct DetectorCounts
{
  int handFrames = 0;     ///< ground truth: some hand pixel visible
  int tagFrames = 0;      ///< ground truth: the glove's tag readable
  int markerInHand = 0, markerInTag = 0, markerFreeInHand = 0;
  int handFreeFrames = 0, markerFalse = 0, markerFreeFalse = 0;  ///< hand reported where there is none
  std::vector<double> markerError_m, markerFreeError_m;
};

double ratio(int n, int d) { return d > 0 ? static_cast<double>(n) / d : std::nan(""); }

DetectorCounts countDemo(const detail::PerceivedDemo& demo)
{
  DetectorCounts c;
  for (int i = 0; i < demo.frames; ++i) {
    const auto& truth = demo.groundTruth.frames[static_cast<std::size_t>(i)];
    const auto& marker = demo.marker[static_cast<std::size_t>(i)];
    const auto& markerFree = demo.markerFree[static_cast<std::size_t>(i)];
    if (!truth.handInView) {
      ++c.handFreeFrames;
      c.markerFalse += marker.detected;
      c.markerFreeFalse += markerFree.detected;
      continue;
    }
    ++c.handFrames;
    c.markerInHand += marker.detected;
    c.markerFreeInHand += markerFree.detected;
    if (truth.tagInView) {
      ++c.tagFrames;
      c.markerInTag += marker.detected;
    }
    if (marker.hasPoint) c.markerError_m.push_back((marker.p_camera_palm_m - truth.p_camera_palm_m).norm());
    if (markerFree.hasPoint) c.markerFreeError_m.push_back((markerFree.p_camera_palm_m - truth.p_camera_palm_m).norm());
  }
  return c;
}

void accumulate(DetectorCounts& total, const DetectorCounts& c)
{
  total.handFrames += c.handFrames;
  total.tagFrames += c.tagFrames;
  total.markerInHand += c.markerInHand;
  total.markerInTag += c.markerInTag;
  total.markerFreeInHand += c.markerFreeInHand;
  total.handFreeFrames += c.handFreeFrames;
  total.markerFalse += c.markerFalse;
  total.markerFreeFalse += c.markerFreeFalse;
  total.markerError_m.insert(total.markerError_m.end(), c.markerError_m.begin(), c.markerError_m.end());
  total.markerFreeError_m.insert(total.markerFreeError_m.end(), c.markerFreeError_m.begin(), c.markerFreeError_m.end());
}

nlohmann::json errorStats(const std::vector<double>& error_m)
{
  return {{"frames", error_m.size()},
          {"median_m", detail::percentile(error_m, 0.5)},
          {"p95_m", detail::percentile(error_m, 0.95)},
          {"max_m", detail::percentile(error_m, 1.0)}};
}

/// Empirical CDF of errors on a log10 [mm] axis.
void errorCdf(plot::Axes& axes, std::vector<double> error_m, const std::string& label, plot::Colour colour)
{
  if (error_m.empty()) return;
  std::sort(error_m.begin(), error_m.end());
  std::vector<double> x, y;
  for (std::size_t i = 0; i < error_m.size(); ++i) {
    x.push_back(std::log10(std::max(1e-3, 1e3 * error_m[i])));
    y.push_back(static_cast<double>(i + 1) / static_cast<double>(error_m.size()));
  }
  axes.line(x, y, label, colour);
}

/// The 3D palm error of both detectors against ground truth, over all demos.
ResultTable palmErrorTable(const DetectorCounts& total)
{
  ResultTable error;
  error.title = "Hand: 3D palm error against ground truth (camera frame)";
  error.columns = {"Detector", "Frames with a 3D palm", "Median [mm]", "p95 [mm]", "Max [mm]",
                   "False detections (hand-free frames)", "Thesis"};
  error.note =
      "Error = distance of the reported palm centre to the true one, over hand-visible frames with a 3D "
      "point (depth holes filled as the module does: the last depth carried along the palm pixel's ray). "
      "The thesis had no ground truth for the hand (only depth validity, section 8.3.3). Targets: "
      "median <= 5 mm, p95 <= 15 mm for the marker and median <= 15 mm for the marker-free detector.";
  auto errorRow = [&](const std::string& name, const std::vector<double>& e, int falseDetections) {
    error.rows.push_back({name, std::to_string(e.size()), formatNumber(1e3 * detail::percentile(e, 0.5), 1),
                          formatNumber(1e3 * detail::percentile(e, 0.95), 1), formatNumber(1e3 * detail::percentile(e, 1.0), 1),
                          std::to_string(falseDetections) + " / " + std::to_string(total.handFreeFrames), "—"});
  };
  errorRow("Marker (AprilTag glove)", total.markerError_m, total.markerFalse);
  errorRow("Marker-free (depth foreground + skin)", total.markerFreeError_m, total.markerFreeFalse);
  return error;
}

/// Figure: per-demo detection rates beside the thesis, and the error CDFs (hand/hand_detection.png).
std::filesystem::path handFigure(const ExperimentOptions& options, const detail::PerceptionStudySize& size,
                                 std::size_t demoCount, const std::vector<double>& markerRates,
                                 const std::vector<double>& markerFreeRates, const DetectorCounts& total)
{
  const std::filesystem::path dir = options.outDir / "hand";
  std::filesystem::create_directories(dir);
  plot::Figure figure(1200, 500, 1, 2);
  figure.title = "Hand detection: " + std::to_string(size.demoCount) + " synthetic demo(s) x first " +
                 std::to_string(size.framesPerDemo) + " frames, 640x480";
  auto& bars = figure.axes(0, 0);
  bars.title = "Hand-visible frames detected";
  bars.xLabel = "demo";
  bars.yLabel = "detected [%]";
  bars.yLimits = std::make_pair(0.0, 130.0);  // room for the legend above the bars
  bars.xLimits = std::make_pair(0.4, demoCount + 0.6);
  for (std::size_t k = 0; k < demoCount; ++k) {
    const double x = static_cast<double>(k + 1);
    // Bars as thick vertical segments; the legend entry once per series.
    bars.line({x - 0.15, x - 0.15}, {0.0, 100.0 * markerRates[k]}, k == 0 ? "ours: marker" : "", plot::Colour::tab(0), 18.0);
    bars.line({x + 0.15, x + 0.15}, {0.0, 100.0 * markerFreeRates[k]}, k == 0 ? "ours: marker-free" : "",
              plot::Colour::tab(1), 18.0);
  }
  std::vector<double> thesisX, thesisFaster, thesisMp;
  for (std::size_t k = 0; k < demoCount && k < kThesisFasterRcnn.size(); ++k) {
    thesisX.push_back(static_cast<double>(k + 1));
    thesisFaster.push_back(100.0 * kThesisFasterRcnn[k]);
    thesisMp.push_back(100.0 * kThesisMediaPipe[k]);
  }
  bars.scatter(thesisX, thesisFaster, "thesis: Faster-RCNN", plot::Colour::tab(2), plot::Marker::Triangle, 7.0);
  bars.scatter(thesisX, thesisMp, "thesis: MediaPipe", plot::Colour::tab(3), plot::Marker::Cross, 7.0);
  auto& cdf = figure.axes(0, 1);
  cdf.title = "3D palm error, cumulative";
  cdf.xLabel = "log10(error [mm])";
  cdf.yLabel = "fraction of frames";
  cdf.yLimits = std::make_pair(0.0, 1.02);
  errorCdf(cdf, total.markerError_m, "marker", plot::Colour::tab(0));
  errorCdf(cdf, total.markerFreeError_m, "marker-free", plot::Colour::tab(1));
  cdf.verticalLine(std::log10(15.0), "15 mm", plot::Colour::gray());
  const auto png = dir / "hand_detection.png";
  figure.save(png.string());
  return png;
}

/// One demo's counts, as the metrics' "demos" entry.
nlohmann::json demoMetrics(const detail::PerceivedDemo& demo, const DetectorCounts& c)
{
  return {{"seed", demo.seed},
          {"frames", demo.frames},
          {"hand_frames", c.handFrames},
          {"tag_frames", c.tagFrames},
          {"marker_detected", c.markerInHand},
          {"marker_rate", ratio(c.markerInHand, c.handFrames)},
          {"marker_tag_rate", ratio(c.markerInTag, c.tagFrames)},
          {"marker_free_detected", c.markerFreeInHand},
          {"marker_free_rate", ratio(c.markerFreeInHand, c.handFrames)},
          {"marker_false_detections", c.markerFalse},
          {"marker_free_false_detections", c.markerFreeFalse},
          {"perception_time_s", demo.perceptionTime_s}};
}

}  // namespace

ExperimentResult runHandExperiment(const ExperimentOptions& options)
{
  const auto start = std::chrono::steady_clock::now();
  const detail::PerceptionStudySize size = detail::studySize(options);
  const std::vector<detail::PerceivedDemo> demos = detail::perceivedDemos(options, "hand");

  ExperimentResult result;
  result.name = "hand";

  ResultTable detection;
  detection.title = "Table 8.2: hand detected (% of hand-visible frames)";
  detection.columns = {"Demo",          "Hand-visible frames", "Thesis Faster-RCNN", "Thesis MediaPipe",
                       "Ours: marker (AprilTag glove)", "Ours: marker-free", "Ours: marker, tag-readable frames"};
  detection.note =
      "Thesis: table 8.2, its five recorded videos (video k beside demo k; 3601 frames, 2631 with the hand). "
      "Ours: " +
      size.describe() +
      "; hand-visible = some hand pixel in the ground truth; tag-readable = the whole tag plate visible "
      "(the marker's target is set on these). Both detectors see the same frames.";

  DetectorCounts total;
  nlohmann::json perDemo = nlohmann::json::array();
  std::vector<double> markerRates, markerFreeRates;
  double perceptionTime_s = 0.0;
  int perceivedFrames = 0;
  for (std::size_t k = 0; k < demos.size(); ++k) {
    const auto& demo = demos[k];
    const DetectorCounts c = countDemo(demo);
    accumulate(total, c);
    perceptionTime_s += demo.perceptionTime_s;
    perceivedFrames += demo.frames;
    markerRates.push_back(ratio(c.markerInHand, c.handFrames));
    markerFreeRates.push_back(ratio(c.markerFreeInHand, c.handFrames));
    detection.rows.push_back({"Demo " + std::to_string(k + 1) + " (seed " + std::to_string(demo.seed) + ")",
                              std::to_string(c.handFrames),
                              k < kThesisFasterRcnn.size() ? formatPercent(kThesisFasterRcnn[k], 2) : "—",
                              k < kThesisMediaPipe.size() ? formatPercent(kThesisMediaPipe[k], 2) : "—",
                              formatPercent(markerRates.back(), 2), formatPercent(markerFreeRates.back(), 2),
                              formatPercent(ratio(c.markerInTag, c.tagFrames), 2)});
    perDemo.push_back(demoMetrics(demo, c));
  }
  detection.rows.push_back({"All", std::to_string(total.handFrames), "91.67–100 % (range)", "8.86–93.99 % (range)",
                            formatPercent(ratio(total.markerInHand, total.handFrames), 2),
                            formatPercent(ratio(total.markerFreeInHand, total.handFrames), 2),
                            formatPercent(ratio(total.markerInTag, total.tagFrames), 2)});

  const ResultTable error = palmErrorTable(total);
  result.tables = {detection, error};

  // Figure: per-demo detection rates beside the thesis, and the error CDFs.
  const auto png = handFigure(options, size, demos.size(), markerRates, markerFreeRates, total);
  result.figures.push_back(png);

  const double markerRate = ratio(total.markerInHand, total.handFrames);
  const double markerFreeRate = ratio(total.markerFreeInHand, total.handFrames);
  result.metrics = {{"demos", perDemo},
                    {"size", size.describe()},
                    {"frames_per_demo", size.framesPerDemo},
                    {"hand_frames", total.handFrames},
                    {"tag_frames", total.tagFrames},
                    {"marker_rate", markerRate},
                    {"marker_tag_rate", ratio(total.markerInTag, total.tagFrames)},
                    {"marker_free_rate", markerFreeRate},
                    {"hand_free_frames", total.handFreeFrames},
                    {"marker_false_detections", total.markerFalse},
                    {"marker_free_false_detections", total.markerFreeFalse},
                    {"marker_error", errorStats(total.markerError_m)},
                    {"marker_free_error", errorStats(total.markerFreeError_m)},
                    {"perception_frames_per_s", perceptionTime_s > 0 ? perceivedFrames / perceptionTime_s : std::nan("")},
                    {"thesis_faster_rcnn", kThesisFasterRcnn},
                    {"thesis_mediapipe", kThesisMediaPipe}};
  result.summary = "Hand detected in " + formatPercent(markerRate, 1) + " (AprilTag glove) and " +
                   formatPercent(markerFreeRate, 1) + " (marker-free) of " + std::to_string(total.handFrames) +
                   " hand-visible frames (thesis: Faster-RCNN 91.7–100 %, MediaPipe 8.9–94 %); palm error median " +
                   formatNumber(1e3 * detail::percentile(total.markerError_m, 0.5), 1) + " mm (p95 " +
                   formatNumber(1e3 * detail::percentile(total.markerError_m, 0.95), 1) + ") with the marker, " +
                   formatNumber(1e3 * detail::percentile(total.markerFreeError_m, 0.5), 1) + " mm (p95 " +
                   formatNumber(1e3 * detail::percentile(total.markerFreeError_m, 0.95), 1) +
                   ") marker-free. Size: " + size.describe() + ".";
  result.wallTime_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace srp::experiment
