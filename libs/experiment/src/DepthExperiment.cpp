// `srp experiment depth`: how much of the hand and the objects has valid depth
// under the sensor model, and how well the hand's depth is filled in where the
// depth image has holes (thesis section 8.3.3).
#include <algorithm>
#include <cmath>

#include "DemoAnalysis.h"
#include "srp/core/Error.h"
#include "srp/experiment/Experiments.h"
#include "srp/experiment/ExperimentSupport.h"
#include "srp/perception/MarkerHandDetector.h"
#include "srp/plot/Figure.h"
#include "srp/rawlog/RawlogReader.h"

namespace srp::experiment {
namespace {

/// Depth [m] at a pixel, 0 when outside the image or invalid.
float depthAt(const cv::Mat& depth_m, const Eigen::Vector2d& px)
{
  const int u = static_cast<int>(std::lround(px.x())), v = static_cast<int>(std::lround(px.y()));
  if (u < 0 || v < 0 || u >= depth_m.cols || v >= depth_m.rows) return 0.f;
  return depth_m.at<float>(v, u);
}

struct Stats
{
  std::vector<double> values;
  void add(double v) { values.push_back(v); }
  double quantile(double q) const
  {
    if (values.empty()) return NAN;
    std::vector<double> s = values;
    std::sort(s.begin(), s.end());
    return s[static_cast<size_t>(std::min<double>(s.size() - 1, std::floor(q * (s.size() - 1) + 0.5)))];
  }
  double mean() const
  {
    if (values.empty()) return NAN;
    double sum = 0;
    for (double v : values) sum += v;
    return sum / values.size();
  }
};

struct Fraction
{
  int hits = 0, total = 0;
  void add(bool hit)
  {
    hits += hit;
    ++total;
  }
  double value() const { return total ? static_cast<double>(hits) / total : NAN; }
};

/// One demo's share of valid depth on the hand and the objects.
struct DemoDepth {
  Fraction handSamples, objectSamples;
  Stats handPixels, objectPixels;
};

/// Errors of the hand's depth [m] (|z - z_true| of the palm centre) by source, over every demo,
/// and demo 1's depth over time for the figure.
struct HandDepthErrors {
  Stats tagOnly, tagRefined, tagUnrefined, carried, rawPalm;
  std::vector<double> plotT, plotTruth, plotFilled, plotRaw;
};

/// Reads demo `d` frame by frame: valid depth at the hand's and the objects' pixels, and the
/// hand's depth from the tag alone, tag + depth, and carried forward (added to `errors`; the
/// plot series only for demo 0).
DemoDepth measureDemo(const ExperimentOptions& options, const CachedDemo& demo, const synth::DemoGroundTruth& gt, int d,
                      int count, const std::string& label, HandDepthErrors& errors) {
  perception::MarkerHandDetector::Options withDepth, tagAlone;
  withDepth.tagSize_m = tagAlone.tagSize_m = gt.tagSize_m;
  withDepth.tagId = tagAlone.tagId = gt.tagId;
  tagAlone.useDepth = false;
  perception::MarkerHandDetector detector(withDepth), detectorTagAlone(tagAlone);

  DemoDepth out;
  std::optional<double> lastRefinedZ;
  rawlog::RawlogReader reader(demo.rawlogPath.string());
  while (auto f = reader.next()) {
    if (f->index % 60 == 0)
      reportProgress(options, label + " frame " + std::to_string(f->index) + "/" + std::to_string(gt.frames.size()),
                     (d + 0.5 + 0.5 * f->index / std::max<double>(1.0, gt.frames.size())) / count);
    if (f->index < 0 || f->index >= static_cast<int>(gt.frames.size())) continue;
    const auto& truth = gt.frames[static_cast<size_t>(f->index)];
    if (truth.handValidDepthFraction) out.handPixels.add(*truth.handValidDepthFraction);
    if (truth.objectsValidDepthFraction) out.objectPixels.add(*truth.objectsValidDepthFraction);
    // Every object's centre pixel (the thesis read depth at the detected box centre).
    for (const auto& o : gt.objects) {
      if (o.id == truth.carriedObject) continue;  // in the hand: counted with the hand's blur
      const Eigen::Vector3d p = gt.X_camera_object(f->index, o.id).translation();
      if (const auto px = gt.intrinsics.project(p)) out.objectSamples.add(depthAt(f->depth_m, *px) > 0.f);
    }
    if (!truth.handInView) continue;
    const Eigen::Vector3d pTrue = truth.p_camera_palm_m;
    const auto palmPx = gt.intrinsics.project(pTrue);
    if (palmPx) {
      const float z = depthAt(f->depth_m, *palmPx);
      out.handSamples.add(z > 0.f);
      // The camera sees the back of the hand, not the palm centre: compare
      // the raw depth only where it is on the hand (within 5 cm).
      if (z > 0.f && std::abs(z - pTrue.z()) < 0.05) errors.rawPalm.add(std::abs(z - pTrue.z()));
    }
    if (!truth.tagInView) continue;
    const auto h = detector.detect(*f);
    const auto a = detectorTagAlone.detect(*f);
    if (!h || !a) continue;
    errors.tagOnly.add(std::abs(a->p_camera_palm_m.z() - pTrue.z()));
    const bool refined = std::abs(h->p_camera_palm_m.z() - a->p_camera_palm_m.z()) > 1e-9;
    if (refined) {
      errors.tagRefined.add(std::abs(h->p_camera_palm_m.z() - pTrue.z()));
      lastRefinedZ = h->p_camera_palm_m.z();
    } else {
      errors.tagUnrefined.add(std::abs(h->p_camera_palm_m.z() - pTrue.z()));
      // The thesis' and the marker-free detector's fill-in: the last valid depth carried forward.
      if (lastRefinedZ) errors.carried.add(std::abs(*lastRefinedZ - pTrue.z()));
    }
    if (d == 0) {
      errors.plotT.push_back(truth.t_s);
      errors.plotTruth.push_back(pTrue.z());
      errors.plotFilled.push_back(h->p_camera_palm_m.z());
      errors.plotRaw.push_back(palmPx ? depthAt(f->depth_m, *palmPx) : 0.0);
    }
  }
  if (reader.damage())
    throw core::FileError(demo.rawlogPath.string(),
                          "damaged demo rawlog (" + *reader.damage() + "); delete the demo cache folder and run again");
  return out;
}

/// The table of the hand's depth error by source (and its metrics).
ResultTable handDepthErrorTable(const HandDepthErrors& e, ExperimentResult& result) {
  ResultTable fill;
  fill.title = "Section 8.3.3: error of the hand's depth (palm centre, |z - z_true|) by source";
  fill.columns = {"source", "frames", "median [mm]", "p95 [mm]", "thesis"};
  const auto row = [&](const std::string& source, const Stats& s, const std::string& thesis, const std::string& key) {
    fill.rows.push_back({source, std::to_string(s.values.size()), formatNumber(1e3 * s.quantile(0.5), 1),
                         formatNumber(1e3 * s.quantile(0.95), 1), thesis});
    result.metrics["hand_depth_error_m"][key] = {
        {"frames", s.values.size()}, {"median", s.quantile(0.5)}, {"p95", s.quantile(0.95)}};
  };
  row("tag pose alone (all tag frames)", e.tagOnly, "—", "tag_only");
  row("tag + median depth inside the tag (frames with valid depth there; perception's default)", e.tagRefined, "—",
      "tag_refined");
  row("tag pose where the tag's depth is invalid (perception's default fill-in)", e.tagUnrefined,
      "< 10 mm (monocular depth network vs valid camera depth)", "tag_unrefined");
  row("last valid depth carried forward (thesis' fallback; marker-free detector)", e.carried, "—", "carried_forward");
  row("raw depth at the palm pixel, where valid (back of the hand)", e.rawPalm, "—", "raw_palm_pixel");
  fill.note =
      "Truth: the renderer's palm centre. The tag gives the palm's depth from the tag's size wherever the tag "
      "is readable, so a depth hole needs no network; the raw pixel sees the back of the hand, ~1.4 cm above "
      "the palm centre.";
  return fill;
}

/// Demo 1's hand depth over time (truth, perception, raw pixel) as `<dir>/hand_depth.png`.
std::filesystem::path handDepthFigure(const HandDepthErrors& e, unsigned seed, const std::filesystem::path& dir) {
  plot::Figure fig(1000, 420);
  fig.title = "Hand depth, demo seed " + std::to_string(seed);
  auto& ax = fig.axes();
  ax.xLabel = "t [s]";
  ax.yLabel = "z [m]";
  std::vector<double> tRaw, zRaw;
  for (size_t i = 0; i < e.plotT.size(); ++i)
    if (e.plotRaw[i] > 0) tRaw.push_back(e.plotT[i]), zRaw.push_back(e.plotRaw[i]);
  ax.scatter(tRaw, zRaw, "raw depth at the palm pixel (valid only)", plot::Colour::gray(), plot::Marker::Cross, 3.0);
  ax.line(e.plotT, e.plotTruth, "truth (palm centre)", plot::Colour{0, 0, 0});
  ax.line(e.plotT, e.plotFilled, "perception (tag + depth)", plot::Colour::tab(0), 1.5, true);
  const auto png = dir / "hand_depth.png";
  fig.save(png.string());
  return png;
}

}  // namespace

ExperimentResult runDepthExperiment(const ExperimentOptions& options)
{
  const WallClock clock;
  ExperimentResult result;
  result.name = "depth";
  const auto dir = experimentDirOf(options, result.name);
  const int count = demoCountOf(options);
  const DemoCache cache = demoCacheFor(options);

  ResultTable valid;
  valid.title = "Section 8.3.3: valid depth on the hand and the objects (default sensor model)";
  valid.columns = {"demo (seed)", "frames", "hand pixels valid", "hand samples valid (palm pixel)", "object pixels valid",
                   "object samples valid (centre pixel)"};
  Fraction handSamplesAll, objectSamplesAll;
  Stats handPixelsAll, objectPixelsAll;
  HandDepthErrors errors;

  for (int d = 0; d < count; ++d) {
    const DemoRequest request = standardDemoRequest(options, d);
    const std::string label = "depth: demo " + std::to_string(d + 1) + "/" + std::to_string(count) + " (seed " +
                              std::to_string(request.seed) + ")";
    const CachedDemo demo = cache.get(request, [&](int k, int n) {
      if (k % 50 == 0) reportProgress(options, label + " render " + std::to_string(k) + "/" + std::to_string(n), (d + 0.5 * k / n) / count);
    });
    const auto gt = synth::DemoGroundTruth::load(demo.groundTruthPath.string());
    const DemoDepth m = measureDemo(options, demo, gt, d, count, label, errors);
    valid.rows.push_back({std::to_string(d + 1) + " (" + std::to_string(request.seed) + ")",
                          std::to_string(gt.frames.size()), formatPercent(m.handPixels.mean()),
                          formatPercent(m.handSamples.value()), formatPercent(m.objectPixels.mean()),
                          formatPercent(m.objectSamples.value())});
    result.metrics["demos"].push_back({{"seed", request.seed},
                                       {"hand_pixels_valid", m.handPixels.mean()},
                                       {"hand_samples_valid", m.handSamples.value()},
                                       {"object_pixels_valid", m.objectPixels.mean()},
                                       {"object_samples_valid", m.objectSamples.value()}});
    handSamplesAll.hits += m.handSamples.hits;
    handSamplesAll.total += m.handSamples.total;
    objectSamplesAll.hits += m.objectSamples.hits;
    objectSamplesAll.total += m.objectSamples.total;
    for (double v : m.handPixels.values) handPixelsAll.add(v);
    for (double v : m.objectPixels.values) objectPixelsAll.add(v);
  }
  valid.rows.push_back({"all", "—", formatPercent(handPixelsAll.mean()), formatPercent(handSamplesAll.value()),
                        formatPercent(objectPixelsAll.mean()), formatPercent(objectSamplesAll.value())});
  valid.rows.push_back({"thesis (L515, 5 videos)", "—", "—", "< 50 %", "—", "> 70 %"});
  valid.note = "Pixels: mean over frames of the share of visible hand / part pixels with valid depth (the renderer's "
               "masks); samples: share of frames whose depth at the palm centre / object centre pixel is valid, as a "
               "trajectory reads it. Thesis section 8.3.3 (ToF motion blur on the moving hand).";
  result.tables.push_back(valid);
  result.metrics["all"] = {{"hand_pixels_valid", handPixelsAll.mean()},
                           {"hand_samples_valid", handSamplesAll.value()},
                           {"object_pixels_valid", objectPixelsAll.mean()},
                           {"object_samples_valid", objectSamplesAll.value()}};
  result.tables.push_back(handDepthErrorTable(errors, result));
  if (!errors.plotT.empty())
    result.figures.push_back(handDepthFigure(errors, standardDemoRequest(options, 0).seed, dir));

  result.summary = "Valid depth on the hand " + formatPercent(handSamplesAll.value()) + " of samples (" +
                   formatPercent(handPixelsAll.mean()) + " of pixels), on objects " +
                   formatPercent(objectSamplesAll.value()) +
                   " (thesis: < 50 %, > 70 %); the hand's depth where the "
                   "image has a hole: median error " +
                   formatNumber(1e3 * errors.tagUnrefined.quantile(0.5), 1) + " mm from the tag, " +
                   formatNumber(1e3 * errors.carried.quantile(0.5), 1) + " mm carried forward.";
  result.wallTime_s = clock.seconds();
  return result;
}

}  // namespace srp::experiment
