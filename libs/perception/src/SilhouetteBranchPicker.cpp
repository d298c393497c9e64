#include "srp/perception/SilhouetteBranchPicker.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "srp/perception/SegmentColour.h"

namespace srp::perception {

std::optional<std::size_t> SilhouetteBranchPicker::pick(const kb::TriangleMesh& mesh, const std::vector<core::Pose3>& candidates,
                                                        const std::vector<cv::Point>& segmentPixels, const cv::Mat& colour_bgr8,
                                                        const CameraModel& camera, std::vector<double>* iou) const {
  if (candidates.empty() || colour_bgr8.empty() || segmentPixels.empty() || mesh.empty()) return std::nullopt;
  cv::Rect roi = cv::boundingRect(segmentPixels);
  roi.x -= options_.margin_px;
  roi.y -= options_.margin_px;
  roi.width += 2 * options_.margin_px;
  roi.height += 2 * options_.margin_px;
  roi &= cv::Rect(0, 0, colour_bgr8.cols, colour_bgr8.rows);
  if (roi.area() == 0) return std::nullopt;

  // Pixels of the colour of the part's top face: the median colour of its
  // depth segment (a part seen from above shows mostly its top).
  const cv::Vec3b topColour = medianColour(segmentPixels, colour_bgr8);
  const int maxDiff = static_cast<int>(std::lround(255 * options_.maxColourDifference));
  cv::Mat colourMask(roi.size(), CV_8U, cv::Scalar(0));
  for (int y = 0; y < roi.height; ++y) {
    const cv::Vec3b* c = colour_bgr8.ptr<cv::Vec3b>(roi.y + y) + roi.x;
    std::uint8_t* m = colourMask.ptr<std::uint8_t>(y);
    for (int x = 0; x < roi.width; ++x) {
      int d = 0;
      for (int k = 0; k < 3; ++k) d = std::max(d, std::abs(static_cast<int>(c[x][k]) - static_cast<int>(topColour[k])));
      m[x] = d <= maxDiff ? 255 : 0;
    }
  }

  // Each candidate's silhouette: its mesh triangles filled (sub-pixel vertices).
  double topZ = -1e9;
  topZ = mesh.bounds().max().z();
  topZ -= 1e-4;
  constexpr int kShift = 4;  // fillConvexPoly's fractional bits
  std::vector<double> local;
  std::vector<double>& agreements = iou ? *iou : local;
  agreements.clear();
  // Rendered kSuper times finer, then averaged: fillConvexPoly's filled
  // pixels include the outline's, a pixel too many all around at full size.
  constexpr int kSuper = 4;
  cv::Mat fine(roi.height * kSuper, roi.width * kSuper, CV_8U), silhouette;
  for (std::size_t k = 0; k < candidates.size(); ++k) {
    fine.setTo(0);
    for (const auto& t : mesh.triangles()) {
      const Eigen::Vector3d& a = t[0];
      const Eigen::Vector3d n = (t[1] - a).cross(t[2] - a);
      if (n.z() < 0.9 * n.norm() || a.z() < topZ) continue;  // the top face only
      cv::Point corners[3];
      bool inFront = true;
      for (int i = 0; i < 3; ++i) {
        const Eigen::Vector3d p = candidates[k] * t[i];
        if (p.z() <= 0.0) inFront = false;
        const Eigen::Vector2d px = camera.cameraToPixel(p);
        // Pixel centres at integers in both images: x -> S (x + 0.5) - 0.5.
        corners[i] = cv::Point(static_cast<int>(std::lround((kSuper * (px.x() - roi.x + 0.5) - 0.5) * (1 << kShift))),
                               static_cast<int>(std::lround((kSuper * (px.y() - roi.y + 0.5) - 0.5) * (1 << kShift))));
      }
      if (inFront) cv::fillConvexPoly(fine, corners, 3, cv::Scalar(255), cv::LINE_8, kShift);
    }
    // A pixel belongs to the silhouette when the outline covers most of it.
    cv::resize(fine, silhouette, roi.size(), 0, 0, cv::INTER_AREA);
    cv::threshold(silhouette, silhouette, 127, 255, cv::THRESH_BINARY);
    const double inter = cv::countNonZero(silhouette & colourMask);
    const double uni = cv::countNonZero(silhouette | colourMask);
    const double agreement = uni > 0 ? inter / uni : 0.0;
    agreements.push_back(agreement);
  }
  std::optional<std::size_t> best;
  double bestIoU = 0.0, secondIoU = 0.0;
  for (std::size_t k = 0; k < agreements.size(); ++k) {
    if (agreements[k] > bestIoU) {
      secondIoU = bestIoU;
      bestIoU = agreements[k];
      best = k;
    } else if (agreements[k] > secondIoU) {
      secondIoU = agreements[k];
    }
  }
  // A partial view (the hand in front) fits every turn about as badly.
  if (bestIoU < options_.minIoU || bestIoU - secondIoU < options_.minMargin) return std::nullopt;
  return best;
}

}  // namespace srp::perception
