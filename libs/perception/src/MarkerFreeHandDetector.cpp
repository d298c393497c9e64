#include "srp/perception/MarkerFreeHandDetector.h"

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

}  // namespace

MarkerFreeHandDetector::MarkerFreeHandDetector(const Options& options) : options_(options) {
  core::require(options.backgroundFrames >= 1, "MarkerFreeHandDetector: backgroundFrames must be >= 1");
}

std::optional<HandObservation> MarkerFreeHandDetector::detect(const rawlog::RgbdFrame& frame) {
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
  const bool hasColour = !frame.colour_bgr8.empty();
  cv::Mat skin(depth.size(), CV_8UC1, cv::Scalar(255));
  if (options_.useSkin && hasColour) {
    cv::Mat ycrcb;
    cv::cvtColor(frame.colour_bgr8, ycrcb, cv::COLOR_BGR2YCrCb);
    cv::inRange(ycrcb, cv::Scalar(0, 135, 80), cv::Scalar(255, 180, 130), skin);
  }
  cv::Mat mask(depth.size(), CV_8UC1, cv::Scalar(0));
  for (int v = 0; v < depth.rows; ++v) {
    const float* z = depth.ptr<float>(v);
    const float* bg = backgroundDepth_m_.ptr<float>(v);
    const uchar* s = skin.ptr<uchar>(v);
    uchar* m = mask.ptr<uchar>(v);
    for (int u = 0; u < depth.cols; ++u) {
      if (!s[u]) continue;
      if (z[u] > 0.f && bg[u] > 0.f) m[u] = (bg[u] - z[u] > options_.minForeground_m) ? 255 : 0;
      else if (z[u] <= 0.f && hasColour) {
        // A hole (moving hand): foreground when the colour changed.
        const cv::Vec3b a = frame.colour_bgr8.at<cv::Vec3b>(v, u), b = backgroundColour_.at<cv::Vec3b>(v, u);
        const int diff = std::abs(a[0] - b[0]) + std::abs(a[1] - b[1]) + std::abs(a[2] - b[2]);
        m[u] = diff > 60 ? 255 : 0;
      }
    }
  }
  cv::morphologyEx(mask, mask, cv::MORPH_OPEN, cv::getStructuringElement(cv::MORPH_ELLIPSE, {5, 5}));
  lastMask_ = mask;
  cv::Mat labels, stats, centroids;
  const int n = cv::connectedComponentsWithStats(mask, labels, stats, centroids, 8, CV_32S);
  int bestLabel = -1, bestArea = 0;
  bool bestTouches = false;
  for (int l = 1; l < n; ++l) {
    const int x = stats.at<int>(l, cv::CC_STAT_LEFT), y = stats.at<int>(l, cv::CC_STAT_TOP);
    const int w = stats.at<int>(l, cv::CC_STAT_WIDTH), h = stats.at<int>(l, cv::CC_STAT_HEIGHT);
    const int area = stats.at<int>(l, cv::CC_STAT_AREA);
    if (area < options_.minPixels) continue;
    const bool touches = x <= 1 || y <= 1 || x + w >= mask.cols - 1 || y + h >= mask.rows - 1;
    // Prefer components the arm connects to the border; then size.
    if ((touches && !bestTouches) || (touches == bestTouches && area > bestArea)) {
      bestLabel = l;
      bestArea = area;
      bestTouches = touches;
    }
  }
  if (bestLabel < 0) return std::nullopt;
  cv::Mat hand = (labels == bestLabel);
  // Entry point: mean of the component's border pixels (none: its centroid).
  Eigen::Vector2d entry = Eigen::Vector2d::Zero();
  int nBorder = 0;
  for (int v = 0; v < hand.rows; ++v)
    for (int u = 0; u < hand.cols; ++u)
      if (hand.at<uchar>(v, u) && (u <= 1 || v <= 1 || u >= hand.cols - 2 || v >= hand.rows - 2)) {
        entry += Eigen::Vector2d(u, v);
        ++nBorder;
      }
  if (nBorder > 0) entry /= nBorder;
  else entry = {centroids.at<double>(bestLabel, 0), centroids.at<double>(bestLabel, 1)};
  cv::Mat dist;
  cv::distanceTransform(hand, dist, cv::DIST_L2, 5);
  double farthest = 0.0;
  for (int v = 0; v < hand.rows; ++v)
    for (int u = 0; u < hand.cols; ++u)
      if (hand.at<uchar>(v, u)) farthest = std::max(farthest, (Eigen::Vector2d(u, v) - entry).norm());
  // The palm: the thickest part in the outer half (away from the arm).
  double bestDist = 0.0;
  Eigen::Vector2d palm(-1, -1);
  for (int v = 0; v < hand.rows; ++v) {
    const float* d = dist.ptr<float>(v);
    for (int u = 0; u < hand.cols; ++u)
      if (d[u] > bestDist && (nBorder == 0 || (Eigen::Vector2d(u, v) - entry).norm() > 0.45 * farthest)) {
        bestDist = d[u];
        palm = {u, v};
      }
  }
  if (palm.x() < 0) return std::nullopt;
  HandObservation h;
  h.palm_px = palm;
  h.confidence = std::min(1.0, bestArea / 3000.0);
  // Median depth of the valid hand pixels in the palm disc.
  const int r = std::max(2, static_cast<int>(bestDist * 0.7));
  std::vector<float> depths;
  for (int v = std::max(0, static_cast<int>(palm.y()) - r); v <= std::min(hand.rows - 1, static_cast<int>(palm.y()) + r); ++v)
    for (int u = std::max(0, static_cast<int>(palm.x()) - r); u <= std::min(hand.cols - 1, static_cast<int>(palm.x()) + r); ++u)
      if (hand.at<uchar>(v, u) && depth.at<float>(v, u) > 0.f &&
          (Eigen::Vector2d(u, v) - palm).squaredNorm() <= static_cast<double>(r) * r)
        depths.push_back(depth.at<float>(v, u));
  if (depths.size() >= 5) {
    std::nth_element(depths.begin(), depths.begin() + depths.size() / 2, depths.end());
    const double z = depths[depths.size() / 2] + options_.palmDepth_m;
    const auto& k = frame.intrinsics;
    h.p_camera_palm_m = {(palm.x() - k.cx_px) * z / k.fx_px, (palm.y() - k.cy_px) * z / k.fy_px, z};
    h.hasDepth = true;
  }
  return h;
}

}  // namespace srp::perception
