#include "srp/perception/EdgeYawRefiner.h"
#include "srp/core/Log.h"

#include "srp/core/Angles.h"
#include "srp/perception/SegmentColour.h"

#include <cmath>
#include <complex>
#include <cstdio>
#include <cstdlib>
#include <opencv2/imgproc.hpp>
#include <optional>
#include <vector>

namespace srp::perception {
using srp::core::kPi;

EdgeYawRefiner::EdgeYawRefiner(const ObjectModel& model) : EdgeYawRefiner(model, Options{}) {}

EdgeYawRefiner::EdgeYawRefiner(const ObjectModel& model, const Options& options)
    : options_(options), top_m_(model.dimensions_m.z()) {
  // Orders 4 and 8 only: for them an edge's tangent and its normal give the
  // same exp(i m angle), so the image's edge tangents compare with the model's normals.
  for (int m : {4, 8}) {
    std::complex<double> sum = 0.0;
    double weight = 0.0;
    for (const kb::SurfacePoint& s : model.surface) {
      if (std::abs(s.n.z()) > options_.sideMaxNormalZ) continue;  // side faces only
      sum += std::polar(1.0, m * std::atan2(s.n.y(), s.n.x()));
      weight += 1.0;
    }
    if (weight > 0 && std::abs(sum) / weight > options_.regularOutlineCoherence) {
      order_ = m;
      modelPhase_rad_ = std::arg(sum);
      break;
    }
  }
  if (order_ != 0) return;
  // Other polygonal outlines (parallelogram, star): the distinct directions of
  // the side normals, modulo pi (an image edge has no inside), 1-degree bins.
  constexpr int kBins = 180;
  std::vector<double> hist(kBins, 0.0);
  double sides = 0.0;
  for (const kb::SurfacePoint& s : model.surface) {
    if (std::abs(s.n.z()) > options_.sideMaxNormalZ) continue;
    const double a = std::fmod(std::atan2(s.n.y(), s.n.x()) + 2 * kPi, kPi);
    hist[static_cast<std::size_t>(std::min(kBins - 1.0, std::floor(a / kPi * kBins)))] += 1.0;
    sides += 1.0;
  }
  if (sides <= 0) return;
  double covered = 0.0;
  for (int b = 0; b < kBins; ++b) {
    const double h = hist[static_cast<std::size_t>(b)];
    const double left = hist[static_cast<std::size_t>((b + kBins - 1) % kBins)], right = hist[static_cast<std::size_t>((b + 1) % kBins)];
    if (h < options_.minDirectionShare * sides || h < left || h <= right) continue;  // local peaks only
    // Weighted mean over the peak and its neighbours (a face's normal may straddle two bins).
    const double c = (b + 0.5) * kPi / kBins;
    const double mean = c + (right - left) / (left + h + right) * kPi / kBins;
    sideNormals_rad_.push_back(mean);
    covered += left + h + right;
  }
  // Curved outlines (a cylinder) spread their normals: no sharp directions.
  // Many short edges (the star's ten) give corner-dominated votes, and depth
  // fixes such a part's yaw well by itself (the star: 1.0 deg yaw median
  // without, 3.2 deg with): long straight edges in few directions only.
  if (sideNormals_rad_.size() > static_cast<std::size_t>(options_.maxOutlineDirections) ||
      covered < options_.minDirectionsCover * sides)
    sideNormals_rad_.clear();
}

namespace {

/// The segment's outline as the refiner reads it: a ring of pixels around the
/// depth segment inside `roi`, the colour patch under it, and the plane-frame
/// directions `ex`, `ey` of one pixel step in u and v at the part's centre.
struct OutlineView {
  cv::Rect roi;
  cv::Mat ring;   ///< CV_8U, roi-sized: 255 on the outline ring
  cv::Mat patch;  ///< the colour image inside roi
  Eigen::Vector3d ex, ey;
  double yawFit = 0.0;  ///< the fitted pose's yaw in the plane frame [rad]
};

/// The outline of `segmentPixels` and the image-to-plane Jacobian on the plane
/// parallel to the support at the model's top height `top_m`; nullopt when the
/// region is too small.
std::optional<OutlineView> outlineView(const core::Pose3& X_camera_object, const std::vector<cv::Point>& segmentPixels,
                                       const cv::Mat& colour_bgr8, const CameraModel& camera, const Plane& plane,
                                       int ringWidth_px, double top_m) {
  OutlineView view;
  const int margin = ringWidth_px + 3;
  cv::Rect roi = cv::boundingRect(segmentPixels);
  roi.x -= margin;
  roi.y -= margin;
  roi.width += 2 * margin;
  roi.height += 2 * margin;
  roi &= cv::Rect(0, 0, colour_bgr8.cols, colour_bgr8.rows);
  if (roi.width < 5 || roi.height < 5) return std::nullopt;
  view.roi = roi;

  // Ring around the segment's outline.
  cv::Mat mask(roi.size(), CV_8U, cv::Scalar(0));
  for (const cv::Point& p : segmentPixels) mask.at<std::uint8_t>(p.y - roi.y, p.x - roi.x) = 255;
  const cv::Mat kernel = cv::getStructuringElement(cv::MORPH_ELLIPSE, {2 * ringWidth_px + 1, 2 * ringWidth_px + 1});
  cv::Mat dilated, eroded;
  cv::morphologyEx(mask, mask, cv::MORPH_CLOSE, kernel);  // depth holes inside the segment are no outline
  cv::dilate(mask, dilated, kernel);
  cv::erode(mask, eroded, kernel);
  view.ring = dilated - eroded;

  view.patch = colour_bgr8(roi);

  // Plane-frame direction of an image tangent at pixel (u, v), on the plane
  // parallel to the support at the model's top height.
  const core::Pose3 X_camera_plane = plane.X_camera_plane();
  const core::Pose3 X_plane_camera = X_camera_plane.inverse();
  const auto& k = camera.intrinsics();
  auto onTop = [&](double u, double v) -> std::optional<Eigen::Vector3d> {
    const Eigen::Vector3d ray((u - k.cx_px) / k.fx_px, (v - k.cy_px) / k.fy_px, 1.0);
    const auto s = plane.rayScaleAtHeight(ray, top_m);
    if (!s) return std::nullopt;
    return Eigen::Vector3d(*s * ray);
  };
  const Eigen::Vector2d centre_px = camera.cameraToPixel(X_camera_object * Eigen::Vector3d(0, 0, top_m));
  const auto P0 = onTop(centre_px.x(), centre_px.y());
  const auto Px = onTop(centre_px.x() + 1, centre_px.y());
  const auto Py = onTop(centre_px.x(), centre_px.y() + 1);
  if (!P0 || !Px || !Py) return std::nullopt;  // the part's top seen edge-on or from below
  view.ex = X_plane_camera.linear() * (*Px - *P0);
  view.ey = X_plane_camera.linear() * (*Py - *P0);
  // The image-to-plane map is nearly affine over a part's few dozen pixels:
  // its Jacobian at the part's centre maps every tangent.

  const core::Pose3 X_plane_object = X_plane_camera * X_camera_object;
  view.yawFit = std::atan2(X_plane_object.linear()(1, 0), X_plane_object.linear()(0, 0));
  return view;
}

/// Order 0 (polygonal outlines): the turn that lines the model's side normals
/// up with the edge normals: each edge pixel votes with a kernel (sigma ~3
/// deg) around every model direction, searched within maxCorrection of the
/// fit. Edges of the part's own colour only (a box wall beside it, the floor's
/// texture do not vote): the gradient of each pixel's likeness to the top
/// face's colour (the median colour of the depth segment). nullopt when the
/// edges are too few or incoherent, or the optimum lies at the search's border.
std::optional<double> sideNormalCorrection(const OutlineView& view, const std::vector<cv::Point>& segmentPixels,
                                           const cv::Mat& colour_bgr8, const std::vector<double>& sideNormals_rad,
                                           const EdgeYawRefiner::Options& options) {
  const cv::Rect& roi = view.roi;
  const cv::Vec3b topColour = medianColour(segmentPixels, colour_bgr8);
  cv::Mat likeness(roi.size(), CV_32F);
  for (int y = 0; y < roi.height; ++y) {
    const cv::Vec3b* c = view.patch.ptr<cv::Vec3b>(y);
    float* l = likeness.ptr<float>(y);
    for (int x = 0; x < roi.width; ++x) {
      int d = 0;
      for (int k3 = 0; k3 < 3; ++k3)
        d = std::max(d, std::abs(static_cast<int>(c[x][k3]) - static_cast<int>(topColour[k3])));
      const double r = d / (255.0 * options.colourLikeness);
      l[x] = static_cast<float>(std::exp(-r * r));
    }
  }
  cv::Mat lx, ly;
  cv::Sobel(likeness, lx, CV_32F, 1, 0, 5);
  cv::Sobel(likeness, ly, CV_32F, 0, 1, 5);
  constexpr int kNormalBins = 720;  // edge normals modulo pi, 0.25-degree bins
  std::vector<double> normals(kNormalBins, 0.0);
  int partEdgePixels = 0;
  double partWeight = 0.0;
  for (int y = 0; y < roi.height; ++y) {
    const std::uint8_t* r = view.ring.ptr<std::uint8_t>(y);
    for (int x = 0; x < roi.width; ++x) {
      if (!r[x]) continue;
      const double gx1 = lx.at<float>(y, x), gy1 = ly.at<float>(y, x);
      const double strength = gx1 * gx1 + gy1 * gy1;
      if (strength < options.minLikenessGradient2) continue;  // a full step gives ~48^2
      const double theta = std::atan2(gy1, gx1);              // gradient direction
      const Eigen::Vector3d t = -std::sin(theta) * view.ex + std::cos(theta) * view.ey;
      const double normal = std::fmod(std::atan2(t.y(), t.x()) + 0.5 * kPi + 4 * kPi, kPi);
      normals[static_cast<std::size_t>(std::min(kNormalBins - 1.0, std::floor(normal / kPi * kNormalBins)))] +=
          strength;
      partWeight += strength;
      ++partEdgePixels;
    }
  }
  if (partEdgePixels < options.minEdgePixels || partWeight <= 0) return std::nullopt;
  const double binWidth = kPi / kNormalBins;
  constexpr int kReach = 48;  // 12 deg = 4 sigma
  std::vector<double> kernel(2 * kReach + 1);
  for (int d = -kReach; d <= kReach; ++d)
    kernel[static_cast<std::size_t>(d + kReach)] = std::exp(90.0 * (std::cos(2 * d * binWidth) - 1.0));
  const int steps = static_cast<int>(options.maxCorrection_rad / binWidth);
  auto score = [&](int step) {
    double v = 0.0;
    for (double beta : sideNormals_rad) {
      const int c =
          static_cast<int>(std::lround(std::fmod(beta + view.yawFit + step * binWidth + 8 * kPi, kPi) / binWidth));
      for (int d = -kReach; d <= kReach; ++d)
        v += normals[static_cast<std::size_t>(((c + d) % kNormalBins + kNormalBins) % kNormalBins)] *
             kernel[static_cast<std::size_t>(d + kReach)];
    }
    return v;
  };
  int best = 0;
  double bestScore = -1.0;
  std::vector<double> scores(static_cast<std::size_t>(2 * steps + 1));
  for (int st = -steps; st <= steps; ++st) {
    scores[static_cast<std::size_t>(st + steps)] = score(st);
    if (scores[static_cast<std::size_t>(st + steps)] > bestScore) {
      bestScore = scores[static_cast<std::size_t>(st + steps)];
      best = st;
    }
  }
  const double coherence = bestScore / partWeight;
  if (core::Log::enabled("perception", core::Log::Level::Debug))
    core::Log::writef("perception", core::Log::Level::Debug, "edges (%zu directions): %d px, coherence %.2f, correction %.2f deg\n", sideNormals_rad.size(),
                 partEdgePixels, coherence, best * binWidth * 180 / kPi);
  // At the search's border the optimum lies beyond it: distrusted.
  if (coherence < options.minOutlineCoherence || std::abs(best) >= steps) return std::nullopt;
  const double l = scores[static_cast<std::size_t>(best + steps - 1)], c = bestScore,
               r = scores[static_cast<std::size_t>(best + steps + 1)];
  const double sub = (l - 2 * c + r) < 0 ? 0.5 * (l - r) / (l - 2 * c + r) : 0.0;
  return (best + sub) * binWidth;
}

/// m-fold regular outlines (`order` 4 or 8): the circular mean of the colour
/// edges' tangents (structure tensor of the three channels), times m, against
/// the model's phase; the branch nearest the fit. nullopt when the edges are
/// too few or incoherent, or the correction exceeds maxCorrection.
std::optional<double> regularOutlineCorrection(const OutlineView& view, int order, double modelPhase_rad,
                                               const EdgeYawRefiner::Options& options) {
  cv::Mat gx, gy;
  cv::Sobel(view.patch, gx, CV_32F, 1, 0, 5);
  cv::Sobel(view.patch, gy, CV_32F, 0, 1, 5);
  std::complex<double> sum = 0.0;
  double weight = 0.0;
  int edgePixels = 0;
  for (int y = 0; y < view.roi.height; ++y) {
    const std::uint8_t* r = view.ring.ptr<std::uint8_t>(y);
    const cv::Vec3f* ax = gx.ptr<cv::Vec3f>(y);
    const cv::Vec3f* ay = gy.ptr<cv::Vec3f>(y);
    for (int x = 0; x < view.roi.width; ++x) {
      if (!r[x]) continue;
      double jxx = 0, jyy = 0, jxy = 0;
      for (int c = 0; c < 3; ++c) {
        jxx += ax[x][c] * ax[x][c];
        jyy += ay[x][c] * ay[x][c];
        jxy += ax[x][c] * ay[x][c];
      }
      const double strength = std::sqrt((jxx - jyy) * (jxx - jyy) + 4 * jxy * jxy);
      if (strength < options.minStructureStrength) continue;      // flat
      const double theta = 0.5 * std::atan2(2 * jxy, jxx - jyy);  // gradient direction, mod pi
      const Eigen::Vector3d t = -std::sin(theta) * view.ex + std::cos(theta) * view.ey;  // tangent on the plane
      const double tangent = std::atan2(t.y(), t.x());
      sum += strength * std::polar(1.0, order * tangent);
      weight += strength;
      ++edgePixels;
    }
  }
  if (core::Log::enabled("perception", core::Log::Level::Debug))
    core::Log::writef("perception", core::Log::Level::Debug, "edges: %d px, coherence %.2f\n", edgePixels, std::abs(sum) / std::max(1e-9, weight));
  if (edgePixels < options.minEdgePixels || std::abs(sum) < options.minCoherence * weight) return std::nullopt;

  const double yawEdges = (std::arg(sum) - modelPhase_rad) / order;
  const double period = 2 * kPi / order;
  double delta = std::remainder(yawEdges - view.yawFit, period);  // the branch nearest the fit
  if (core::Log::enabled("perception", core::Log::Level::Debug))
    core::Log::writef("perception", core::Log::Level::Debug, "edges: fit yaw %.2f deg, edge yaw %.2f deg, correction %.2f deg\n", view.yawFit * 180 / kPi,
                 yawEdges * 180 / kPi, delta * 180 / kPi);
  if (std::abs(delta) > options.maxCorrection_rad) return std::nullopt;
  return delta;
}

}  // namespace

std::optional<core::Pose3> EdgeYawRefiner::refine(const core::Pose3& X_camera_object,
                                                  const std::vector<cv::Point>& segmentPixels,
                                                  const cv::Mat& colour_bgr8, const CameraModel& camera,
                                                  const Plane& plane) const {
  if ((order_ == 0 && sideNormals_rad_.empty()) || colour_bgr8.empty() || segmentPixels.size() < 10)
    return std::nullopt;
  const std::optional<OutlineView> view =
      outlineView(X_camera_object, segmentPixels, colour_bgr8, camera, plane, options_.ringWidth_px, top_m_);
  if (!view) return std::nullopt;
  const std::optional<double> delta =
      order_ == 0 ? sideNormalCorrection(*view, segmentPixels, colour_bgr8, sideNormals_rad_, options_)
                  : regularOutlineCorrection(*view, order_, modelPhase_rad_, options_);
  if (!delta) return std::nullopt;
  core::Pose3 X = X_camera_object;
  X.linear() = X_camera_object.linear() * Eigen::AngleAxisd(*delta, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  return X;
}

}  // namespace srp::perception
