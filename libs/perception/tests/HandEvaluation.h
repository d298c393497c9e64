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
#include <functional>
#include <map>
#include <optional>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <string>
#include <ctime>
#include <vector>

#include "srp/perception/MarkerFreeHandDetector.h"
#include "srp/rawlog/RawlogReader.h"
#include "srp/synth/DemoGenerator.h"
#include "srp/synth/DemoGroundTruth.h"

namespace srp::perception::testing {

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
  std::map<std::string, std::vector<double>> errorByPhase_m;
  std::map<std::string, std::pair<int, int>> detectedByPhase;  ///< phase -> (detected, in view)

  double rate() const { return static_cast<double>(error_m.size()) / std::max(1, handInView); }
  double median_m() const { return percentile(error_m, 0.5); }
  double p95_m() const { return percentile(error_m, 0.95); }

  void print(const std::string& what) const {
    std::printf("[ figures  ] marker-free hand, %s (%d frames): detected in %zu/%d frames with the hand in view "
                "(%.1f %%; %d with carried depth), palm error median %.1f mm, p95 %.1f mm, max %.1f mm; "
                "hand reported in %d frames without a hand; detect() %.1f ms CPU per frame\n",
                what.c_str(), frames, error_m.size(), handInView, 100.0 * rate(), depthCarried, 1e3 * median_m(),
                1e3 * p95_m(), 1e3 * percentile(error_m, 1.0), handWithoutHand,
                1e3 * detectCpu_s / std::max(1, timedFrames));
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
inline HandEvaluation evaluateMarkerFreeHand(
    const std::string& rawlogPath, const MarkerFreeHandDetector::Options& options = {},
    const std::function<void(const rawlog::RgbdFrame&, const MarkerFreeHandDetector&, const synth::GroundTruthFrame&,
                             const std::optional<Eigen::Vector3d>&)>& onFrame = {}) {
  const auto gt = synth::DemoGroundTruth::load(synth::groundTruthPathFor(rawlogPath));
  rawlog::RawlogReader reader(rawlogPath);
  MarkerFreeHandDetector detector(options);
  HandEvaluation ev;
  double lastZ_m = -1.0;
  while (auto f = reader.next()) {
    const auto i = static_cast<std::size_t>(reader.framesRead() - 1);
    if (i >= gt.frames.size()) break;
    ++ev.frames;
    const auto& truth = gt.frames[i];
    timespec t0{}, t1{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t0);
    const auto h = detector.detect(*f);
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t1);
    if (static_cast<int>(i) >= options.backgroundFrames) ++ev.timedFrames;
    if (static_cast<int>(i) >= options.backgroundFrames)
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
      }
    }
    if (onFrame) onFrame(*f, detector, truth, have ? std::optional<Eigen::Vector3d>(p_m) : std::nullopt);
  }
  return ev;
}

}  // namespace srp::perception::testing
