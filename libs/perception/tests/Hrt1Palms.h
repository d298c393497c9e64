#pragma once
// The marker-free hand on HRT1's real demonstrations (datasets/real/hrt1-pick-place,
// MIT, credits in its README) against our own palm labels (palm_labels.json),
// and the robustness harness: label-preserving perturbations a new recording
// of the same kind plausibly brings (light, white balance, compression, sensor
// noise, depth noise and holes, the other intrinsics, a tilted camera, a
// mirrored scene, half the frame rate, sensor wires and tape on the hand). Shared by MarkerFreeHandDetector_test
// and MarkerFreeHandRobustness_test.
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <functional>
#include <map>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <string>
#include <vector>

#include "srp/core/Json.h"
#include "srp/perception/MarkerFreeHandDetector.h"
#include "srp/perception/RgbdFolder.h"

namespace srp::perception::testing {

/// One recording: its frames and the labelled palm pixel of each frame with a visible hand.
struct Hrt1Task {
  std::string name;
  std::vector<rawlog::RgbdFrame> frames;
  std::map<int, Eigen::Vector2d> label_px;  ///< frame index -> palm pixel
};

inline std::string hrt1Root() { return std::string(SRP_DATASETS_DIR) + "/real/hrt1-pick-place"; }

/// Our palm labels of one recording: frame index -> palm pixel (frames with a visible hand).
inline std::map<int, Eigen::Vector2d> hrt1PalmLabels(const std::string& task) {
  const auto labels = core::readJsonFile(hrt1Root() + "/palm_labels.json").at("tasks").at(task);
  std::map<int, Eigen::Vector2d> out;
  for (const auto& l : labels.at("visible")) out[l[0].get<int>()] = {l[1].get<double>(), l[2].get<double>()};
  return out;
}

inline Hrt1Task loadHrt1(const std::string& task) {
  Hrt1Task t;
  t.name = task;
  t.label_px = hrt1PalmLabels(task);
  t.frames = readRgbdFolder(hrt1Root() + "/" + task);
  return t;
}

struct RealFrameError {
  int frame = 0;
  bool detected = false;
  Eigen::Vector2d palm_px = Eigen::Vector2d::Zero(), label_px = Eigen::Vector2d::Zero();
  double error_px = 0.0;
  bool bareForearm = false;
};

/// CPU time of one run (figures, never asserted).
struct PalmTiming {
  double preview_ms_per_frame = 0.0, firstDetect_ms = 0.0, detect_ms_per_frame = 0.0;
};

/// Previews the whole recording, then detects every frame; the error of each
/// labelled frame. `debugDir` (non-empty): every frame is drawn there with the
/// found (red +) and the labelled (white x) palm.
inline std::vector<RealFrameError> palmErrors(const Hrt1Task& t, const MarkerFreeHandDetector::Options& options,
                                              PalmTiming* timing = nullptr, const std::string& debugDir = {}) {
  MarkerFreeHandDetector detector(options);
  const std::clock_t c0 = std::clock();
  for (const auto& f : t.frames) detector.preview(f);
  const std::clock_t c1 = std::clock();
  std::clock_t cFirst = 0, cDetect = 0;
  std::vector<RealFrameError> out;
  for (const auto& f : t.frames) {
    const std::clock_t t0 = std::clock();
    const auto h = detector.detect(f);
    if (&f == &t.frames.front()) cFirst = std::clock() - t0;
    else cDetect += std::clock() - t0;
    const auto it = t.label_px.find(f.index);
    if (!debugDir.empty()) {
      std::filesystem::create_directories(debugDir);
      cv::Mat img = f.colour_bgr8.clone();
      const auto& g = detector.lastGeometry();
      if (!detector.lastMask().empty() && h) {
        std::vector<std::vector<cv::Point>> contours;
        cv::findContours(detector.lastMask().clone(), contours, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_NONE);
        cv::drawContours(img, contours, -1, cv::Scalar(0, 255, 0), 1);
      }
      auto pt = [](const Eigen::Vector2d& p) { return cv::Point(static_cast<int>(p.x()), static_cast<int>(p.y())); };
      cv::circle(img, pt(g.entry_px), 5, cv::Scalar(255, 0, 255), cv::FILLED);
      if (g.bareForearm) cv::circle(img, pt(g.farEnd_px), 4, cv::Scalar(255, 255, 0), cv::FILLED);
      if (h) cv::drawMarker(img, pt(h->palm_px), cv::Scalar(0, 0, 255), cv::MARKER_CROSS, 14, 2);
      if (it != t.label_px.end())
        cv::drawMarker(img, pt(it->second), cv::Scalar(255, 255, 255), cv::MARKER_TILTED_CROSS, 14, 2);
      char name[64];
      std::snprintf(name, sizeof name, "/%s_%04d.png", t.name.c_str(), f.index);
      cv::imwrite(debugDir + name, img);
    }
    if (it == t.label_px.end()) continue;  // hand not visible: not scored
    RealFrameError e;
    e.frame = f.index;
    e.label_px = it->second;
    e.detected = h.has_value();
    if (h) {
      e.palm_px = h->palm_px;
      e.error_px = (h->palm_px - it->second).norm();
      e.bareForearm = detector.lastGeometry().bareForearm;
    }
    out.push_back(e);
  }
  if (timing) {
    auto ms = [](std::clock_t c) { return 1e3 * static_cast<double>(c) / CLOCKS_PER_SEC; };
    const double n = static_cast<double>(t.frames.size());
    *timing = {ms(c1 - c0) / n, ms(cFirst), ms(cDetect) / std::max(1.0, n - 1.0)};
  }
  return out;
}

constexpr double kPalmTol_px = 40.0;  // issue 17: palm within 40 px of the labelled palm

/// Within-40-px count, median and worst error of a run (a miss counts as outside, not in the median).
struct PalmScore {
  int within = 0, labelled = 0, missed = 0;
  double median_px = 0.0, worst_px = 0.0;
  double rate() const { return labelled > 0 ? static_cast<double>(within) / labelled : 0.0; }
};

inline PalmScore score(const std::vector<RealFrameError>& errors) {
  PalmScore s;
  std::vector<double> err;
  for (const auto& e : errors) {
    ++s.labelled;
    if (!e.detected) {
      ++s.missed;
      continue;
    }
    err.push_back(e.error_px);
    if (e.error_px <= kPalmTol_px) ++s.within;
    s.worst_px = std::max(s.worst_px, e.error_px);
  }
  std::sort(err.begin(), err.end());
  if (!err.empty()) s.median_px = err[err.size() / 2];
  return s;
}

// ---- perturbations -------------------------------------------------------

/// A label-preserving change of a whole recording (frames and, for a
/// geometric change, the labels with them).
struct Perturbation {
  std::string name;
  std::function<void(Hrt1Task&)> apply;
};

/// Applies `f(colour)` to every frame's colour image.
inline std::function<void(Hrt1Task&)> perColour(const std::function<void(cv::Mat&, int)>& f) {
  return [f](Hrt1Task& t) {
    for (auto& fr : t.frames) f(fr.colour_bgr8, fr.index);
  };
}

/// Per-channel gains (B, G, R) on the linear 8-bit values, saturating.
inline void gains(cv::Mat& c, double b, double g, double r) {
  cv::Mat f;
  c.convertTo(f, CV_32FC3);
  cv::multiply(f, cv::Scalar(b, g, r), f);
  f.convertTo(c, CV_8UC3);
}

inline void gamma(cv::Mat& c, double gamma) {
  cv::Mat lut(1, 256, CV_8UC1);
  for (int i = 0; i < 256; ++i) lut.at<uchar>(i) = cv::saturate_cast<uchar>(255.0 * std::pow(i / 255.0, gamma));
  cv::LUT(c, lut, c);
}

inline void jpeg(cv::Mat& c, int quality) {
  std::vector<uchar> buf;
  cv::imencode(".jpg", c, buf, {cv::IMWRITE_JPEG_QUALITY, quality});
  c = cv::imdecode(buf, cv::IMREAD_COLOR);
}

/// Gaussian sensor noise of `sigma` 8-bit units per channel, seeded by the frame.
inline void colourNoise(cv::Mat& c, double sigma, int frame) {
  cv::RNG rng(static_cast<std::uint64_t>(1000 + frame));
  cv::Mat n(c.size(), CV_32FC3), f;
  rng.fill(n, cv::RNG::NORMAL, cv::Scalar::all(0), cv::Scalar::all(sigma));
  c.convertTo(f, CV_32FC3);
  f += n;
  f.convertTo(c, CV_8UC3);
}

/// Depth noise growing with the square of the depth (structured light / ToF
/// axial noise): sigma = k z^2, k [1/m]; quantised to the sensor's mm.
inline void depthNoise(cv::Mat& depth_m, double k_per_m, int frame) {
  cv::RNG rng(static_cast<std::uint64_t>(2000 + frame));
  cv::Mat n(depth_m.size(), CV_32FC1);
  rng.fill(n, cv::RNG::NORMAL, 0.0, 1.0);
  for (int v = 0; v < depth_m.rows; ++v) {
    float* z = depth_m.ptr<float>(v);
    const float* e = n.ptr<float>(v);
    for (int u = 0; u < depth_m.cols; ++u)
      if (z[u] > 0.f) z[u] = std::max(0.001f, std::round(1e3f * (z[u] + static_cast<float>(k_per_m) * z[u] * z[u] * e[u])) * 1e-3f);
  }
}

/// Random depth holes: squares of `side_px` until `share` of the image is hit, seeded by the frame.
inline void depthHoles(cv::Mat& depth_m, double share, int side_px, int frame) {
  cv::RNG rng(static_cast<std::uint64_t>(3000 + frame));
  const int n = static_cast<int>(share * depth_m.total() / (side_px * side_px));
  for (int i = 0; i < n; ++i) {
    const int u = rng.uniform(0, depth_m.cols - side_px), v = rng.uniform(0, depth_m.rows - side_px);
    depth_m(cv::Rect(u, v, side_px, side_px)).setTo(0.f);
  }
}

/// Holes along depth discontinuities (the shadow of a structured-light
/// camera's projector, mixed pixels dropped): pixels within `width_px` of a
/// step of more than `step_m` between neighbours.
inline void depthEdgeHoles(cv::Mat& depth_m, double step_m, int width_px) {
  cv::Mat gx, gy, edge;
  cv::Sobel(depth_m, gx, CV_32F, 1, 0, 1);
  cv::Sobel(depth_m, gy, CV_32F, 0, 1, 1);
  cv::Mat valid = depth_m > 0, validEroded;
  cv::erode(valid, validEroded, cv::Mat());
  edge = ((cv::abs(gx) > step_m) | (cv::abs(gy) > step_m)) & validEroded;
  cv::dilate(edge, edge, cv::getStructuringElement(cv::MORPH_RECT, {2 * width_px - 1, 2 * width_px - 1}));
  depth_m.setTo(0.f, edge);
}

/// The camera turned by `R_new_old` about its centre: colour and depth
/// re-rendered (a pure rotation needs no scene depth), labels moved by the
/// homography K R K^-1. Depth is re-expressed in the new camera (z' of the
/// rotated point); pixels seen by neither keep no depth and the edge colour.
inline void rotateCamera(Hrt1Task& t, const Eigen::Matrix3d& R_new_old) {
  const auto& k = t.frames.front().intrinsics;
  Eigen::Matrix3d K;
  K << k.fx_px, 0, k.cx_px, 0, k.fy_px, k.cy_px, 0, 0, 1;
  const Eigen::Matrix3d H = K * R_new_old * K.inverse(), Hinv = H.inverse();
  const int W = k.width_px, Hh = k.height_px;
  cv::Mat mapU(Hh, W, CV_32FC1), mapV(Hh, W, CV_32FC1), zScale(Hh, W, CV_32FC1);
  for (int v = 0; v < Hh; ++v)
    for (int u = 0; u < W; ++u) {
      const Eigen::Vector3d s = Hinv * Eigen::Vector3d(u, v, 1.0);
      const Eigen::Vector2d ps = s.hnormalized();
      mapU.at<float>(v, u) = static_cast<float>(ps.x());
      mapV.at<float>(v, u) = static_cast<float>(ps.y());
      // z' = z (R r).z with r = K^-1 p_s (unit depth)
      zScale.at<float>(v, u) = static_cast<float>((R_new_old * K.inverse() * Eigen::Vector3d(ps.x(), ps.y(), 1.0)).z());
    }
  for (auto& f : t.frames) {
    cv::Mat c, d;
    cv::remap(f.colour_bgr8, c, mapU, mapV, cv::INTER_LINEAR, cv::BORDER_REPLICATE);
    cv::remap(f.depth_m, d, mapU, mapV, cv::INTER_NEAREST, cv::BORDER_CONSTANT, cv::Scalar(0));
    f.colour_bgr8 = c;
    f.depth_m = d.mul(zScale);
  }
  for (auto& [i, p] : t.label_px) p = (H * Eigen::Vector3d(p.x(), p.y(), 1.0)).hnormalized();
}

inline Eigen::Matrix3d rotX(double deg) {
  const double a = deg * M_PI / 180.0;
  Eigen::Matrix3d R;
  R << 1, 0, 0, 0, std::cos(a), -std::sin(a), 0, std::sin(a), std::cos(a);
  return R;
}

inline Eigen::Matrix3d rotZ(double deg) {
  const double a = deg * M_PI / 180.0;
  Eigen::Matrix3d R;
  R << std::cos(a), -std::sin(a), 0, std::sin(a), std::cos(a), 0, 0, 0, 1;
  return R;
}

/// The scene mirrored left-right (the demonstrator on the other side of the
/// table; the depth camera's blind band then on the left).
inline void mirror(Hrt1Task& t) {
  for (auto& f : t.frames) {
    cv::flip(f.colour_bgr8, f.colour_bgr8, 1);
    cv::flip(f.depth_m, f.depth_m, 1);
    f.intrinsics.cx_px = f.intrinsics.width_px - 1 - f.intrinsics.cx_px;
  }
  for (auto& [i, p] : t.label_px) p.x() = t.frames.front().intrinsics.width_px - 1 - p.x();
}

/// Keeps every other frame from `first` (5 Hz from 10 Hz); labels of dropped frames go.
inline void halfRate(Hrt1Task& t, int first) {
  std::vector<rawlog::RgbdFrame> kept;
  for (auto& f : t.frames)
    if ((f.index - first) % 2 == 0) kept.push_back(std::move(f));
    else t.label_px.erase(f.index);
  t.frames = std::move(kept);
}

/// A glove-less hand-pose sensor rig drawn on the hand (label-preserving; depth untouched: wires this
/// thin are below the depth camera's resolution and tape lies flat on the skin). One rig per recording
/// (seeded by `seed`), placed about each frame's palm label in image axes: `wires` dark curves 2 px wide
/// (2-3.5 mm at HRT1's ~1 m), quadratic curves from near the palm outwards over 45-75 px (the back of
/// the hand and the fingers), and `patches` light squares of 5-9 px (8-15 mm) within 60 px of the
/// palm. Drawn only on the labelled hand: pixels within `radius_px` of the palm label that are of skin
/// colour (the detector's prior box) and whose depth lies within 0.1 m of the hand's (the median
/// depth within 15 px of the label), so never on the table, the part or the background. Frames
/// without a label (no hand in view) are left as they are.
inline void wiresAndTape(Hrt1Task& t, std::uint64_t seed, int wires = 5, int patches = 6, double radius_px = 75.0) {
  cv::RNG rng(seed);
  struct Curve {
    cv::Point2d p0, p1, p2;
  };
  std::vector<Curve> curves;
  for (int i = 0; i < wires; ++i) {
    const double a = rng.uniform(0.0, 2.0 * M_PI), len = rng.uniform(45.0, 75.0), bend = rng.uniform(-15.0, 15.0);
    const cv::Point2d dir(std::cos(a), std::sin(a)), across(-dir.y, dir.x);
    const cv::Point2d p0(rng.uniform(-10.0, 10.0), rng.uniform(-10.0, 10.0));
    curves.push_back({p0, p0 + 0.5 * len * dir + bend * across, p0 + len * dir});
  }
  std::vector<cv::Rect2d> squares;
  for (int i = 0; i < patches; ++i) {
    const double side = rng.uniform(5.0, 9.0), r = rng.uniform(0.0, 60.0), a = rng.uniform(0.0, 2.0 * M_PI);
    squares.emplace_back(r * std::cos(a) - 0.5 * side, r * std::sin(a) - 0.5 * side, side, side);
  }
  const MarkerFreeHandDetector::Options prior;
  for (auto& f : t.frames) {
    const auto it = t.label_px.find(f.index);
    if (it == t.label_px.end()) continue;
    const cv::Point2d c(it->second.x(), it->second.y());
    // The hand's depth: the median valid depth within 15 px of the palm label.
    std::vector<float> z;
    for (int v = std::max(0, static_cast<int>(c.y) - 15); v <= std::min(f.depth_m.rows - 1, static_cast<int>(c.y) + 15); ++v)
      for (int u = std::max(0, static_cast<int>(c.x) - 15); u <= std::min(f.depth_m.cols - 1, static_cast<int>(c.x) + 15); ++u)
        if (f.depth_m.at<float>(v, u) > 0.f) z.push_back(f.depth_m.at<float>(v, u));
    cv::Mat ycrcb, region;
    cv::cvtColor(f.colour_bgr8, ycrcb, cv::COLOR_BGR2YCrCb);
    cv::inRange(ycrcb, cv::Scalar(prior.skinMinLuma, prior.skinPriorCrMin, prior.skinPriorCbMin),
                cv::Scalar(255, prior.skinPriorCrMax, prior.skinPriorCbMax), region);
    cv::Mat disc(region.size(), CV_8UC1, cv::Scalar(0));
    cv::circle(disc, c, static_cast<int>(radius_px), cv::Scalar(255), cv::FILLED);
    region &= disc;
    if (!z.empty()) {
      std::nth_element(z.begin(), z.begin() + static_cast<long>(z.size() / 2), z.end());
      const float zHand = z[z.size() / 2];
      // A pixel without depth next to the hand may still be hand (its depth holes): kept.
      region &= (f.depth_m <= 0.f) | ((f.depth_m > zHand - 0.1f) & (f.depth_m < zHand + 0.1f));
    }
    cv::Mat drawn = f.colour_bgr8.clone();
    for (const auto& s : squares)
      cv::rectangle(drawn, cv::Rect(cv::Point(cvRound(c.x + s.x), cvRound(c.y + s.y)), cv::Size(cvRound(s.width), cvRound(s.height))),
                    cv::Scalar(222, 228, 230), cv::FILLED);
    for (const auto& k : curves) {
      std::vector<cv::Point> pts;
      for (int j = 0; j <= 16; ++j) {
        const double u = j / 16.0;
        const cv::Point2d p = (1 - u) * (1 - u) * k.p0 + 2 * u * (1 - u) * k.p1 + u * u * k.p2;
        pts.emplace_back(cvRound(c.x + p.x), cvRound(c.y + p.y));
      }
      cv::polylines(drawn, pts, false, cv::Scalar(28, 26, 26), 2);
    }
    drawn.copyTo(f.colour_bgr8, region);
  }
}

/// The perturbation set (names as in the README's table).
inline std::vector<Perturbation> hrt1Perturbations() {
  std::vector<Perturbation> p;
  p.push_back({"none", [](Hrt1Task&) {}});
  p.push_back({"gain 0.75", perColour([](cv::Mat& c, int) { gains(c, 0.75, 0.75, 0.75); })});
  p.push_back({"gain 1.25", perColour([](cv::Mat& c, int) { gains(c, 1.25, 1.25, 1.25); })});
  // Beyond the +-25 % the settings were selected on (added after the selection: a check, not a criterion).
  p.push_back({"gain 0.6 (check)", perColour([](cv::Mat& c, int) { gains(c, 0.6, 0.6, 0.6); })});
  p.push_back({"gamma 0.8", perColour([](cv::Mat& c, int) { gamma(c, 0.8); })});
  p.push_back({"gamma 1.25", perColour([](cv::Mat& c, int) { gamma(c, 1.25); })});
  // Colour temperature: tungsten-like (warmer) and shade-like (cooler) white balance.
  p.push_back({"warm (R x1.15, B x0.8)", perColour([](cv::Mat& c, int) { gains(c, 0.8, 1.0, 1.15); })});
  p.push_back({"cool (R x0.85, B x1.15)", perColour([](cv::Mat& c, int) { gains(c, 1.15, 1.0, 0.85); })});
  p.push_back({"JPEG 50", perColour([](cv::Mat& c, int) { jpeg(c, 50); })});
  p.push_back({"colour noise sd 6", perColour([](cv::Mat& c, int i) { colourNoise(c, 6.0, i); })});
  p.push_back({"dark + noise + JPEG 50", perColour([](cv::Mat& c, int i) {
                 gains(c, 0.75, 0.75, 0.75);
                 colourNoise(c, 6.0, i);
                 jpeg(c, 50);
               })});
  p.push_back({"depth noise 3 mm at 1 m", [](Hrt1Task& t) {
                 for (auto& f : t.frames) depthNoise(f.depth_m, 0.003, f.index);
               }});
  p.push_back({"depth holes 10 % (8 px)", [](Hrt1Task& t) {
                 for (auto& f : t.frames) depthHoles(f.depth_m, 0.10, 8, f.index);
               }});
  p.push_back({"depth edge holes (3 px)", [](Hrt1Task& t) {
                 for (auto& f : t.frames) depthEdgeHoles(f.depth_m, 0.05, 3);
               }});
  p.push_back({"driver intrinsics", [](Hrt1Task& t) {
                 for (auto& f : t.frames) {
                   f.intrinsics.fx_px = f.intrinsics.fy_px = 574.05;
                   f.intrinsics.cx_px = 319.5;
                   f.intrinsics.cy_px = 239.5;
                 }
               }});
  p.push_back({"tilt down 3 deg", [](Hrt1Task& t) { rotateCamera(t, rotX(3.0)); }});
  p.push_back({"tilt up 3 deg", [](Hrt1Task& t) { rotateCamera(t, rotX(-3.0)); }});
  p.push_back({"roll 5 deg", [](Hrt1Task& t) { rotateCamera(t, rotZ(5.0)); }});
  p.push_back({"mirrored", [](Hrt1Task& t) { mirror(t); }});
  p.push_back({"5 Hz (even frames)", [](Hrt1Task& t) { halfRate(t, 0); }});
  p.push_back({"5 Hz (odd frames)", [](Hrt1Task& t) { halfRate(t, 1); }});
  // A sensor rig on the skin (the dressing of srp::synth's HandModel::SensorWires, drawn): a check, not a criterion.
  p.push_back({"wires and tape (drawn)", [](Hrt1Task& t) { wiresAndTape(t, 4001); }});
  return p;
}

}  // namespace srp::perception::testing
