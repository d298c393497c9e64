#include "srp/perception/MarkerHandDetector.h"

#include <algorithm>
#include <opencv2/imgproc.hpp>
#include <vector>

namespace srp::perception {

MarkerHandDetector::MarkerHandDetector(const Options& options)
    : options_(options), tags_({options.tagSize_m, options.quadDecimate, 1}) {}

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
  if (lastTagBox_px_ && options_.trackWindowTagSides > 0) {
    // The window around the last tag, detected as an image of its own (principal point shifted).
    const cv::Rect& b = *lastTagBox_px_;
    const int side = static_cast<int>(options_.trackWindowTagSides * std::max(b.width, b.height)) + 16;
    const cv::Rect window =
        cv::Rect(b.x + b.width / 2 - side / 2, b.y + b.height / 2 - side / 2, side, side) &
        cv::Rect(0, 0, frame.colour_bgr8.cols, frame.colour_bgr8.rows);
    core::CameraIntrinsics k = frame.intrinsics;
    k.cx_px -= window.x;
    k.cy_px -= window.y;
    k.width_px = window.width;
    k.height_px = window.height;
    if (window.width >= 32 && window.height >= 32) {
      tags = tags_.detect(frame.colour_bgr8(window), k);
      const Eigen::Vector2d offset(window.x, window.y);
      for (auto& t : tags) {
        for (auto& c : t.corners_px) c += offset;
        t.centre_px += offset;
      }
      tag = best(tags);
    }
  }
  if (!tag) {
    tags = tags_.detect(frame.colour_bgr8, frame.intrinsics);
    tag = best(tags);
  }
  lastTagBox_px_.reset();
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
