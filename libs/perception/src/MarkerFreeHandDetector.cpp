#include "srp/perception/MarkerFreeHandDetector.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "srp/core/Error.h"

namespace srp::perception {
namespace {

/// Per-pixel median of valid (> 0) values of CV_32F images.
cv::Mat medianDepth(const std::vector<cv::Mat>& images) {
  cv::Mat out(images[0].size(), CV_32FC1, cv::Scalar(0));
  std::vector<float> vals;
  for (int v = 0; v < out.rows; ++v)
    for (int u = 0; u < out.cols; ++u) {
      vals.clear();
      for (const auto& im : images)
        if (const float z = im.at<float>(v, u); z > 0.f) vals.push_back(z);
      if (vals.empty()) continue;
      std::nth_element(vals.begin(), vals.begin() + vals.size() / 2, vals.end());
      out.at<float>(v, u) = vals[vals.size() / 2];
    }
  return out;
}

bool onBorder(const cv::Mat& m, int u, int v) { return u <= 1 || v <= 1 || u >= m.cols - 2 || v >= m.rows - 2; }

/// Median of the valid depths of `mask` pixels within `radius_px` of `centre`; nullopt when fewer than `minCount`.
std::optional<double> medianDepthInDisc(const cv::Mat& depth_m, const cv::Mat& mask, const Eigen::Vector2d& centre,
                                        double radius_px, std::size_t minCount) {
  std::vector<float> depths;
  const int r = static_cast<int>(std::ceil(radius_px));
  const int cu = static_cast<int>(std::lround(centre.x())), cv_ = static_cast<int>(std::lround(centre.y()));
  for (int v = std::max(0, cv_ - r); v <= std::min(mask.rows - 1, cv_ + r); ++v) {
    const uchar* m = mask.ptr<uchar>(v);
    const float* z = depth_m.ptr<float>(v);
    for (int u = std::max(0, cu - r); u <= std::min(mask.cols - 1, cu + r); ++u)
      if (m[u] && z[u] > 0.f && (Eigen::Vector2d(u, v) - centre).squaredNorm() <= radius_px * radius_px)
        depths.push_back(z[u]);
  }
  if (depths.size() < minCount) return std::nullopt;
  std::nth_element(depths.begin(), depths.begin() + depths.size() / 2, depths.end());
  return depths[depths.size() / 2];
}

}  // namespace

MarkerFreeHandDetector::MarkerFreeHandDetector(const Options& options) : options_(options) {
  core::require(options.backgroundFrames >= 1, "MarkerFreeHandDetector: backgroundFrames must be >= 1");
  core::require(options.palmFromWrist_m > 0.0 && options.palmFromFingertips_m > 0.0 && options.palmRadius_m > 0.0,
                "MarkerFreeHandDetector: palmFromWrist_m, palmFromFingertips_m and palmRadius_m must be > 0 m "
                "(lengths of the demonstrator's hand)");
}

std::optional<HandObservation> MarkerFreeHandDetector::detect(const rawlog::RgbdFrame& frame) {
  geometry_ = Geometry{};
  ++frameCount_;
  if (backgroundDepth_m_.empty()) {
    depthHistory_.push_back(frame.depth_m.clone());
    colourHistory_.push_back(frame.colour_bgr8.clone());
    if (static_cast<int>(depthHistory_.size()) < options_.backgroundFrames) return std::nullopt;
    backgroundDepth_m_ = medianDepth(depthHistory_);
    // Colour background: the mean is enough (it is only used where depth is missing).
    cv::Mat acc(frame.colour_bgr8.size(), CV_32FC3, cv::Scalar::all(0));
    for (const auto& c : colourHistory_) cv::accumulate(c, acc);
    acc.convertTo(backgroundColour_, CV_8UC3, 1.0 / static_cast<double>(colourHistory_.size()));
    depthHistory_.clear();
    colourHistory_.clear();
    return std::nullopt;  // background frames show no hand by assumption
  }
  const cv::Mat& depth = frame.depth_m;
  const auto& k = frame.intrinsics;
  const bool hasColour = !frame.colour_bgr8.empty();
  cv::Mat skin(depth.size(), CV_8UC1, cv::Scalar(255));
  if (options_.useSkin && hasColour) {
    cv::Mat ycrcb;
    cv::cvtColor(frame.colour_bgr8, ycrcb, cv::COLOR_BGR2YCrCb);
    cv::inRange(ycrcb, cv::Scalar(0, 135, 80), cv::Scalar(255, 180, 130), skin);
  }
  // Foreground by depth (the whole arm, sleeve included, reaches the border);
  // the hand is its skin-coloured part.
  // Sum of |BGR| changes that marks a depth hole as foreground: skin over a
  // beige table differs by ~60, sensor colour noise (sigma 2 per channel) by ~5.
  constexpr int kHoleColourChange = 30;
  cv::Mat mask(depth.size(), CV_8UC1, cv::Scalar(0));
  for (int v = 0; v < depth.rows; ++v) {
    const float* z = depth.ptr<float>(v);
    const float* bg = backgroundDepth_m_.ptr<float>(v);
    uchar* m = mask.ptr<uchar>(v);
    for (int u = 0; u < depth.cols; ++u) {
      if (z[u] > 0.f && bg[u] > 0.f) m[u] = (bg[u] - z[u] > options_.minForeground_m) ? 255 : 0;
      else if (z[u] <= 0.f && hasColour) {
        // A hole (moving hand): foreground when the colour changed.
        const cv::Vec3b a = frame.colour_bgr8.at<cv::Vec3b>(v, u), b = backgroundColour_.at<cv::Vec3b>(v, u);
        const int diff = std::abs(a[0] - b[0]) + std::abs(a[1] - b[1]) + std::abs(a[2] - b[2]);
        m[u] = diff > kHoleColourChange ? 255 : 0;
      }
    }
  }
  const cv::Mat disc5 = cv::getStructuringElement(cv::MORPH_ELLIPSE, {5, 5});
  cv::morphologyEx(mask, mask, cv::MORPH_OPEN, disc5);
  cv::Mat labels, stats, centroids;
  const int n = cv::connectedComponentsWithStats(mask, labels, stats, centroids, 8, CV_32S);
  int bestLabel = -1, bestArea = 0;
  bool bestTouches = false;
  auto touchesBorder = [&](const cv::Mat& s, int l) {
    const int x = s.at<int>(l, cv::CC_STAT_LEFT), y = s.at<int>(l, cv::CC_STAT_TOP);
    const int w = s.at<int>(l, cv::CC_STAT_WIDTH), hgt = s.at<int>(l, cv::CC_STAT_HEIGHT);
    return x <= 1 || y <= 1 || x + w >= mask.cols - 1 || y + hgt >= mask.rows - 1;
  };
  for (int l = 1; l < n; ++l) {
    const int area = stats.at<int>(l, cv::CC_STAT_AREA);
    if (area < options_.minPixels) continue;
    const bool touches = touchesBorder(stats, l);
    // Prefer components the arm connects to the border; then size.
    if ((touches && !bestTouches) || (touches == bestTouches && area > bestArea)) {
      bestLabel = l;
      bestArea = area;
      bestTouches = touches;
    }
  }
  if (bestLabel < 0) return std::nullopt;
  const cv::Mat arm = (labels == bestLabel);
  cv::Mat hand = arm & skin;
  cv::morphologyEx(hand, hand, cv::MORPH_OPEN, disc5);
  if (cv::countNonZero(hand) < options_.minPixels / 2) return std::nullopt;
  {
    // Fill holes (a held object, a badge on the glove): the palm disc's depth
    // and the sleeve (the arm's non-skin part) must not include them.
    std::vector<std::vector<cv::Point>> contours;
    cv::findContours(hand.clone(), contours, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_SIMPLE);
    cv::drawContours(hand, contours, -1, cv::Scalar(255), cv::FILLED);
    hand &= arm;
  }
  lastMask_ = hand;

  // Entry point: mean of the arm's border pixels (none: the arm's centroid).
  Eigen::Vector2d entry = Eigen::Vector2d::Zero();
  int nBorder = 0;
  for (int v = 0; v < arm.rows; ++v) {
    const uchar* a = arm.ptr<uchar>(v);
    for (int u = 0; u < arm.cols; ++u)
      if (a[u] && onBorder(arm, u, v)) {
        entry += Eigen::Vector2d(u, v);
        ++nBorder;
      }
  }
  if (nBorder > 0) entry /= nBorder;
  else entry = {centroids.at<double>(bestLabel, 0), centroids.at<double>(bestLabel, 1)};
  geometry_.entry_px = entry;

  // The sleeve: the non-skin part of the arm that reaches the border (a
  // carried object under the hand does not).
  cv::Mat sleeve;
  {
    const cv::Mat rest = arm & ~hand;
    cv::Mat sl, ss, sc;
    const int ns = cv::connectedComponentsWithStats(rest, sl, ss, sc, 8, CV_32S);
    int best = -1, area = options_.minPixels / 2;
    for (int l = 1; l < ns; ++l)
      if (ss.at<int>(l, cv::CC_STAT_AREA) > area && touchesBorder(ss, l)) {
        best = l;
        area = ss.at<int>(l, cv::CC_STAT_AREA);
      }
    sleeve = best > 0 ? cv::Mat(sl == best) : cv::Mat(arm.size(), CV_8UC1, cv::Scalar(0));
  }

  // Principal direction of a mask's pixels (every 2nd row and column),
  // oriented from the border inwards; also the pixel mean and whether the
  // blob is elongated (else the direction means little).
  struct Axis {
    Eigen::Vector2d dir, mean;
    bool elongated;
  };
  auto principalAxis = [&](const cv::Mat& a, const cv::Mat& b) -> std::optional<Axis> {
    Eigen::Vector2d mean = Eigen::Vector2d::Zero();
    Eigen::Matrix2d scatter = Eigen::Matrix2d::Zero();
    int count = 0;
    for (int v = 0; v < a.rows; v += 2) {
      const uchar* ap = a.ptr<uchar>(v);
      const uchar* bp = b.empty() ? nullptr : b.ptr<uchar>(v);
      for (int u = 0; u < a.cols; u += 2) {
        if (!ap[u] && !(bp && bp[u])) continue;
        const Eigen::Vector2d p(u, v);
        mean += p;
        scatter += p * p.transpose();
        ++count;
      }
    }
    if (count < 3) return std::nullopt;
    mean /= count;
    scatter = scatter / count - mean * mean.transpose();
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(scatter);
    Axis out{eig.eigenvectors().col(1).normalized(), mean, eig.eigenvalues()(1) > 2.0 * eig.eigenvalues()(0)};
    if (out.dir.dot(mean - entry) < 0) out.dir = -out.dir;
    return out;
  };
  const auto handAxis = principalAxis(hand, cv::Mat());
  if (!handAxis) return std::nullopt;
  const Eigen::Vector2d handMean = handAxis->mean;
  // Depth of the hand (median of its valid pixels) for the pixel scale.
  std::optional<double> z_hand = medianDepthInDisc(depth, hand, handMean, 1e4, 5);
  if (!z_hand && lastDepth_m_ > 0.0) z_hand = lastDepth_m_;
  if (!z_hand) return std::nullopt;  // no scale yet: the first frames of the hand are all depth holes
  const double pxPerM = k.fx_px / *z_hand;

  // Wrist: the cuff line, skin pixels next to the sleeve. Not when the skin
  // itself reaches the border (the hand entering or leaving: the cuff is out
  // of view, the "sleeve" may be something else).
  int handOnBorder = 0;
  for (int v = 0; v < hand.rows; ++v) {
    const uchar* p = hand.ptr<uchar>(v);
    if (v <= 1 || v >= hand.rows - 2) handOnBorder += cv::countNonZero(hand.row(v));
    else handOnBorder += (p[0] || p[1]) + (p[hand.cols - 1] || p[hand.cols - 2]);
  }
  constexpr int kMinCuffPixels = 10;
  Eigen::Vector2d wrist = Eigen::Vector2d::Zero();
  int nCuff = 0;
  if (handOnBorder < kMinCuffPixels && cv::countNonZero(sleeve) > 0) {
    cv::Mat near;
    cv::dilate(sleeve, near, disc5);
    near &= hand;
    for (int v = 0; v < near.rows; ++v) {
      const uchar* p = near.ptr<uchar>(v);
      for (int u = 0; u < near.cols; ++u)
        if (p[u]) {
          wrist += Eigen::Vector2d(u, v);
          ++nCuff;
        }
    }
  }
  // The palm is placed in metres: the anchor (cuff line or fingertips)
  // back-projected at the palm's depth, then a fixed length along the axis
  // in that plane. (The cuff's own depth is no help: the median there is the
  // sleeve's, centimetres above the wrist's skin.)
  Eigen::Vector2d anchor_px, dir;
  double length_m = 0.0;
  if (nCuff >= kMinCuffPixels) {
    // The palm a fixed length from the cuff along the arm (sleeve + hand) axis.
    anchor_px = wrist / nCuff;
    dir = principalAxis(hand, sleeve)->dir;
    length_m = options_.palmFromWrist_m;
    geometry_.haveWrist = true;
    geometry_.wrist_px = anchor_px;
  } else {
    // The palm a fixed length back from the fingertips along the hand's axis
    // (or, for a short blob, the inward normal of the border the arm enters
    // from), on the hand's centre line.
    dir = handAxis->dir;
    if (!handAxis->elongated) {
      const double du = std::min(entry.x(), hand.cols - 1 - entry.x()), dv = std::min(entry.y(), hand.rows - 1 - entry.y());
      dir = du < dv ? Eigen::Vector2d(entry.x() < hand.cols / 2 ? 1 : -1, 0) : Eigen::Vector2d(0, entry.y() < hand.rows / 2 ? 1 : -1);
    }
    double tip = -1e9;
    for (int v = 0; v < hand.rows; v += 2) {
      const uchar* p = hand.ptr<uchar>(v);
      for (int u = 0; u < hand.cols; u += 2)
        if (p[u]) tip = std::max(tip, (Eigen::Vector2d(u, v) - handMean).dot(dir));
    }
    anchor_px = handMean + tip * dir;
    length_m = -options_.palmFromFingertips_m;
  }
  geometry_.axis = dir;
  const Eigen::Vector2d dir_m = Eigen::Vector2d(dir.x() / k.fx_px, dir.y() / k.fy_px).normalized();
  auto palmAt = [&](double z_m) {  // palm centre if it lies at depth z_m
    return Eigen::Vector3d((anchor_px.x() - k.cx_px) * z_m / k.fx_px + length_m * dir_m.x(),
                           (anchor_px.y() - k.cy_px) * z_m / k.fy_px + length_m * dir_m.y(), z_m);
  };
  auto project = [&](const Eigen::Vector3d& p) {
    return Eigen::Vector2d(k.fx_px * p.x() / p.z() + k.cx_px, k.fy_px * p.y() / p.z() + k.cy_px);
  };
  // First at the hand's depth (for the palm disc), then at the palm's own.
  Eigen::Vector2d palm = project(palmAt(*z_hand + options_.palmDepth_m));
  HandObservation h;
  h.confidence = std::min(1.0, bestArea / 3000.0) * (geometry_.haveWrist ? 1.0 : 0.5);
  std::optional<double> z = medianDepthInDisc(depth, hand, palm, options_.palmRadius_m * pxPerM, 5);
  // No depth on the palm (a hole, or the palm out of view while the fingers
  // enter or leave): the last palm depth if it is a few frames old (the caller
  // carries it along the ray), else the whole hand's (biased by the fingers'
  // and the wrist's tilt, but the best there is).
  constexpr int kMaxCarryFrames = 3;
  if (!z && lastDepth_m_ > 0.0 && frameCount_ - lastDepthFrame_ <= kMaxCarryFrames) {
    palm = project(palmAt(lastDepth_m_ + options_.palmDepth_m));
  } else {
    if (!z) z = medianDepthInDisc(depth, hand, handMean, 1e4, 5);
    if (z) {
      h.p_camera_palm_m = palmAt(*z + options_.palmDepth_m);
      palm = project(h.p_camera_palm_m);
      h.hasDepth = true;
      lastDepth_m_ = *z;
      lastDepthFrame_ = frameCount_;
    }
  }
  h.palm_px = palm;
  geometry_.palm_px = palm;
  return h;
}

}  // namespace srp::perception
