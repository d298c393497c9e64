#pragma once
// The marker-free hand detector on a synthetic demo with ground truth
// (srp::synth): streams the rawlog through the detector (depth carried along
// the palm's ray in holes, as DemoPerceiver does) and compares the palm centre
// with the ground truth. Shared by MarkerFreeHandDetector_test and
// bench/marker_free_hand_bench.
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <functional>
#include <map>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <optional>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "srp/perception/MarkerFreeHandDetector.h"
#include "srp/rawlog/RawlogReader.h"
#include "srp/synth/DemoGenerator.h"
#include "srp/synth/DemoGroundTruth.h"

namespace srp::perception::testing {

/// Overrides of detector options by name, SRP_HAND_OPTIONS="name=value,name=value" (development: selection runs).
inline MarkerFreeHandDetector::Options optionsFromEnvironment() {
  MarkerFreeHandDetector::Options o;
  const char* env = std::getenv("SRP_HAND_OPTIONS");
  if (!env) return o;
  std::map<std::string, double*> d{{"skinMaxMahalanobis", &o.skinMaxMahalanobis},
                                   {"skinModeRadius", &o.skinModeRadius},
                                   {"palmFromFarEnd_m", &o.palmFromFarEnd_m},
                                   {"palmFromFarEndAlongRay_m", &o.palmFromFarEndAlongRay_m},
                                   {"palmFromFarEndAcrossRay_m", &o.palmFromFarEndAcrossRay_m},
                                   {"maxHandLength_m", &o.maxHandLength_m},
                                   {"minForeground_m", &o.minForeground_m},
                                   {"backgroundPercentile", &o.backgroundPercentile},
                                   {"movingBackgroundGap", &o.movingBackgroundGap},
                                   {"skinLumaModeRadius", &o.skinLumaModeRadius},
                                   {"bareForearmFraction", &o.bareForearmFraction},
                                   {"skinGrowMahalanobis", &o.skinGrowMahalanobis},
                                   {"skinLumaFloorFraction", &o.skinLumaFloorFraction},
                                   {"skinNoiseLuma", &o.skinNoiseLuma},
                                   {"maxPalmSpeed_mps", &o.maxPalmSpeed_mps},
                                   {"minSkinReach_m", &o.minSkinReach_m},
                                   {"minBackgroundValidFraction", &o.minBackgroundValidFraction},
                                   {"tiltInlier_m", &o.tiltInlier_m},
                                   {"maxWalkFactor", &o.maxWalkFactor},
                                   {"maxNormalFlatness", &o.maxNormalFlatness},
                                   {"minIslandSkinFraction", &o.minIslandSkinFraction},
                                   {"minFieldOfViewValid", &o.minFieldOfViewValid},
                                   {"movingBackgroundMargin", &o.movingBackgroundMargin},
                                   {"stillArmShapeShare", &o.stillArmShapeShare},
                                   {"palmHalfWidth_m", &o.palmHalfWidth_m},
                                   {"palmDepth_m", &o.palmDepth_m},
                                   {"minPalmCrossSections", &o.minPalmCrossSections},
                                   {"maxWristToPalm", &o.maxWristToPalm},
                                   {"skinGapClose_m", &o.skinGapClose_m},
                                   {"skinIlluminantNorm", &o.skinIlluminantNorm},
                                   {"skinMaxChromaPerLuma", &o.skinMaxChromaPerLuma}};
  std::map<std::string, int*> i{{"holeColourChange", &o.holeColourChange},
                                {"minWorkingWidth_px", &o.minWorkingWidth_px},
                                {"backgroundFillDiameter_px", &o.backgroundFillDiameter_px},
                                {"skinMinLuma", &o.skinMinLuma},
                                {"maxDepthLag_px", &o.maxDepthLag_px},
                                {"minLagColourChange", &o.minLagColourChange},
                                {"geodesicStep_px", &o.geodesicStep_px},
                                {"skinColourBlur_px", &o.skinColourBlur_px},
                                {"minTiltSamples", &o.minTiltSamples},
                                {"maxBandParallax_px", &o.maxBandParallax_px},
                                {"movingBackgroundSlack_px", &o.movingBackgroundSlack_px}};
  std::map<std::string, bool*> b{{"walkOnDepth", &o.walkOnDepth},
                                 {"palmAlongNormal", &o.palmAlongNormal},
                                 {"cuffTowardsThickest", &o.cuffTowardsThickest},
                                 {"farWithoutDepth", &o.farWithoutDepth},
                                 {"cuffFirst", &o.cuffFirst},
                                 {"stillArmFromPlane", &o.stillArmFromPlane},
                                 {"followCameraMotion", &o.followCameraMotion},
                                 {"enterThroughStillArm", &o.enterThroughStillArm},
                                 {"backgroundColourFromSurface", &o.backgroundColourFromSurface},
                                 {"cuffAtSleeveEdge", &o.cuffAtSleeveEdge},
                                 {"farEndOpenHand", &o.farEndOpenHand},
                                 {"skinFromArmOnly", &o.skinFromArmOnly},
                                 {"holesInPreview", &o.holesInPreview},
                                 {"handFirstAtTheBorder", &o.handFirstAtTheBorder}};
  std::stringstream ss(env);
  std::string item;
  while (std::getline(ss, item, ',')) {
    const auto eq = item.find('=');
    if (eq == std::string::npos) throw std::invalid_argument("SRP_HAND_OPTIONS: '" + item + "' is not name=value");
    const std::string name = item.substr(0, eq);
    const double value = std::stod(item.substr(eq + 1));
    if (d.count(name)) *d[name] = value;
    else if (i.count(name)) *i[name] = static_cast<int>(value);
    else if (b.count(name)) *b[name] = value != 0.0;
    else throw std::invalid_argument("SRP_HAND_OPTIONS: no option '" + name + "' here (see optionsFromEnvironment)");
  }
  return o;
}

inline double percentile(std::vector<double> v, double p) {
  if (v.empty()) return std::nan("");
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<std::size_t>(p * static_cast<double>(v.size())))];
}

struct HandEvaluation {
  int frames = 0;
  int handInView = 0;       ///< frames whose ground truth shows some of the hand or arm
  int handWithoutHand = 0;  ///< frames with a hand reported but none in view
  int depthCarried = 0;     ///< detections whose depth came from an earlier frame
  double detectCpu_s = 0.0;  ///< thread CPU time in detect() over the frames after the background ones
  int timedFrames = 0;
  std::vector<double> error_m;  ///< palm centre 3D error of every detection in a hand-in-view frame
  /// Image error of the same detections [px, scaled to a 640-px wide image].
  std::vector<double> error640_px;
  int carried = 0;  ///< hand-in-view frames with a part in the hand
  /// Of those, palms past the held part: beyond its origin (the centre of its bottom face) on the line from
  /// the true palm, (palm - true palm) . u > |part - true palm|, u the unit vector towards the part (3D).
  int farSide = 0;
  double worstFarSide_m = -1.0;  ///< the largest (palm - true palm) . u - |part - true palm| [m]
  std::map<std::string, std::vector<double>> errorByPhase_m;
  std::map<std::string, std::pair<int, int>> detectedByPhase;  ///< phase -> (detected, in view)

  double rate() const { return static_cast<double>(error_m.size()) / std::max(1, handInView); }
  /// Pools another evaluation's frames into this one.
  void add(const HandEvaluation& o) {
    frames += o.frames;
    handInView += o.handInView;
    handWithoutHand += o.handWithoutHand;
    depthCarried += o.depthCarried;
    detectCpu_s += o.detectCpu_s;
    timedFrames += o.timedFrames;
    error_m.insert(error_m.end(), o.error_m.begin(), o.error_m.end());
    error640_px.insert(error640_px.end(), o.error640_px.begin(), o.error640_px.end());
    for (const auto& [phase, e] : o.errorByPhase_m)
      errorByPhase_m[phase].insert(errorByPhase_m[phase].end(), e.begin(), e.end());
    for (const auto& [phase, n] : o.detectedByPhase) {
      detectedByPhase[phase].first += n.first;
      detectedByPhase[phase].second += n.second;
    }
    carried += o.carried;
    farSide += o.farSide;
    worstFarSide_m = std::max(worstFarSide_m, o.worstFarSide_m);
  }
  /// Share of the hand-in-view frames with a palm within `tol_px` (at 640-px width); a miss counts as outside.
  double within640(double tol_px) const {
    return static_cast<double>(
               std::count_if(error640_px.begin(), error640_px.end(), [&](double e) { return e <= tol_px; })) /
           std::max(1, handInView);
  }
  double median_m() const { return percentile(error_m, 0.5); }
  double p95_m() const { return percentile(error_m, 0.95); }

  void print(const std::string& what) const {
    std::printf("[ figures  ] marker-free hand, %s (%d frames): detected in %zu/%d frames with the hand in view "
                "(%.1f %%; %d with carried depth), palm error median %.1f mm, p95 %.1f mm, max %.1f mm; "
                "hand reported in %d frames without a hand; detect() %.1f ms CPU per frame\n",
                what.c_str(), frames, error_m.size(), handInView, 100.0 * rate(), depthCarried, 1e3 * median_m(),
                1e3 * p95_m(), 1e3 * percentile(error_m, 1.0), handWithoutHand,
                1e3 * detectCpu_s / std::max(1, timedFrames));
    std::printf(
        "[ figures  ]   within 40 px (640-px width) %.1f %%, image median %.1f px; palm past the held part in %d "
        "of %d carry frames (closest %.0f mm)\n",
        100.0 * within640(40.0), percentile(error640_px, 0.5), farSide, carried, 1e3 * worstFarSide_m);
    for (const auto& [phase, e] : errorByPhase_m)
      std::printf("[ figures  ]   %-8s detected %3d/%3d, median %5.1f mm, p95 %5.1f mm\n", phase.c_str(),
                  detectedByPhase.at(phase).first, detectedByPhase.at(phase).second, 1e3 * percentile(e, 0.5),
                  1e3 * percentile(e, 0.95));
    std::fflush(stdout);
  }
};

/// Writes the frame with the detector's last hand mask (green), entry point
/// (magenta), wrist and axis (cyan), palm (red +) and the true palm (white x).
inline void drawHandGeometry(const rawlog::RgbdFrame& f, const MarkerFreeHandDetector& d,
                             const synth::GroundTruthFrame& truth, const std::string& pngPath) {
  cv::Mat img = f.colour_bgr8.clone();
  if (!d.lastMask().empty()) {
    std::vector<std::vector<cv::Point>> contours;
    cv::findContours(d.lastMask().clone(), contours, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_NONE);
    cv::drawContours(img, contours, -1, cv::Scalar(0, 255, 0), 1);
  }
  const auto& g = d.lastGeometry();
  auto pt = [](const Eigen::Vector2d& p) { return cv::Point(static_cast<int>(p.x()), static_cast<int>(p.y())); };
  cv::circle(img, pt(g.entry_px), 4, cv::Scalar(255, 0, 255), cv::FILLED);
  if (g.haveWrist) {
    cv::circle(img, pt(g.wrist_px), 4, cv::Scalar(255, 255, 0), cv::FILLED);
    cv::line(img, pt(g.wrist_px), pt(g.wrist_px + 150 * g.axis), cv::Scalar(255, 255, 0), 1);
  }
  cv::drawMarker(img, pt(g.palm_px), cv::Scalar(0, 0, 255), cv::MARKER_CROSS, 12, 2);
  const auto& k = f.intrinsics;
  const Eigen::Vector3d& q = truth.p_camera_palm_m;
  if (q.z() > 0)
    cv::drawMarker(img, cv::Point(static_cast<int>(k.fx_px * q.x() / q.z() + k.cx_px), static_cast<int>(k.fy_px * q.y() / q.z() + k.cy_px)),
                   cv::Scalar(255, 255, 255), cv::MARKER_TILTED_CROSS, 12, 2);
  cv::imwrite(pngPath, img);
}

/// `onFrame(frame, detector, truth, p_camera_palm_m)` is called after every
/// frame (drawing, collecting frames for a benchmark); nullopt = no palm.
/// `previewFirst`: every frame is shown to preview() first, as `srp perceive` does
/// (whole-recording background, learnt skin); else the first frames are the background.
inline HandEvaluation evaluateMarkerFreeHand(
    const std::string& rawlogPath, const MarkerFreeHandDetector::Options& options = {},
    const std::function<void(const rawlog::RgbdFrame&, const MarkerFreeHandDetector&, const synth::GroundTruthFrame&,
                             const std::optional<Eigen::Vector3d>&)>& onFrame = {},
    bool previewFirst = false) {
  const auto gt = synth::DemoGroundTruth::load(synth::groundTruthPathFor(rawlogPath));
  MarkerFreeHandDetector detector(options);
  // SRP_VIEW_PHASES=grasp,move: only the frames of these phases are previewed
  // and scored (a recording in which the hand is in view, nearly still or
  // holding a part, in every frame).
  std::set<std::string> phases;
  if (const char* env = std::getenv("SRP_VIEW_PHASES")) {
    std::stringstream names(env);
    for (std::string name; std::getline(names, name, ',');) phases.insert(name);
  }
  auto inPhases = [&](std::size_t i) {
    return phases.empty() || (i < gt.frames.size() && phases.count(gt.frames[i].phase) > 0);
  };
  if (previewFirst) {
    rawlog::RawlogReader all(rawlogPath);
    std::size_t j = 0;
    while (auto f = all.next()) if (inPhases(j++)) detector.preview(*f);
  }
  rawlog::RawlogReader reader(rawlogPath);
  HandEvaluation ev;
  double lastZ_m = -1.0;
  while (auto f = reader.next()) {
    const auto i = static_cast<std::size_t>(reader.framesRead() - 1);
    if (i >= gt.frames.size()) break;
    if (!inPhases(i)) continue;
    ++ev.frames;
    const auto& truth = gt.frames[i];
    timespec t0{}, t1{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t0);
    const auto h = detector.detect(*f);
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t1);
    const bool timed = previewFirst || static_cast<int>(i) >= options.backgroundFrames;
    if (timed) ++ev.timedFrames;
    if (timed)
      ev.detectCpu_s += static_cast<double>(t1.tv_sec - t0.tv_sec) + 1e-9 * static_cast<double>(t1.tv_nsec - t0.tv_nsec);
    bool have = false;
    Eigen::Vector3d p_m = Eigen::Vector3d::Zero();
    if (h && h->hasDepth) {
      p_m = h->p_camera_palm_m;
      lastZ_m = p_m.z();
      have = true;
    } else if (h && lastZ_m > 0.0) {
      const auto& k = f->intrinsics;
      p_m = {(h->palm_px.x() - k.cx_px) * lastZ_m / k.fx_px, (h->palm_px.y() - k.cy_px) * lastZ_m / k.fy_px, lastZ_m};
      ++ev.depthCarried;
      have = true;
    }
    const auto& k = f->intrinsics;
    auto project = [&](const Eigen::Vector3d& q) {
      return Eigen::Vector2d(k.fx_px * q.x() / q.z() + k.cx_px, k.fy_px * q.y() / q.z() + k.cy_px);
    };
    if (!truth.handInView) {
      ev.handWithoutHand += have;
    } else {
      ++ev.handInView;
      auto& [detected, inView] = ev.detectedByPhase[truth.phase];
      ++inView;
      if (have) {
        ++detected;
        const double e = (p_m - truth.p_camera_palm_m).norm();
        ev.error_m.push_back(e);
        ev.errorByPhase_m[truth.phase].push_back(e);
        ev.error640_px.push_back((project(p_m) - project(truth.p_camera_palm_m)).norm() * 640.0 / k.width_px);
      }
      if (!truth.carriedObject.empty()) {
        ++ev.carried;
        if (have) {
          // In 3D: past the part's origin (its bottom face's centre) on the line from the true palm.
          const Eigen::Vector3d toPart =
              gt.X_camera_object(truth.index, truth.carriedObject).translation() - truth.p_camera_palm_m;
          const double beyond_m = (p_m - truth.p_camera_palm_m).dot(toPart.normalized()) - toPart.norm();
          ev.worstFarSide_m = std::max(ev.worstFarSide_m, beyond_m);
          ev.farSide += beyond_m > 0.0;
        }
      }
    }
    if (onFrame) onFrame(*f, detector, truth, have ? std::optional<Eigen::Vector3d>(p_m) : std::nullopt);
  }
  return ev;
}

}  // namespace srp::perception::testing
