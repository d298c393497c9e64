#include "srp/perception/MarkerHandDetector.h"

#include <algorithm>
#include <opencv2/imgproc.hpp>
#include <vector>

namespace srp::perception {

MarkerHandDetector::MarkerHandDetector(const Options& options)
    : options_(options), tags_({options.tagSize_m, options.quadDecimate, 1}) {}

std::optional<cv::Rect> MarkerHandDetector::changedRegion(const cv::Mat& grey) const {
  if (!options_.searchChangedRegionOnly || previousGrey_.empty() || previousGrey_.size() != grey.size())
    return std::nullopt;
  // Changed pixels, counted per 8x8 block so that sensor noise does not count.
  constexpr int kBlock = 8;
  cv::Mat diff, changed, blocks;
  cv::absdiff(grey, previousGrey_, diff);
  cv::threshold(diff, changed, options_.changeThreshold, 255, cv::THRESH_BINARY);
  cv::resize(changed, blocks, cv::Size(grey.cols / kBlock, grey.rows / kBlock), 0, 0, cv::INTER_AREA);
  cv::threshold(blocks, blocks, 255.0 * 4 / (kBlock * kBlock) - 1, 255, cv::THRESH_BINARY);  // >= 4 pixels of 64
  std::vector<cv::Point> at;
  cv::findNonZero(blocks, at);
  if (at.empty()) return cv::Rect();
  cv::Rect r = cv::boundingRect(at);
  r = cv::Rect(r.x * kBlock, r.y * kBlock, r.width * kBlock, r.height * kBlock);
  // A tag only partly inside the change (an edge sharpened after blur) is
  // still found: the margin is half the region, at least `changeMargin_px`.
  const int margin = std::max(options_.changeMargin_px, std::max(r.width, r.height) / 2);
  r = cv::Rect(r.x - margin, r.y - margin, r.width + 2 * margin, r.height + 2 * margin);
  return r & cv::Rect(0, 0, grey.cols, grey.rows);
}

std::optional<HandObservation> MarkerHandDetector::detect(const rawlog::RgbdFrame& frame) {
  auto best = [this](const std::vector<TagDetection>& tags) {
    const TagDetection* tag = nullptr;
    for (const auto& t : tags)
      if ((options_.tagId < 0 || t.id == options_.tagId) && (!tag || t.reprojectionError_px < tag->reprojectionError_px))
        tag = &t;
    return tag;
  };
  std::vector<TagDetection> tags;
  const TagDetection* tag = nullptr;
  cv::Mat grey;
  if (frame.colour_bgr8.channels() == 3) cv::cvtColor(frame.colour_bgr8, grey, cv::COLOR_BGR2GRAY);
  else grey = frame.colour_bgr8;
  const cv::Rect image(0, 0, grey.cols, grey.rows);
  // A window detected as an image of its own (principal point shifted).
  auto searchWindow = [&](const cv::Rect& window) {
    core::CameraIntrinsics k = frame.intrinsics;
    k.cx_px -= window.x;
    k.cy_px -= window.y;
    k.width_px = window.width;
    k.height_px = window.height;
    if (window.width < 32 || window.height < 32) return;
    tags = tags_.detect(grey(window), k);
    const Eigen::Vector2d offset(window.x, window.y);
    for (auto& t : tags) {
      for (auto& c : t.corners_px) c += offset;
      t.centre_px += offset;
    }
    tag = best(tags);
  };
  if (lastTagBox_px_ && options_.trackWindowTagSides > 0) {
    // The window around the last tag.
    const cv::Rect& b = *lastTagBox_px_;
    const int side = static_cast<int>(options_.trackWindowTagSides * std::max(b.width, b.height)) + 16;
    searchWindow(cv::Rect(b.x + b.width / 2 - side / 2, b.y + b.height / 2 - side / 2, side, side) & image);
  }
  if (!tag) {
    // Lost: the whole image, or only where it changed since the last frame
    // (a tag that was not found there cannot appear where nothing changed).
    const std::optional<cv::Rect> changed =
        ++lostFrames_ % std::max(1, options_.fullSearchEveryFrames) == 0 ? std::nullopt : changedRegion(grey);
    if (!changed || changed->area() > image.area() / 2) {
      tags = tags_.detect(grey, frame.intrinsics);
      tag = best(tags);
    } else if (changed->area() > 0) {
      searchWindow(*changed);
    }
  }
  lastTagBox_px_.reset();
  // The next frame's change is against this one, kept only while lost (the
  // conversion made `grey` a new image unless the frame was grey already).
  if (tag) lostFrames_ = 0;
  if (tag || !options_.searchChangedRegionOnly) previousGrey_.release();
  else previousGrey_ = grey.data == frame.colour_bgr8.data ? grey.clone() : grey;
  if (!tag) return std::nullopt;
  {
    std::vector<cv::Point2f> corners;
    for (const auto& c : tag->corners_px) corners.emplace_back(static_cast<float>(c.x()), static_cast<float>(c.y()));
    lastTagBox_px_ = cv::boundingRect(corners);
  }
  core::Pose3 X_camera_tag = tag->X_camera_tag;
  if (options_.useDepth && !frame.depth_m.empty()) {
    // Median depth of the valid pixels inside the tag (shrunk to stay off its edge).
    std::vector<cv::Point> poly;
    for (const auto& c : tag->corners_px) {
      const Eigen::Vector2d q = tag->centre_px + 0.7 * (c - tag->centre_px);
      poly.emplace_back(static_cast<int>(std::lround(q.x())), static_cast<int>(std::lround(q.y())));
    }
    const cv::Rect box = cv::boundingRect(poly) & cv::Rect(0, 0, frame.depth_m.cols, frame.depth_m.rows);
    std::vector<float> depths;
    for (int v = box.y; v < box.y + box.height; ++v)
      for (int u = box.x; u < box.x + box.width; ++u) {
        const float z = frame.depth_m.at<float>(v, u);
        if (z > 0.f && cv::pointPolygonTest(poly, cv::Point2f(static_cast<float>(u), static_cast<float>(v)), false) >= 0)
          depths.push_back(z);
      }
    if (depths.size() >= 8) {
      std::nth_element(depths.begin(), depths.begin() + depths.size() / 2, depths.end());
      const double zMedian = depths[depths.size() / 2];
      // Depth of the tag centre along its ray: the plane's depth at the centre pixel.
      const double zTag = X_camera_tag.translation().z();
      if (std::abs(zMedian - zTag) < options_.maxDepthDisagreement_m)
        X_camera_tag.translation() *= zMedian / zTag;
    }
  }
  HandObservation h;
  h.p_camera_palm_m = X_camera_tag * options_.p_tag_palm_m;
  h.palm_px = {frame.intrinsics.fx_px * h.p_camera_palm_m.x() / h.p_camera_palm_m.z() + frame.intrinsics.cx_px,
               frame.intrinsics.fy_px * h.p_camera_palm_m.y() / h.p_camera_palm_m.z() + frame.intrinsics.cy_px};
  h.hasDepth = true;
  h.confidence = 1.0 / (1.0 + tag->reprojectionError_px);
  return h;
}

}  // namespace srp::perception
