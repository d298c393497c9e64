#include "srp/perception/MarkerFreeHandDetector.h"
#include "srp/core/Log.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <string>
#include <tuple>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "srp/core/Angles.h"
#include "srp/core/Error.h"
#include "srp/perception/CameraModel.h"
#include "srp/perception/CameraMotionEstimator.h"
#include "srp/perception/DepthCloud.h"
#include "srp/perception/LandingWindow.h"
#include "srp/perception/MaskMorphology.h"
#include "srp/perception/PlaneFit.h"

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

/// For each label of `labels` (n labels), does it have a pixel among `zone` (the zone's pixels)?
std::vector<char> labelsInZone(const cv::Mat& labels, int n, const std::vector<cv::Point>& zone) {
  std::vector<char> in(static_cast<std::size_t>(n), 0);
  for (const auto& p : zone) in[static_cast<std::size_t>(labels.at<int>(p))] = 1;
  return in;
}

/// The rows and columns where at least `minValid` of the pixels have a valid
/// (> 0) depth in `depth`: the depth camera's field of view in a registered
/// depth image (a band at the image's edge that the depth camera does not see
/// is no place an arm can be seen entering from).
cv::Rect depthFieldOfView(const cv::Mat& depth, double minValid) {
  cv::Mat valid = depth > 0, cols, rows;
  cv::reduce(valid, cols, 0, cv::REDUCE_AVG, CV_32F);  // 1 x W: share of valid rows per column (x255)
  cv::reduce(valid, rows, 1, cv::REDUCE_AVG, CV_32F);  // H x 1
  const float t = static_cast<float>(255.0 * minValid);
  int u0 = 0, u1 = depth.cols - 1, v0 = 0, v1 = depth.rows - 1;
  while (u0 < u1 && cols.at<float>(0, u0) < t) ++u0;
  while (u1 > u0 && cols.at<float>(0, u1) < t) --u1;
  while (v0 < v1 && rows.at<float>(v0, 0) < t) ++v0;
  while (v1 > v0 && rows.at<float>(v1, 0) < t) --v1;
  return {u0, v0, u1 - u0 + 1, v1 - v0 + 1};
}

/// The element of rank floor(q n) of `v` (q = 0.5: the median, the upper one of an even count);
/// `v` must not be empty.
double quantile(std::vector<double> v, double q) {
  const auto k = std::min(v.size() - 1, static_cast<std::size_t>(q * static_cast<double>(v.size())));
  std::nth_element(v.begin(), v.begin() + static_cast<long>(k), v.end());
  return v[k];
}

/// How arm-like a set of 3D points is (the skin of a bare forearm with its
/// hand, seen in one frame): its length along the principal direction
/// (2nd to 98th percentile) and its width across it (the second principal
/// direction, 5th to 95th percentile, over 0.9) in slices of `slice_m` along
/// the length that hold at least `minSlicePoints` points.
struct ArmShape {
  double length_m = 0.0;
  std::vector<double> widths_m;  ///< one per slice, along the length
};

ArmShape armShape(const std::vector<Eigen::Vector3d>& points, double slice_m, std::size_t minSlicePoints) {
  ArmShape shape;
  if (points.size() < 3 * minSlicePoints) return shape;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const auto& p : points) mean += p;
  mean /= static_cast<double>(points.size());
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  for (const auto& p : points) scatter += (p - mean) * (p - mean).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(scatter);
  const Eigen::Vector3d along = eig.eigenvectors().col(2), across = eig.eigenvectors().col(1);
  std::vector<double> t;
  t.reserve(points.size());
  for (const auto& p : points) t.push_back(along.dot(p - mean));
  const double t0 = quantile(t, 0.02), t1 = quantile(t, 0.98);
  shape.length_m = t1 - t0;
  const int slices = std::max(1, static_cast<int>(std::ceil(shape.length_m / slice_m)));
  std::vector<std::vector<double>> side(static_cast<std::size_t>(slices));
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (t[i] < t0 || t[i] > t1) continue;
    const int j = std::min(slices - 1, static_cast<int>((t[i] - t0) / slice_m));
    side[static_cast<std::size_t>(j)].push_back(across.dot(points[i] - mean));
  }
  for (const auto& s : side)
    if (s.size() >= minSlicePoints) shape.widths_m.push_back((quantile(s, 0.95) - quantile(s, 0.05)) / 0.9);
  return shape;
}

/// The point [m, camera frame] seen at pixel (u, v) [px] at depth z [m] (an undistorted pinhole; the
/// detector's per-pixel loops call it, so no CameraModel, whose conversion goes through ViSP).
inline Eigen::Vector3d pixelToCamera(const core::CameraIntrinsics& k, double u_px, double v_px, double z_m) {
  return {(u_px - k.cx_px) * z_m / k.fx_px, (v_px - k.cy_px) * z_m / k.fy_px, z_m};
}

/// The intrinsics of an image shrunk `factor` times (`width_px` x `height_px`), pixel centres kept:
/// u = factor (u_shrunk + 0.5) - 0.5.
core::CameraIntrinsics shrunkIntrinsics(const core::CameraIntrinsics& k, int factor, int width_px, int height_px) {
  const double f = factor;
  return {k.fx_px / f, k.fy_px / f, (k.cx_px + 0.5) / f - 0.5, (k.cy_px + 0.5) / f - 0.5, width_px, height_px};
}

/// `view` shrunk by `margin_px` on every side: the pixels a region may hold without being cut by its edge.
cv::Rect inset(const cv::Rect& view, int margin_px) {
  return {view.x + margin_px, view.y + margin_px, view.width - 2 * margin_px, view.height - 2 * margin_px};
}

/// A disc-shaped structuring element of this diameter [px].
cv::Mat disc(int diameter_px) { return cv::getStructuringElement(cv::MORPH_ELLIPSE, {diameter_px, diameter_px}); }

/// Per label of a cv::connectedComponentsWithStats result `stats`, 1 when its
/// bounding box comes within `margin_px` of the border of `view` (where an
/// arm enters); label 0, the background, 0.
std::vector<uchar> labelsAtBorder(const cv::Mat& stats, const cv::Rect& view, int margin_px) {
  std::vector<uchar> atBorder(static_cast<std::size_t>(stats.rows), 0);
  for (int l = 1; l < stats.rows; ++l) {
    const int x = stats.at<int>(l, cv::CC_STAT_LEFT), y = stats.at<int>(l, cv::CC_STAT_TOP);
    const int w = stats.at<int>(l, cv::CC_STAT_WIDTH), h = stats.at<int>(l, cv::CC_STAT_HEIGHT);
    atBorder[static_cast<std::size_t>(l)] = x <= view.x + margin_px || y <= view.y + margin_px ||
                                            x + w >= view.x + view.width - margin_px ||
                                            y + h >= view.y + view.height - margin_px;
  }
  return atBorder;
}

/// Per pixel, the quantile `q` of the samples' valid depths (CV_16UC1 [mm], 0 = none): the k-th
/// smallest, k = min(n - 1, floor(q n)) of the n valid ones, into `quantile_mm` (CV_32FC1, left
/// where none is valid); pixels with fewer than `minValid` valid samples are marked 255 in `few`
/// (CV_8UC1). The k-th smallest valid depth is the (n - k)-th largest of all the samples' values
/// (no depth = 0 ranks below every depth): for a high quantile each pixel keeps its few largest
/// values, a sorting network of image-wide min/max over bands of rows that stay in the cache.
void depthQuantiles(const std::vector<cv::Mat>& samples_mm, double q, std::size_t minValid, cv::Mat& quantile_mm,
                    cv::Mat& few) {
  const std::size_t S = samples_mm.size();
  std::vector<int> rankFromTop(S + 1, 0);  // per count n of valid samples, n - k
  int ranks = 0;
  for (std::size_t n = 1; n <= S; ++n) {
    const std::size_t k = std::min(n - 1, static_cast<std::size_t>(q * static_cast<double>(n)));
    rankFromTop[n] = static_cast<int>(n - k);
    ranks = std::max(ranks, rankFromTop[n]);
  }
  const int W = samples_mm[0].cols, H = samples_mm[0].rows;
  if (ranks > 8) {  // a low quantile: per pixel
    std::vector<std::uint16_t> vals;
    for (int v = 0; v < H; ++v)
      for (int u = 0; u < W; ++u) {
        vals.clear();
        for (const auto& d : samples_mm)
          if (const std::uint16_t z = d.ptr<std::uint16_t>(v)[u]; z > 0) vals.push_back(z);
        if (vals.empty()) continue;
        if (vals.size() < minValid) few.ptr<uchar>(v)[u] = 255;
        const auto k = static_cast<long>(vals.size()) - rankFromTop[vals.size()];
        std::nth_element(vals.begin(), vals.begin() + k, vals.end());
        quantile_mm.ptr<float>(v)[u] = vals[static_cast<std::size_t>(k)];
      }
    return;
  }
  const int band = std::max(1, 16384 / std::max(1, W));           // rows per band: a few 32 KB images
  std::vector<cv::Mat> largest(static_cast<std::size_t>(ranks));  // per pixel, descending
  cv::Mat x, valid, count, higher;
  for (int r0 = 0; r0 < H; r0 += band) {
    const cv::Range rows(r0, std::min(H, r0 + band));
    for (auto& l : largest) l = cv::Mat::zeros(rows.size(), W, CV_16UC1);
    count = cv::Mat::zeros(rows.size(), W, CV_16UC1);
    for (const auto& d : samples_mm) {
      d.rowRange(rows).copyTo(x);
      cv::min(x, 1, valid);
      cv::add(count, valid, count);
      for (auto& l : largest) {  // insert x: each rank keeps the larger, passes the smaller on
        cv::max(l, x, higher);
        cv::min(l, x, x);
        std::swap(l, higher);
      }
    }
    for (int v = 0; v < rows.size(); ++v) {
      const std::uint16_t* n = count.ptr<std::uint16_t>(v);
      float* out = quantile_mm.ptr<float>(r0 + v);
      uchar* f = few.ptr<uchar>(r0 + v);
      for (int u = 0; u < W; ++u) {
        if (n[u] == 0) continue;
        if (n[u] < minValid) f[u] = 255;
        out[u] = largest[static_cast<std::size_t>(rankFromTop[n[u]] - 1)].ptr<std::uint16_t>(v)[u];
      }
    }
  }
}

/// std::lround(x) when it lies in [0, n) (then true), for the destination pixel of a warped point:
/// the same integer as lround, without its library call.
inline bool roundedIndex(float x, int n, int& i) {
  if (!(x > -0.5f && x < static_cast<float>(n) - 0.5f)) return false;  // lround(x) outside [0, n), or NaN
  const int t = static_cast<int>(x);                                   // towards zero; x - t is exact
  i = t + (x - static_cast<float>(t) >= 0.5f ? 1 : 0);
  return true;
}

/// Forward-warps the depth `src_m` [m, CV_32FC1] of a camera with intrinsics `Ks` (and its colour,
/// CV_8UC3 of the same size, or empty) into a camera with intrinsics `Kd` at X_dst_src: per
/// destination pixel the nearest point landing there; pixels where none landed (0) take the nearest
/// of their 3x3 neighbours (the gaps a forward warp leaves), their colour the brightest (per channel);
/// pixels with none there either `noDepth` (colour 0). `dst_m` and `*dstColour` are reused when they
/// already have the destination's size and type. Only the source pixels inside `window` (default: all)
/// are warped: landingWindow's, which holds every pixel that can land.
void warpDepth(const cv::Mat& src_m, const cv::Mat& srcColour, const core::CameraIntrinsics& Ks,
               const core::Pose3& X_dst_src, const core::CameraIntrinsics& Kd, cv::Mat& dst_m, cv::Mat* dstColour,
               float noDepth = 0.f, cv::Rect window = {}) {
  // Where no point lands yet: farther than any (the gaps' fill below is then a plain erosion).
  constexpr float kNone = std::numeric_limits<float>::max();
  dst_m.create(Kd.height_px, Kd.width_px, CV_32FC1);
  dst_m.setTo(kNone);
  const bool colour = dstColour && !srcColour.empty();
  if (colour) {
    dstColour->create(dst_m.size(), CV_8UC3);
    dstColour->setTo(cv::Scalar::all(0));
  }
  const Eigen::Matrix3f R = X_dst_src.linear().cast<float>();
  const Eigen::Vector3f t = X_dst_src.translation().cast<float>();
  std::vector<float> xr(static_cast<std::size_t>(src_m.cols));
  for (int u = 0; u < src_m.cols; ++u) xr[static_cast<std::size_t>(u)] = static_cast<float>((u - Ks.cx_px) / Ks.fx_px);
  const float fx = static_cast<float>(Kd.fx_px), fy = static_cast<float>(Kd.fy_px);
  const float cx = static_cast<float>(Kd.cx_px), cy = static_cast<float>(Kd.cy_px);
  const float r0x = R(0, 0), r0y = R(1, 0), r0z = R(2, 0), tx = t.x(), ty = t.y(), tz = t.z();
  const int W = dst_m.cols, H = dst_m.rows;
  window = window.area() > 0 ? window & cv::Rect(0, 0, src_m.cols, src_m.rows) : cv::Rect(0, 0, src_m.cols, src_m.rows);
  const int n = window.width;
  const Eigen::Map<const Eigen::ArrayXf> xa(xr.data() + window.x, n);
  Eigen::ArrayXf qz(n), pu(n), pv(n);
  for (int v = window.y; v < window.y + window.height; ++v) {
    const float yr = static_cast<float>((v - Ks.cy_px) / Ks.fy_px);
    const float* z = src_m.ptr<float>(v) + window.x;
    const cv::Vec3b* c = colour ? srcColour.ptr<cv::Vec3b>(v) + window.x : nullptr;
    // Per row: the image of the point (xr z, yr z, z) is (a z + t) with a = R (xr, yr, 1); its
    // pixel (pu, pv), the whole row at once (vectorised; a point without depth is skipped below).
    const Eigen::Vector3f b = R * Eigen::Vector3f(0.f, yr, 1.f);
    const Eigen::Map<const Eigen::ArrayXf> za(z, n);
    qz = (b.z() + r0z * xa) * za + tz;
    pu = fx * ((b.x() + r0x * xa) * za + tx) / qz + cx;
    pv = fy * ((b.y() + r0y * xa) * za + ty) / qz + cy;
    for (int u = 0; u < n; ++u) {
      int ud = 0, vd = 0;
      if (z[u] <= 0.f || qz[u] <= 0.f || !roundedIndex(pu[u], W, ud) || !roundedIndex(pv[u], H, vd)) continue;
      float& d = dst_m.ptr<float>(vd)[ud];
      if (d <= qz[u]) continue;
      d = qz[u];
      if (colour) dstColour->ptr<cv::Vec3b>(vd)[ud] = c[u];
    }
  }
  // The gaps (still at kNone): the nearest landed depth of the 3x3 neighbours (none: noDepth), and the
  // per-channel brightest colour of the neighbours (a gap's own colour is 0).
  cv::Mat nearest, brightest;
  cv::erode(dst_m, nearest, cv::Mat());
  if (noDepth != kNone) nearest.setTo(noDepth, nearest == kNone);
  const cv::Mat gaps = dst_m == kNone;
  nearest.copyTo(dst_m, gaps);
  if (!colour) return;
  cv::dilate(*dstColour, brightest, cv::Mat());
  brightest.copyTo(*dstColour, gaps);
}

/// Gaps of `depth_m` [m, CV_32FC1; 0: none] narrower than `gap_px` take the farthest depth and the
/// brightest colour of `colour_bgr8` (same size, or empty) within gap_px / 2: the surface behind that a
/// depth edge uncovers. Wider regions without depth keep none. Measured on images pooled so that the
/// gap is at most 10 px wide there (the CPU of a 640-px image at any size).
void fillNarrowGaps(cv::Mat& depth_m, cv::Mat& colour_bgr8, int gap_px) {
  if (gap_px <= 1) return;
  const cv::Mat none = depth_m <= 0.f;
  if (cv::countNonZero(none) == 0) return;
  const int f = (gap_px + 9) / 10;
  const cv::Size small((depth_m.cols + f - 1) / f, (depth_m.rows + f - 1) / f);
  // At f = 1 the images themselves (a resize to the same size is a copy).
  cv::Mat noneSmall = none, depthSmall = depth_m, colourSmall = colour_bgr8;
  if (f > 1) {
    cv::resize(none, noneSmall, small, 0, 0, cv::INTER_AREA);  // a pooled pixel with any gap
    noneSmall = noneSmall > 0;
    cv::resize(depth_m, depthSmall, small, 0, 0, cv::INTER_NEAREST);
    if (!colour_bgr8.empty()) cv::resize(colour_bgr8, colourSmall, small, 0, 0, cv::INTER_NEAREST);
  }
  const cv::Mat d = disc(std::max(3, gap_px / f));
  cv::Mat wide, needed;
  cv::morphologyEx(noneSmall, wide, cv::MORPH_OPEN, d);
  // The farthest depth and brightest colour are needed at the gaps only (a few hundred pixels): at
  // f > 1, the pooled pixels that hold one (with a pixel's slack for the two resizes' rounding).
  if (f > 1) cv::dilate(noneSmall, needed, cv::Mat());
  else needed = noneSmall;
  needed &= ~wide;
  cv::Mat farthest = dilateWhere(depthSmall, d, needed);
  if (f > 1) {
    cv::resize(wide, wide, depth_m.size(), 0, 0, cv::INTER_NEAREST);
    cv::resize(farthest, farthest, depth_m.size(), 0, 0, cv::INTER_NEAREST);
  }
  const cv::Mat gaps = f > 1 ? none & ~wide : needed;
  farthest.copyTo(depth_m, gaps);
  if (colour_bgr8.empty()) return;
  cv::Mat brightest = dilateWhere(colourSmall, d, needed);
  if (f > 1) cv::resize(brightest, brightest, depth_m.size(), 0, 0, cv::INTER_NEAREST);
  brightest.copyTo(colour_bgr8, gaps);
}

/// Principal direction of a blob, oriented from `entry` inwards; its pixel
/// mean; and whether it is elongated (else the direction means little).
struct Axis {
  Eigen::Vector2d dir, mean;
  bool elongated;
};

/// Principal axis of the pixels of `a` or `b` (`b` may be empty), sampled
/// every `stride` rows and columns; nullopt below 3 samples.
std::optional<Axis> principalAxis(const cv::Mat& a, const cv::Mat& b, const Eigen::Vector2d& entry, int stride,
                                  double minElongation) {
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  Eigen::Matrix2d scatter = Eigen::Matrix2d::Zero();
  int count = 0;
  for (int v = 0; v < a.rows; v += stride) {
    const uchar* ap = a.ptr<uchar>(v);
    const uchar* bp = b.empty() ? nullptr : b.ptr<uchar>(v);
    for (int u = 0; u < a.cols; u += stride) {
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
  Axis out{eig.eigenvectors().col(1).normalized(), mean, eig.eigenvalues()(1) > minElongation * eig.eigenvalues()(0)};
  if (out.dir.dot(mean - entry) < 0) out.dir = -out.dir;
  return out;
}

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

/// The maximum of the distance transform inside `mask` (CV_8UC1); nullopt when empty.
std::optional<Eigen::Vector2d> thickestPoint(const cv::Mat& mask) {
  // The maximum of the distance transform inside the mask (on its bounding box, with a free margin).
  const cv::Rect box = cv::boundingRect(mask);
  if (box.area() == 0) return std::nullopt;
  cv::Mat padded(box.height + 2, box.width + 2, CV_8UC1, cv::Scalar(0)), distance;
  mask(box).copyTo(padded(cv::Rect(1, 1, box.width, box.height)));
  cv::distanceTransform(padded, distance, cv::DIST_L2, cv::DIST_MASK_5);
  cv::Point best;
  cv::minMaxLoc(distance, nullptr, nullptr, nullptr, &best);
  return Eigen::Vector2d(box.x + best.x - 1, box.y + best.y - 1);
}

/// The breadth of `mask` (CV_8UC1) across `dir` [m], in slices `step_m` long back from `end_px` against `dir`
/// (slice i: from i step_m to (i + 1) step_m from the end, in 3D on the depth line z = line(0) + line(1) s, s the
/// pixel distance back from the end), `slices` of them: each slice's pixels of the mask over its length in
/// pixels, at its depth. A slice past the mask's end is 0.
std::vector<double> breadthFromEnd(const cv::Mat& mask, const core::CameraIntrinsics& k, const Eigen::Vector2d& end_px,
                                   const Eigen::Vector2d& dir, const Eigen::Vector2d& line, double step_m, int slices) {
  // Each whole pixel distance back from the end -> its slice, walking the 3D centre line on the depth line.
  std::vector<int> sliceOf;
  std::vector<double> length_px(static_cast<std::size_t>(slices), 0.0), depth_m(static_cast<std::size_t>(slices), 0.0);
  const Eigen::Vector3d p0 = pixelToCamera(k, end_px.x(), end_px.y(), line(0));
  for (int s = 0; s < mask.cols + mask.rows; ++s) {
    const double z = line(0) + line(1) * (s + 0.5);
    if (z <= 0.0) break;
    const Eigen::Vector2d q = end_px - (s + 0.5) * dir;
    const int i = static_cast<int>((pixelToCamera(k, q.x(), q.y(), z) - p0).norm() / step_m);
    if (i >= slices) break;
    sliceOf.push_back(i);
    length_px[static_cast<std::size_t>(i)] += 1.0;
    depth_m[static_cast<std::size_t>(i)] = z;
  }
  std::vector<double> count(static_cast<std::size_t>(slices), 0.0);
  for (int v = 0; v < mask.rows; ++v) {
    const uchar* m = mask.ptr<uchar>(v);
    for (int u = 0; u < mask.cols; ++u) {
      if (!m[u]) continue;
      const double s = (end_px - Eigen::Vector2d(u, v)).dot(dir);
      if (s < 0.0 || s >= static_cast<double>(sliceOf.size())) continue;
      count[static_cast<std::size_t>(sliceOf[static_cast<std::size_t>(s)])] += 1.0;
    }
  }
  std::vector<double> breadth_m(static_cast<std::size_t>(slices), 0.0);
  for (std::size_t i = 0; i < breadth_m.size(); ++i)
    if (length_px[i] > 0.0) breadth_m[i] = count[i] / length_px[i] * depth_m[i] / k.fx_px;
  return breadth_m;
}

}  // namespace

MarkerFreeHandDetector::MarkerFreeHandDetector(const Options& options) : options_(options) {
  core::require(options.backgroundFrames >= 1, "MarkerFreeHandDetector: backgroundFrames must be >= 1");
  core::require(options.minWorkingWidth_px == 0 || options.minWorkingWidth_px >= 64,
                "MarkerFreeHandDetector: minWorkingWidth_px must be 0 (every frame at its own size) or >= 64 px");
  core::require(options.backgroundPercentile > 0.0 && options.backgroundPercentile <= 1.0 &&
                    options.maxBackgroundSamples >= 2,
                "MarkerFreeHandDetector: backgroundPercentile must be in (0, 1] and maxBackgroundSamples >= 2");
  core::require(options.skinModeRadius > 0.0 && options.skinMaxMahalanobis > 0.0 && options.minSkinSamples >= 1,
                "MarkerFreeHandDetector: skinModeRadius, skinMaxMahalanobis must be > 0 and minSkinSamples >= 1");
  core::require(options.maxHandLength_m > 0.0 && options.palmFromFarEnd_m > 0.0,
                "MarkerFreeHandDetector: maxHandLength_m and palmFromFarEnd_m must be > 0 m (lengths of the "
                "demonstrator's hand)");
  core::require(options.palmFromFarEndAlongRay_m >= 0.0 && options.palmFromFarEndAcrossRay_m >= 0.0,
                "MarkerFreeHandDetector: palmFromFarEndAlongRay_m and palmFromFarEndAcrossRay_m must be >= 0 m (0: "
                "palmFromFarEnd_m)");
  core::require(options.skinLumaFloorFraction >= 0.0 && options.skinLumaFloorFraction < 1.0,
                "MarkerFreeHandDetector: skinLumaFloorFraction must be in [0, 1) (a share of the skin's luma; 0: "
                "the fixed skinMinLuma)");
  core::require(options.minBackgroundValidFraction >= 0.0 && options.minBackgroundValidFraction <= 1.0 &&
                    options.backgroundFillDiameter_px >= 0,
                "MarkerFreeHandDetector: minBackgroundValidFraction must be in [0, 1] (a share of the preview's "
                "samples; 0: every pixel's own quantile) and backgroundFillDiameter_px >= 0");
  core::require(options.skinIlluminantNorm >= 0.0 && options.skinMaxChromaPerLuma >= 0.0,
                "MarkerFreeHandDetector: skinIlluminantNorm must be >= 0 (a Minkowski exponent; 0: no white balance) "
                "and skinMaxChromaPerLuma >= 0 (0: off)");
  core::require(options.minSkinReach_m >= 0.0,
                "MarkerFreeHandDetector: minSkinReach_m must be >= 0 m (0: skin near the body's entry is not refused)");
  core::require(options.maxPalmSpeed_mps >= 0.0 && options.minPalmTrack >= 1 && options.maxPalmRefusals >= 0,
                "MarkerFreeHandDetector: maxPalmSpeed_mps must be >= 0 m/s (0: no motion prior), minPalmTrack >= 1 "
                "and maxPalmRefusals >= 0");
  core::require(options.stillArmMaxHeight_m > 0.0 && options.stillArmSkinFraction >= 0.0 &&
                    options.stillArmSkinFraction <= 1.0 && options.stillArmBridge_m >= 0.0,
                "MarkerFreeHandDetector: stillArmMaxHeight_m must be > 0 m, stillArmSkinFraction in [0, 1] and "
                "stillArmBridge_m >= 0 m (stillArmFromPlane = false turns the rule off)");
  core::require(options.minCameraMotion_m >= 0.0 && options.minCameraTurn_deg >= 0.0,
                "MarkerFreeHandDetector: minCameraMotion_m and minCameraTurn_deg must be >= 0 (followCameraMotion = "
                "false keeps a still camera's background)");
  core::require(options.movingBackgroundMargin >= 0.0 && options.movingBackgroundMargin <= 1.0,
                "MarkerFreeHandDetector: movingBackgroundMargin must be in [0, 1] (a share of the image's size on "
                "each side)");
  core::require(options.stillArmShapeShare >= 0.0 && options.stillArmShapeShare <= 1.0 &&
                    options.stillArmMinWidth_m >= 0.0 && options.stillArmMaxWidth_m > options.stillArmMinWidth_m &&
                    options.stillArmWidthShare >= 0.0 && options.stillArmWidthShare <= 1.0 &&
                    options.stillArmSlice_m > 0.0 && options.stillArmMinElongation >= 0.0,
                "MarkerFreeHandDetector: stillArmShapeShare and stillArmWidthShare must be in [0, 1], "
                "0 <= stillArmMinWidth_m < stillArmMaxWidth_m, stillArmSlice_m > 0 m and stillArmMinElongation >= 0 "
                "(stillArmShapeShare = 0 turns the shape test off)");
  core::require(options.palmFromWrist_m > 0.0 && options.palmFromFingertips_m > 0.0 && options.palmRadius_m > 0.0,
                "MarkerFreeHandDetector: palmFromWrist_m, palmFromFingertips_m and palmRadius_m must be > 0 m "
                "(lengths of the demonstrator's hand)");
  core::require(options.palmHalfWidth_m >= 0.0 && options.palmDepth_m >= 0.0 && options.minPalmCrossSections >= 0.0 &&
                    options.minPalmCrossSections <= 1.0,
                "MarkerFreeHandDetector: palmHalfWidth_m and palmDepth_m must be >= 0 m (half the demonstrator's palm's "
                "width and thickness; palmHalfWidth_m = 0 turns the silhouette's depth off) and minPalmCrossSections "
                "in [0, 1]");
}

const rawlog::RgbdFrame& MarkerFreeHandDetector::atWorkingSize(const rawlog::RgbdFrame& frame,
                                                               rawlog::RgbdFrame& shrunk) {
  if (shrink_ == 0) {
    const int w = frame.depth_m.cols;
    shrink_ = options_.minWorkingWidth_px > 0 ? std::max(1, w / options_.minWorkingWidth_px) : 1;
  }
  if (shrink_ == 1 || frame.depth_m.empty()) return frame;
  const int f = shrink_, W = frame.depth_m.cols / f, H = frame.depth_m.rows / f;
  shrunk.index = frame.index;
  shrunk.t_s = frame.t_s;
  shrunk.depthRegisteredOnRead = frame.depthRegisteredOnRead;
  // Depth by each f x f block's middle pixel: no depth is made up between a hand and what lies behind it.
  shrunk.depth_m.create(H, W, CV_32FC1);
  for (int v = 0; v < H; ++v) {
    const float* src = frame.depth_m.ptr<float>(v * f + f / 2);
    float* dst = shrunk.depth_m.ptr<float>(v);
    for (int u = 0; u < W; ++u) dst[u] = src[u * f + f / 2];
  }
  if (!frame.colour_bgr8.empty())
    cv::resize(frame.colour_bgr8(cv::Rect(0, 0, W * f, H * f)), shrunk.colour_bgr8, {W, H}, 0, 0, cv::INTER_AREA);
  else
    shrunk.colour_bgr8.release();
  shrunk.intrinsics = shrunkIntrinsics(frame.intrinsics, f, W, H);
  return shrunk;
}

void MarkerFreeHandDetector::preview(const rawlog::RgbdFrame& fullFrame) {
  core::require(frameCount_ == 0,
                "MarkerFreeHandDetector::preview: frame " + std::to_string(fullFrame.index) +
                    " previewed after detect(); preview the whole recording first");
  rawlog::RgbdFrame shrunk;
  const rawlog::RgbdFrame& frame = atWorkingSize(fullFrame, shrunk);
  // A frame without depth or of another size is left out here; detect()'s
  // caller reports it (DemoPerceiver::add checks every frame).
  if (frame.depth_m.empty() || frame.depth_m.type() != CV_32FC1 ||
      (!previewDepth_mm_.empty() && frame.depth_m.size() != previewDepth_mm_[0].size()) ||
      (!frame.colour_bgr8.empty() && frame.colour_bgr8.size() != frame.depth_m.size()))
    return;
  previewIntrinsics_ = frame.intrinsics;
  core::Pose3 X_camera0_camera = core::Pose3::Identity();
  if (options_.followCameraMotion) {
    if (!previewMotion_) previewMotion_ = std::make_shared<CameraMotionEstimator>(frame.intrinsics);
    X_camera0_camera = previewMotion_->add(frame);
    previewFrameIndex_.push_back(frame.index);
  }
  if (previewFrames_ % previewStride_ == 0) {
    cv::Mat mm;
    frame.depth_m.convertTo(mm, CV_16UC1, 1000.0);
    previewDepth_mm_.push_back(mm);
    cv::Mat half;
    if (!frame.colour_bgr8.empty()) cv::resize(frame.colour_bgr8, half, {}, 0.5, 0.5, cv::INTER_AREA);
    previewColour_.push_back(half);
    previewSamplePose_.push_back(X_camera0_camera);
    if (static_cast<int>(previewDepth_mm_.size()) > options_.maxBackgroundSamples) {
      // Keep every other sample: the samples stay evenly spread, at twice the stride.
      for (std::size_t i = 0; 2 * i < previewDepth_mm_.size(); ++i) {
        previewDepth_mm_[i] = previewDepth_mm_[2 * i];
        previewColour_[i] = previewColour_[2 * i];
        previewSamplePose_[i] = previewSamplePose_[2 * i];
      }
      previewDepth_mm_.resize((previewDepth_mm_.size() + 1) / 2);
      previewColour_.resize(previewDepth_mm_.size());
      previewSamplePose_.resize(previewDepth_mm_.size());
      previewStride_ *= 2;
    }
  }
  if (!frame.colour_bgr8.empty() && (previewColourSum_.empty() || previewColourSum_.size() == frame.colour_bgr8.size())) {
    if (previewColourSum_.empty()) previewColourSum_ = cv::Mat(frame.colour_bgr8.size(), CV_32FC3, cv::Scalar::all(0));
    cv::accumulate(frame.colour_bgr8, previewColourSum_);
  }
  ++previewFrames_;
}

void MarkerFreeHandDetector::finishPreview() {
  if (!previewColourSum_.empty()) {  // the lamp, before any skin test (the still arm's too)
    cv::Mat mean_bgr8;
    previewColourSum_.convertTo(mean_bgr8, CV_8UC3, 1.0 / static_cast<double>(std::max(1, previewFrames_)));
    estimateIlluminant(mean_bgr8);
  }
  // A head-mounted camera turns: a shift alone, on a scene that a large moving arm dominates, is ICP
  // following the arm (drawn StillBareForearmInEveryFrame: 4 cm, 0.9 deg).
  const bool turned = previewMotion_ && previewMotion_->maxTranslation_m() > options_.minCameraMotion_m &&
                      previewMotion_->maxRotation_rad() > options_.minCameraTurn_deg * core::kPi / 180.0;
  // Each sample's background at half size [mm]: one for all (a still camera), or each sample's own view.
  const cv::Mat still_mm = backgroundFromPreview(previewDepth_mm_, false);
  cv::Mat stillHalf;
  cv::resize(still_mm, stillHalf, {}, 0.5, 0.5, cv::INTER_NEAREST);
  std::vector<cv::Mat> bgHalf(previewDepth_mm_.size(), stillHalf);
  // Each sample's background colour at half size (holesInPreview; empty: none).
  cv::Mat stillColourHalf;
  if (options_.holesInPreview && !backgroundColour_.empty())
    cv::resize(backgroundColour_, stillColourHalf, {}, 0.5, 0.5, cv::INTER_AREA);
  std::vector<cv::Mat> bgColourHalf(previewDepth_mm_.size(), stillColourHalf);
  // Each sample's own depth at half size [mm, CV_32FC1], for the comparisons below.
  std::vector<cv::Mat> depthHalf_mm(previewDepth_mm_.size());
  for (std::size_t i = 0; i < previewDepth_mm_.size(); ++i) {
    cv::resize(previewDepth_mm_[i], depthHalf_mm[i], {}, 0.5, 0.5, cv::INTER_NEAREST);
    depthHalf_mm[i].convertTo(depthHalf_mm[i], CV_32FC1);
  }
  if (turned) {
    // The estimated motion is used when the samples agree with their warped background better than with
    // the still one (ICP on a scene of little structure, a plane and a large arm, can report a motion
    // that never was).
    const cv::Rect stillView = view_;
    movingBackgroundFromPreview();
    std::vector<cv::Mat> movingHalf(previewDepth_mm_.size());
    std::vector<cv::Mat> movingColourHalf(options_.holesInPreview ? previewDepth_mm_.size() : 0);
    // For the skin model and the bare-forearm decision (enterThroughStillArm), the arm is foreground down to
    // where it enters: the background that stands above the plane at the border is the plane's depth there.
    // Made from the same warp (it is used only if the camera is found to move).
    const bool entering = options_.enterThroughStillArm && canvasPlane_.has_value();
    std::vector<cv::Mat> enteringHalf(entering ? previewDepth_mm_.size() : 0);
    double disagreeStill = 0.0, disagreeMoving = 0.0;
    for (std::size_t i = 0; i < previewDepth_mm_.size(); ++i) {
      cv::Mat depth_m, colour;
      backgroundInView(previewSamplePose_[i], depth_m, options_.holesInPreview ? &colour : nullptr);
      cv::resize(depth_m, movingHalf[i], {}, 0.5, 0.5, cv::INTER_NEAREST);
      movingHalf[i] *= 1e3;
      if (options_.holesInPreview && !colour.empty())
        cv::resize(colour, movingColourHalf[i], {}, 0.5, 0.5, cv::INTER_NEAREST);
      if (entering) {
        cv::Mat noColour, planeDepth_m;
        fillNarrowGaps(depth_m, noColour, static_cast<int>(std::lround(options_.movingBackgroundGap * depth_m.cols)));
        enteringBackground(depth_m, previewSamplePose_[i], &planeDepth_m);
        planeDepth_m.copyTo(depth_m, planeDepth_m > 0.f);
        cv::resize(depth_m, enteringHalf[i], {}, 0.5, 0.5, cv::INTER_NEAREST);
        enteringHalf[i] *= 1e3;
      }
      const cv::Mat& z = depthHalf_mm[i];
      auto disagreement = [&](const cv::Mat& bg) {
        const cv::Mat both = (z > 0.f) & (bg > 0.f);
        const cv::Mat off = both & (cv::abs(bg - z) > 1e3 * options_.minForeground_m);
        return static_cast<double>(cv::countNonZero(off)) / std::max(1, cv::countNonZero(both));
      };
      disagreeStill += disagreement(stillHalf);
      disagreeMoving += disagreement(movingHalf[i]);
    }
    cameraMoves_ = disagreeMoving < options_.maxMovingDisagreement * disagreeStill;
    if (core::Log::enabled("hand", core::Log::Level::Debug))
      core::Log::writef("hand", core::Log::Level::Debug,
                        "camera: moved up to %.3f m, %.2f deg; samples off their background %.3f still, %.3f "
                        "moving: %s\n",
                        previewMotion_->maxTranslation_m(), previewMotion_->maxRotation_rad() * 180.0 / core::kPi,
                        disagreeStill / static_cast<double>(previewDepth_mm_.size()),
                        disagreeMoving / static_cast<double>(previewDepth_mm_.size()),
                        cameraMoves_ ? "follows the camera" : "still");
    if (cameraMoves_) {
      bgHalf = entering ? enteringHalf : movingHalf;
      if (options_.holesInPreview) bgColourHalf = movingColourHalf;
    } else {
      view_ = stillView;
    }
  }
  // Skin from every sample's foreground (half size: plenty of pixels).
  if (options_.useSkin) {
    const cv::Mat open = disc(options_.previewOpenDiameter_px);
    std::vector<cv::Mat> fgHalf(previewDepth_mm_.size());
    for (std::size_t i = 0; i < previewDepth_mm_.size(); ++i) {
      if (previewColour_[i].empty()) continue;
      fgHalf[i] = previewForeground(i, bgHalf[i], depthHalf_mm[i], bgColourHalf[i]);
      cv::Mat fgOpen;
      cv::morphologyEx(fgHalf[i], fgOpen, cv::MORPH_OPEN, open);
      accumulateSkin(previewColour_[i], fgOpen, 1);
    }
    fitSkin();
    if (skin_.learnt) decideBareForearms(fgHalf, depthHalf_mm);
  }
  previewDepth_mm_.clear();
  previewColour_.clear();
  previewSamplePose_.clear();
  previewColourSum_.release();
}

void MarkerFreeHandDetector::movingBackgroundFromPreview() {
  const core::CameraIntrinsics k = previewIntrinsics_;
  const int mx = static_cast<int>(std::lround(options_.movingBackgroundMargin * k.width_px));
  const int my = static_cast<int>(std::lround(options_.movingBackgroundMargin * k.height_px));
  canvasIntrinsics_ = k;
  canvasIntrinsics_.width_px = k.width_px + 2 * mx;
  canvasIntrinsics_.height_px = k.height_px + 2 * my;
  canvasIntrinsics_.cx_px = k.cx_px + mx;
  canvasIntrinsics_.cy_px = k.cy_px + my;
  // Each sample in the first frame's camera; the colour is the mean of the warped samples' colours.
  std::vector<cv::Mat> warped_mm(previewDepth_mm_.size());
  cv::Mat colourSum(canvasIntrinsics_.height_px, canvasIntrinsics_.width_px, CV_32FC3, cv::Scalar::all(0));
  cv::Mat colourCount(colourSum.size(), CV_32FC1, cv::Scalar(0));
  for (std::size_t i = 0; i < previewDepth_mm_.size(); ++i) {
    cv::Mat depth_m, colour, warped_m, warpedColour;
    previewDepth_mm_[i].convertTo(depth_m, CV_32FC1, 1e-3);
    if (!previewColour_[i].empty()) cv::resize(previewColour_[i], colour, depth_m.size(), 0, 0, cv::INTER_NEAREST);
    warpDepth(depth_m, colour, k, previewSamplePose_[i], canvasIntrinsics_, warped_m, &warpedColour);
    warped_m.convertTo(warped_mm[i], CV_16UC1, 1e3);
    if (!warpedColour.empty()) {
      const cv::Mat landed = warped_m > 0.f;
      cv::accumulate(warpedColour, colourSum, landed);
      cv::add(colourCount, cv::Scalar(1), colourCount, landed);
    }
  }
  const cv::Mat canvas_mm = backgroundFromPreview(warped_mm, true);
  // The view moves: the whole image is in view (a pixel without background is no foreground).
  view_ = cv::Rect(0, 0, k.width_px, k.height_px);
  canvas_mm.convertTo(canvasDepth_m_, CV_32FC1, 1e-3);
  double least = 0.0, greatest = 0.0;  // of the valid depths, for landingWindow
  cv::minMaxLoc(canvasDepth_m_, &least, &greatest, nullptr, nullptr, canvasDepth_m_ > 0.f);
  canvasDepthRange_m_ = {static_cast<float>(least), static_cast<float>(greatest)};
  if (options_.enterThroughStillArm) {
    // The support plane in the first camera (half size: plenty of points).
    cv::Mat half_m;
    cv::resize(canvasDepth_m_, half_m, {}, 0.5, 0.5, cv::INTER_NEAREST);
    const CameraModel halfCamera(shrunkIntrinsics(canvasIntrinsics_, 2, half_m.cols, half_m.rows));
    canvasPlane_ = fitSupportPlane(depthToCloud(half_m, halfCamera));
  }
  if (options_.backgroundColourFromSurface && !previewColour_.empty()) {
    // The colour of the samples that show the background's surface there (within minForeground_m of its
    // depth), not of the arm or part that passed over it: a depth hole is foreground by its colour.
    cv::Mat surfaceSum(colourSum.size(), CV_32FC3, cv::Scalar::all(0)), surfaceCount(colourSum.size(), CV_32FC1, cv::Scalar(0));
    for (std::size_t i = 0; i < previewDepth_mm_.size(); ++i) {
      if (previewColour_[i].empty()) continue;
      cv::Mat depth_m, colour, warped_m, warpedColour;
      previewDepth_mm_[i].convertTo(depth_m, CV_32FC1, 1e-3);
      cv::resize(previewColour_[i], colour, depth_m.size(), 0, 0, cv::INTER_NEAREST);
      warpDepth(depth_m, colour, k, previewSamplePose_[i], canvasIntrinsics_, warped_m, &warpedColour);
      const cv::Mat onSurface =
          (warped_m > 0.f) & (canvasDepth_m_ > 0.f) & (cv::abs(warped_m - canvasDepth_m_) <= options_.minForeground_m);
      cv::accumulate(warpedColour, surfaceSum, onSurface);
      cv::add(surfaceCount, cv::Scalar(1), surfaceCount, onSurface);
    }
    const cv::Mat seen = surfaceCount > 0.f;
    surfaceSum.copyTo(colourSum, seen);
    surfaceCount.copyTo(colourCount, seen);
  }
  cv::Mat count3;
  cv::merge(std::vector<cv::Mat>{colourCount, colourCount, colourCount}, count3);
  cv::Mat mean = colourSum / cv::max(count3, 1.f);
  mean.convertTo(canvasColour_, CV_8UC3);
}

void MarkerFreeHandDetector::backgroundInView(const core::Pose3& X_camera0_camera, cv::Mat& depth_m,
                                              cv::Mat* colour_bgr8) const {
  const bool slack = options_.movingBackgroundSlack_px > 0;
  // Where no background lands: 0, or for the erosion below farther than any.
  const core::Pose3 X_camera_camera0 = X_camera0_camera.inverse();
  warpDepth(canvasDepth_m_, canvasColour_, canvasIntrinsics_, X_camera_camera0, previewIntrinsics_, depth_m,
            colour_bgr8, slack ? std::numeric_limits<float>::max() : 0.f,
            landingWindow(canvasIntrinsics_, canvasDepthRange_m_.first, canvasDepthRange_m_.second, X_camera_camera0,
                          previewIntrinsics_));
  if (!slack) return;
  // The nearest background within the slack (the estimated pose's error): a surface seen at a grazing
  // angle, whose depth changes fast across the image, is not foreground for a pixel's misregistration.
  cv::erode(depth_m, depth_m, disc(2 * options_.movingBackgroundSlack_px + 1));
  depth_m.setTo(0.f, depth_m == std::numeric_limits<float>::max());
}

cv::Mat MarkerFreeHandDetector::enteringBackground(const cv::Mat& background_m, const core::Pose3& X_camera0_camera,
                                                  cv::Mat* planeDepth_m) const {
  if (!canvasPlane_) return {};
  // The plane in this camera: height(p) = n0 . (R p + t) + d0.
  const Eigen::Vector3d n = X_camera0_camera.linear().transpose() * canvasPlane_->n;
  const double d = canvasPlane_->n.dot(X_camera0_camera.translation()) + canvasPlane_->d;
  const core::CameraIntrinsics& k = previewIntrinsics_;
  const double lo = options_.minForeground_m, hi = options_.stillArmMaxHeight_m;
  cv::Mat open(background_m.size(), CV_8UC1, cv::Scalar(0));
  std::vector<double> nx(static_cast<std::size_t>(background_m.cols));  // per column, n.x x / z
  for (int u = 0; u < background_m.cols; ++u) nx[static_cast<std::size_t>(u)] = n.x() * (u - k.cx_px) / k.fx_px;
  for (int v = 0; v < background_m.rows; ++v) {
    const float* z = background_m.ptr<float>(v);
    uchar* o = open.ptr<uchar>(v);
    const double ny = n.y() * (v - k.cy_px) / k.fy_px + n.z();
    for (int u = 0; u < background_m.cols; ++u) {
      const double h = z[u] * (nx[static_cast<std::size_t>(u)] + ny) + d;
      o[u] = z[u] <= 0.f || (h >= lo && h <= hi) ? 255 : 0;  // no background: as outside the view
    }
  }
  // Only the regions that reach the image border (where the arm enters), grown by the border margin.
  const int m = options_.borderMargin_px, W = open.cols, H = open.rows;
  cv::Mat out = regionsReachingBorder(open, m);
  if (planeDepth_m) {
    // The plane's depth where the background stands above it in those regions.
    *planeDepth_m = cv::Mat(out.size(), CV_32FC1, cv::Scalar(0));
    for (int v = 0; v < H; ++v)
      for (int u = 0; u < W; ++u) {
        const float z = background_m.at<float>(v, u);
        if (!out.at<uchar>(v, u) || z <= 0.f) continue;
        const double den = n.dot(Eigen::Vector3d((u - k.cx_px) / k.fx_px, (v - k.cy_px) / k.fy_px, 1.0));
        if (den < 0.0) planeDepth_m->at<float>(v, u) = static_cast<float>(-d / den);
      }
  }
  if (m > 0) cv::dilate(out, out, cv::getStructuringElement(cv::MORPH_RECT, {2 * m + 1, 2 * m + 1}));
  return out;
}

core::Pose3 MarkerFreeHandDetector::previewPose(int index) {
  const auto& poses = previewMotion_->poses();
  std::size_t i = nextPose_;
  if (i >= previewFrameIndex_.size() || previewFrameIndex_[i] != index)
    i = static_cast<std::size_t>(std::find(previewFrameIndex_.begin(), previewFrameIndex_.end(), index) -
                                 previewFrameIndex_.begin());
  if (i < previewFrameIndex_.size() && i < poses.size()) {
    lastPose_ = poses[i];
    nextPose_ = i + 1;
  }
  return lastPose_;
}

cv::Mat MarkerFreeHandDetector::backgroundFromPreview(const std::vector<cv::Mat>& samples_mm, bool moving) {
  const cv::Size size = samples_mm[0].size();
  cv::Mat background_mm(size, CV_32FC1, cv::Scalar(0));
  // A pixel with depth in few samples (the shadow band along a static
  // object's edge) has its quantile set by whatever covered it then (the
  // demonstrator's arm): its background comes from its neighbours instead.
  // (A moving camera sees the widened image's margins in few samples: each pixel's own quantile.)
  const std::size_t minValid = moving ? 0 : static_cast<std::size_t>(std::ceil(
      options_.minBackgroundValidFraction * static_cast<double>(samples_mm.size())));
  cv::Mat untrusted(size, CV_8UC1, cv::Scalar(0));
  depthQuantiles(samples_mm, options_.backgroundPercentile, minValid, background_mm, untrusted);
  // The depth's field of view: where any sample had a depth (a registered
  // image's band that the depth camera does not see never has one).
  if (!moving) view_ = depthFieldOfView(background_mm, options_.minFieldOfViewValid);
  if (options_.backgroundFillDiameter_px > 1 && cv::countNonZero(untrusted) > 0) {
    // The farthest trusted background nearby (a grey dilation of the trusted
    // pixels), when it lies behind the pixel's own quantile; with no trusted
    // pixel nearby (a wide region without depth most of the time: beyond the
    // sensor's range, a dark or shiny wall) no background depth
    // (farWithoutDepth: whatever has a depth there is in front of it) or the
    // pixel's own quantile.
    cv::Mat trusted = background_mm.clone(), farthest;
    trusted.setTo(0.f, untrusted);
    cv::dilate(trusted, farthest, disc(options_.backgroundFillDiameter_px));
    cv::Mat filled = cv::max(background_mm, farthest);
    if (options_.farWithoutDepth) filled.setTo(0.f, farthest <= 0.f);
    filled.copyTo(background_mm, untrusted);
  }
  if (moving) return background_mm;
  if (options_.stillArmFromPlane) stillArmToPlane(background_mm);
  background_mm.convertTo(backgroundDepth_m_, CV_32FC1, 1e-3);
  if (!previewColourSum_.empty())
    previewColourSum_.convertTo(backgroundColour_, CV_8UC3, 1.0 / static_cast<double>(previewFrames_));
  return background_mm;
}

void MarkerFreeHandDetector::stillArmToPlane(cv::Mat& background_mm) const {
  // Skin (the prior box) in how many of the colour samples, per pixel (half size).
  cv::Mat skinCount;
  int withColour = 0;
  std::vector<std::pair<std::size_t, cv::Mat>> sampleSkin;  // (sample, its skin mask at half size)
  for (std::size_t i = 0; i < previewColour_.size(); ++i) {
    const cv::Mat& c = previewColour_[i];
    if (c.empty()) continue;
    if (skinCount.empty()) skinCount = cv::Mat(c.size(), CV_16UC1, cv::Scalar(0));
    if (c.size() != skinCount.size()) continue;
    sampleSkin.emplace_back(i, skinMask(c, false));
    cv::add(skinCount, cv::Scalar(1), skinCount, sampleSkin.back().second);
    ++withColour;
  }
  if (withColour == 0) return;
  cv::Mat skinMostly = skinCount >= options_.stillArmSkinFraction * withColour;
  cv::resize(skinMostly, skinMostly, background_mm.size(), 0, 0, cv::INTER_NEAREST);
  cv::Mat background_m;
  background_mm.convertTo(background_m, CV_32FC1, 1e-3);
  const CameraModel cameraModel(previewIntrinsics_);
  const auto plane = fitSupportPlane(depthToCloud(background_m, cameraModel));
  if (!plane) return;
  // The plane's depth along each pixel's ray, where the background stands
  // above it within the arm's height band and is mostly skin.
  const core::CameraIntrinsics& k = previewIntrinsics_;
  cv::Mat planeDepth_mm(background_mm.size(), CV_32FC1, cv::Scalar(0));
  cv::Mat candidate(background_mm.size(), CV_8UC1, cv::Scalar(0));
  for (int v = 0; v < background_mm.rows; ++v)
    for (int u = 0; u < background_mm.cols; ++u) {
      const float z_mm = background_mm.at<float>(v, u);
      if (z_mm <= 0.f || !skinMostly.at<uchar>(v, u)) continue;
      const Eigen::Vector3d ray((u - k.cx_px) / k.fx_px, (v - k.cy_px) / k.fy_px, 1.0);
      const auto planeDepth_m = plane->rayScaleAtHeight(ray);
      if (!planeDepth_m) continue;  // the ray never meets the plane
      const double height_m = plane->height(1e-3 * z_mm * ray);
      if (height_m < options_.minForeground_m || height_m > options_.stillArmMaxHeight_m) continue;
      planeDepth_mm.at<float>(v, u) = static_cast<float>(1e3 * *planeDepth_m);
      candidate.at<uchar>(v, u) = 255;
    }
  // Only the regions that reach the border of the view (an arm enters there),
  // bridged over gaps up to stillArmBridge_m (an arm that moved a little is
  // still in every sample only where it is wide: the hand, not the wrist).
  if (cv::countNonZero(candidate) == 0) return;
  const double z_m = 1e-3 * cv::mean(background_mm, candidate)[0];
  const int bridge_px = static_cast<int>(std::lround(options_.stillArmBridge_m * k.fx_px / z_m));
  cv::Mat bridged;  // a new buffer: dilating into a shallow copy would grow `candidate` itself
  if (bridge_px > 1) cv::dilate(candidate, bridged, disc(bridge_px));
  else bridged = candidate;
  cv::Mat labels, stats, centroids;
  cv::connectedComponentsWithStats(bridged, labels, stats, centroids, 8, CV_32S);
  std::vector<uchar> keep = labelsAtBorder(stats, view_, options_.borderMargin_px);
  // ... and only those shaped like an arm.
  if (options_.stillArmShapeShare > 0.0 && std::find(keep.begin() + 1, keep.end(), 1) != keep.end())
    keepArmShaped(*plane, sampleSkin, labels, stats, candidate, keep);
  int replaced = 0;
  for (int v = 0; v < background_mm.rows; ++v)
    for (int u = 0; u < background_mm.cols; ++u)
      if (const int l = labels.at<int>(v, u); l > 0 && keep[static_cast<std::size_t>(l)] && candidate.at<uchar>(v, u)) {
        background_mm.at<float>(v, u) = planeDepth_mm.at<float>(v, u);
        ++replaced;
      }
  if (core::Log::enabled("hand", core::Log::Level::Debug))
    core::Log::writef("hand", core::Log::Level::Debug, "still arm: %d background pixels from the support plane\n",
                      replaced);
}

void MarkerFreeHandDetector::keepArmShaped(const Plane& plane,
                                           const std::vector<std::pair<std::size_t, cv::Mat>>& sampleSkin,
                                           const cv::Mat& labels, const cv::Mat& stats, const cv::Mat& candidate,
                                           std::vector<uchar>& keep) const {
  // An arm: in most samples, the skin standing in the height band that
  // overlaps the region (the whole arm as that sample shows it, not only where
  // it stayed) is elongated and as wide as a forearm over most of its length
  // (in metres, from its own depth). The demonstrator's trousers, a box or a
  // cloth of skin-like colour are wider or not elongated.
  const core::CameraIntrinsics& k = previewIntrinsics_;
  const cv::Size half = sampleSkin.front().second.size();
  const double sx = static_cast<double>(half.width) / labels.cols;
  const double sy = static_cast<double>(half.height) / labels.rows;
  // Each half-size pixel's ray and its full-size source pixel.
  std::vector<Eigen::Vector3d> rays(static_cast<std::size_t>(half.area()));
  for (int v = 0; v < half.height; ++v)
    for (int u = 0; u < half.width; ++u)
      rays[static_cast<std::size_t>(v * half.width + u)] =
          Eigen::Vector3d(((u + 0.5) / sx - 0.5 - k.cx_px) / k.fx_px, ((v + 0.5) / sy - 0.5 - k.cy_px) / k.fy_px, 1.0);
  auto source = [&](int u, int v) {
    return cv::Point(std::min(labels.cols - 1, static_cast<int>(u / sx)),
                     std::min(labels.rows - 1, static_cast<int>(v / sy)));
  };
  const int n = static_cast<int>(keep.size());
  const int withColour = static_cast<int>(sampleSkin.size());
  std::vector<int> armLike(static_cast<std::size_t>(n), 0);
  std::vector<std::vector<double>> lengths(static_cast<std::size_t>(n)), widths(static_cast<std::size_t>(n));
  const cv::Mat open = disc(options_.previewOpenDiameter_px);
  for (const auto& [i, skin] : sampleSkin) {
    const cv::Mat& depth_mm = previewDepth_mm_[i];
    cv::Mat raised(half, CV_8UC1, cv::Scalar(0));
    std::vector<Eigen::Vector3d> p(rays.size(), Eigen::Vector3d::Zero());
    for (int v = 0; v < half.height; ++v)
      for (int u = 0; u < half.width; ++u) {
        if (!skin.at<uchar>(v, u)) continue;
        const std::uint16_t z_mm = depth_mm.at<std::uint16_t>(source(u, v));
        if (z_mm == 0) continue;
        const std::size_t j = static_cast<std::size_t>(v * half.width + u);
        p[j] = 1e-3 * z_mm * rays[j];
        const double height_m = plane.height(p[j]);
        if (height_m >= options_.minForeground_m && height_m <= options_.stillArmMaxHeight_m) raised.at<uchar>(v, u) = 255;
      }
    cv::morphologyEx(raised, raised, cv::MORPH_OPEN, open);
    cv::Mat parts;
    const int np = cv::connectedComponents(raised, parts, 8, CV_32S);
    std::vector<int> regionOf(static_cast<std::size_t>(np), 0);  // the kept region a part overlaps
    for (int v = 0; v < half.height; ++v)
      for (int u = 0; u < half.width; ++u) {
        const int q = parts.at<int>(v, u);
        const cv::Point src = source(u, v);
        const int l = labels.at<int>(src);
        if (q > 0 && l > 0 && keep[static_cast<std::size_t>(l)] && candidate.at<uchar>(src)) regionOf[static_cast<std::size_t>(q)] = l;
      }
    std::vector<std::vector<Eigen::Vector3d>> points(static_cast<std::size_t>(n));
    for (int v = 0; v < half.height; ++v)
      for (int u = 0; u < half.width; ++u)
        if (const int l = regionOf[static_cast<std::size_t>(parts.at<int>(v, u))]; l > 0)
          points[static_cast<std::size_t>(l)].push_back(p[static_cast<std::size_t>(v * half.width + u)]);
    for (int l = 1; l < n; ++l) {
      if (!keep[static_cast<std::size_t>(l)]) continue;
      const ArmShape shape = armShape(points[static_cast<std::size_t>(l)], options_.stillArmSlice_m, 5);
      if (shape.widths_m.empty()) continue;
      const std::vector<double>& w = shape.widths_m;
      const auto within = std::count_if(w.begin(), w.end(), [&](double x) {
        return x >= options_.stillArmMinWidth_m && x <= options_.stillArmMaxWidth_m;
      });
      const double medianWidth_m = quantile(w, 0.5);
      lengths[static_cast<std::size_t>(l)].push_back(shape.length_m);
      widths[static_cast<std::size_t>(l)].push_back(medianWidth_m);
      if (static_cast<double>(within) >= options_.stillArmWidthShare * static_cast<double>(w.size()) &&
          shape.length_m >= options_.stillArmMinElongation * medianWidth_m)
        ++armLike[static_cast<std::size_t>(l)];
    }
  }
  for (int l = 1; l < n; ++l) {
    if (!keep[static_cast<std::size_t>(l)]) continue;
    const bool arm = armLike[static_cast<std::size_t>(l)] >= options_.stillArmShapeShare * withColour;
    if (core::Log::enabled("hand", core::Log::Level::Debug)) {
      auto median = [](const std::vector<double>& v) { return v.empty() ? 0.0 : quantile(v, 0.5); };
      core::Log::writef("hand", core::Log::Level::Debug,
                        "still arm: region of %d px at the border: arm-shaped in %d of %d samples (median length "
                        "%.3f m, width %.3f m): %s\n",
                        stats.at<int>(l, cv::CC_STAT_AREA), armLike[static_cast<std::size_t>(l)], withColour,
                        median(lengths[static_cast<std::size_t>(l)]), median(widths[static_cast<std::size_t>(l)]),
                        arm ? "an arm" : "not an arm");
    }
    keep[static_cast<std::size_t>(l)] = arm;
  }
}

cv::Mat MarkerFreeHandDetector::previewForeground(std::size_t i, const cv::Mat& backgroundHalf_mm,
                                                  const cv::Mat& depthHalf_mm, const cv::Mat& backgroundColourHalf) const {
  const cv::Mat& z = depthHalf_mm;
  cv::Mat fg = (z > 0) & (backgroundHalf_mm - z > 1e3 * options_.minForeground_m);
  const cv::Rect view(view_.x / 2, view_.y / 2, view_.width / 2, view_.height / 2);
  if (options_.holesInPreview) {
    // As foregroundMask sees each frame: a depth where a still camera's background has none (the arm in
    // front of a wall beyond the sensor's range), a depth hole whose colour changed from the
    // background's (a moving arm is more hole than depth on a ToF camera), inside the field of view.
    if (options_.farWithoutDepth && !cameraMoves_) fg |= (z > 0) & (backgroundHalf_mm <= 0);
    if (!backgroundColourHalf.empty() && backgroundColourHalf.size() == previewColour_[i].size()) {
      cv::Mat change;
      cv::absdiff(previewColour_[i], backgroundColourHalf, change);
      cv::transform(change, change, cv::Matx13f(1.f, 1.f, 1.f));  // sum of |BGR| changes (saturates at 255)
      cv::Mat hole = (z <= 0) & (change > options_.holeColourChange);
      if (cameraMoves_) hole &= backgroundHalf_mm > 0;  // a moving camera's background has a colour only there
      fg |= hole;
    }
    cv::Mat inView(fg.size(), CV_8UC1, cv::Scalar(0));
    inView(view & cv::Rect({0, 0}, fg.size())).setTo(255);
    fg &= inView;
  }
  if (!options_.skinFromArmOnly) return fg;
  // The arm: the components (once opened) that reach the field of view's edge, where the arm enters; a
  // part standing on the table or placed reaches none.
  cv::Mat opened, labels, stats, centroids;
  cv::morphologyEx(fg, opened, cv::MORPH_OPEN, disc(options_.previewOpenDiameter_px));
  const int n = cv::connectedComponentsWithStats(opened, labels, stats, centroids, 8, CV_32S);
  const std::vector<uchar> atBorder = labelsAtBorder(stats, view, options_.borderMargin_px / 2);
  cv::Mat arm(fg.size(), CV_8UC1, cv::Scalar(0));
  for (int v = 0; v < labels.rows; ++v) {
    const int* l = labels.ptr<int>(v);
    uchar* a = arm.ptr<uchar>(v);
    for (int u = 0; u < labels.cols; ++u) a[u] = l[u] > 0 && l[u] < n && atBorder[static_cast<std::size_t>(l[u])] ? 255 : 0;
  }
  return fg & arm;
}

void MarkerFreeHandDetector::decideBareForearms(const std::vector<cv::Mat>& fgHalf,
                                                const std::vector<cv::Mat>& depthHalf_mm) {
  // Does this demonstrator show a bare forearm? The largest skin-coloured
  // foreground component of each sample, longer than a hand in 3D.
  core::CameraIntrinsics k = previewIntrinsics_;
  k.fx_px /= 2;
  k.fy_px /= 2;
  k.cx_px /= 2;
  k.cy_px /= 2;
  const cv::Mat open = disc(options_.previewOpenDiameter_px);
  int withSkin = 0, bare = 0;
  for (std::size_t i = 0; i < previewDepth_mm_.size(); ++i) {
    if (previewColour_[i].empty()) continue;
    cv::Mat z_m;
    depthHalf_mm[i].convertTo(z_m, CV_32FC1, 1e-3);
    cv::Mat m = fgHalf[i] & skinMask(previewColour_[i], true);
    cv::morphologyEx(m, m, cv::MORPH_OPEN, open);
    cv::Mat cl, cs, cc;
    const int nc = cv::connectedComponentsWithStats(m, cl, cs, cc, 8, CV_32S);
    int best = -1, area = options_.minPreviewSkinPixels;
    for (int l = 1; l < nc; ++l)
      if (cs.at<int>(l, cv::CC_STAT_AREA) > area) {
        best = l;
        area = cs.at<int>(l, cv::CC_STAT_AREA);
      }
    if (best < 0) continue;
    ++withSkin;
    const cv::Mat comp = cl == best;
    std::vector<Eigen::Vector2d> pts;
    Eigen::Vector2d mean = Eigen::Vector2d::Zero();
    for (int v = 0; v < comp.rows; ++v)
      for (int u = 0; u < comp.cols; ++u)
        if (comp.at<uchar>(v, u)) {
          pts.emplace_back(u, v);
          mean += pts.back();
        }
    mean /= static_cast<double>(pts.size());
    Eigen::Matrix2d scatter = Eigen::Matrix2d::Zero();
    for (const auto& p : pts) scatter += (p - mean) * (p - mean).transpose();
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(scatter);
    const Eigen::Vector2d axis = eig.eigenvectors().col(1).normalized();
    double sMin = 1e9, sMax = -1e9;
    for (const auto& p : pts) {
      sMin = std::min(sMin, (p - mean).dot(axis));
      sMax = std::max(sMax, (p - mean).dot(axis));
    }
    const double zMean = medianDepthInDisc(z_m, comp, mean, 1e4, options_.minDepthSamples).value_or(0.0);
    if (zMean <= 0.0) continue;
    auto endPoint = [&](double sEnd) {
      const Eigen::Vector2d e = mean + sEnd * axis;
      const double z = medianDepthInDisc(z_m, comp, e, options_.palmRadius_m * k.fx_px / zMean,
                                         options_.minPreviewDepthSamples)
                           .value_or(zMean);
      return pixelToCamera(k, e.x(), e.y(), z);
    };
    const double length_m = (endPoint(sMax) - endPoint(sMin)).norm();
    if (length_m > options_.maxHandLength_m) ++bare;
    if (core::Log::enabled("hand", core::Log::Level::Debug))
      core::Log::writef("hand", core::Log::Level::Debug, "  preview sample %zu: skin %d px, %.0f px long, %.3f m\n", i,
                        area, sMax - sMin, length_m);
  }
  bareForearms_ = withSkin > 0 && bare >= options_.bareForearmFraction * withSkin;
  if (core::Log::enabled("hand", core::Log::Level::Debug))
    core::Log::writef("hand", core::Log::Level::Debug, "bare forearm in %d of %d samples: %s\n", bare, withSkin,
                      bareForearms_ ? "yes" : "no");
}

void MarkerFreeHandDetector::estimateIlluminant(const cv::Mat& background_bgr8) {
  // Once per recording, not per frame (cv::xphoto's balancers estimate per image): the skin model learnt
  // in the preview must see every frame through the same gains, and a frame's own mean moves with the
  // arm in it. The background, not the frame: the hand and a held part are no evidence of the lamp.
  skinGains_bgr_ = cv::Scalar(1.0, 1.0, 1.0, 0.0);
  const double p = options_.skinIlluminantNorm;
  if (p <= 0.0 || background_bgr8.empty()) return;
  cv::Mat f;
  background_bgr8.convertTo(f, CV_64FC3, 1.0 / 255.0);
  cv::pow(f, p, f);
  const cv::Scalar m = cv::mean(f);
  double e[3];
  for (int c = 0; c < 3; ++c) e[c] = std::pow(std::max(m[c], 1e-12), 1.0 / p);
  const double grey = 0.114 * e[0] + 0.587 * e[1] + 0.299 * e[2];  // the illuminant's luma (BGR order)
  for (int c = 0; c < 3; ++c) skinGains_bgr_[c] = grey / std::max(e[c], 1e-6);
  if (core::Log::enabled("hand", core::Log::Level::Debug))
    core::Log::writef("hand", core::Log::Level::Debug, "illuminant: BGR %.3f %.3f %.3f, gains %.3f %.3f %.3f\n", e[0],
                      e[1], e[2], skinGains_bgr_[0], skinGains_bgr_[1], skinGains_bgr_[2]);
}

cv::Mat MarkerFreeHandDetector::skinYCrCb(const cv::Mat& colour_bgr8) const {
  cv::Mat ycrcb;
  if (skinGains_bgr_ == cv::Scalar(1.0, 1.0, 1.0, 0.0)) {
    cv::cvtColor(colour_bgr8, ycrcb, cv::COLOR_BGR2YCrCb);
  } else {
    cv::Mat balanced;
    cv::multiply(colour_bgr8, skinGains_bgr_, balanced);
    cv::cvtColor(balanced, ycrcb, cv::COLOR_BGR2YCrCb);
  }
  return ycrcb;
}

cv::Mat MarkerFreeHandDetector::paleEnough(const cv::Mat& ycrcb) const {
  cv::Mat pale(ycrcb.size(), CV_8UC1, cv::Scalar(255));
  const double k = options_.skinMaxChromaPerLuma;
  if (k <= 0.0) return pale;
  // Squared, as 64-bit integers (k^2 Y^2 overflows an int for k above ~5.6): |(Cr - 128, Cb - 128)|^2 <= k^2 Y^2.
  const std::int64_t k2_1024 = std::llround(1024.0 * k * k);
  for (int v = 0; v < ycrcb.rows; ++v) {
    const cv::Vec3b* c = ycrcb.ptr<cv::Vec3b>(v);
    uchar* m = pale.ptr<uchar>(v);
    for (int u = 0; u < ycrcb.cols; ++u) {
      const int dr = c[u][1] - 128, db = c[u][2] - 128, y = c[u][0];
      m[u] = std::int64_t{1024} * (dr * dr + db * db) <= k2_1024 * y * y ? 255 : 0;
    }
  }
  return pale;
}

void MarkerFreeHandDetector::accumulateSkin(const cv::Mat& colour_bgr8, const cv::Mat& foreground, int step) {
  if (skinHistogram_.empty()) {
    skinHistogram_ = cv::Mat(256, 256, CV_32FC1, cv::Scalar(0));
  }
  const cv::Mat ycrcb = skinYCrCb(colour_bgr8);
  const Options& o = options_;
  for (int v = 0; v < ycrcb.rows; v += step) {
    const cv::Vec3b* c = ycrcb.ptr<cv::Vec3b>(v);
    const uchar* f = foreground.ptr<uchar>(v);
    for (int u = 0; u < ycrcb.cols; u += step) {
      if (f[u] && c[u][0] >= o.skinMinLuma && c[u][1] >= o.skinPriorCrMin && c[u][1] <= o.skinPriorCrMax &&
          c[u][2] >= o.skinPriorCbMin && c[u][2] <= o.skinPriorCbMax)
      {
        skinHistogram_.at<float>(c[u][1], c[u][2]) += 1.f;
        skinSamples_.push_back(c[u]);
      }
    }
  }
}

void MarkerFreeHandDetector::fitSkin() {
  if (skinHistogram_.empty()) return;
  // The mode of the smoothed histogram (JPEG chroma noise),
  // then mean and covariance of the counts within skinModeRadius of it.
  cv::Mat smooth;
  cv::GaussianBlur(skinHistogram_, smooth, {0, 0}, options_.skinHistogramBlur);
  cv::Point mode;
  cv::minMaxLoc(smooth, nullptr, nullptr, nullptr, &mode);
  const double r = options_.skinModeRadius;
  double w = 0.0;
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  Eigen::Matrix2d second = Eigen::Matrix2d::Zero();
  for (int cr = std::max(0, mode.y - static_cast<int>(r)); cr <= std::min(255, mode.y + static_cast<int>(r)); ++cr)
    for (int cb = std::max(0, mode.x - static_cast<int>(r)); cb <= std::min(255, mode.x + static_cast<int>(r)); ++cb) {
      const double n = skinHistogram_.at<float>(cr, cb);
      if (n <= 0.0 || std::hypot(cr - mode.y, cb - mode.x) > r) continue;
      const Eigen::Vector2d x(cr, cb);
      w += n;
      mean += n * x;
      second += n * x * x.transpose();
    }
  if (w < options_.minSkinSamples) {
    skin_.samples = static_cast<int>(w);
    return;
  }
  mean /= w;
  // + identity: the 8-bit quantisation (and a floor for a single-colour render).
  Eigen::Matrix2d cov = second / w - mean * mean.transpose() + Eigen::Matrix2d::Identity();
  // The window around the mode truncates the skin's spread (shading moves
  // the chroma along the skin line); re-estimate from the counts inside the
  // skinMaxMahalanobis ellipse of the current fit, a few times (a trimmed
  // estimate: stable for a Gaussian, it grows to the skin's real extent).
  const double maxD2 = options_.skinMaxMahalanobis * options_.skinMaxMahalanobis;
  for (int it = 0; it < options_.skinRefinements; ++it) {
    const Eigen::Matrix2d info = cov.inverse();
    double w2 = 0.0;
    Eigen::Vector2d m2 = Eigen::Vector2d::Zero();
    Eigen::Matrix2d s2 = Eigen::Matrix2d::Zero();
    for (int cr = 0; cr < 256; ++cr)
      for (int cb = 0; cb < 256; ++cb) {
        const double n = skinHistogram_.at<float>(cr, cb);
        if (n <= 0.0) continue;
        const Eigen::Vector2d x(cr, cb), d = x - mean;
        if (d.dot(info * d) > maxD2) continue;
        w2 += n;
        m2 += n * x;
        s2 += n * x * x.transpose();
      }
    if (w2 < options_.minSkinSamples) break;
    mean = m2 / w2;
    cov = s2 / w2 - mean * mean.transpose() + Eigen::Matrix2d::Identity();
    w = w2;
  }
  // The luma of the skin's pixels (those inside the chroma ellipse): the
  // mode of their luma histogram, then a trimmed mean and spread around it,
  // so that a bright toy or table of the skin's chroma (a second luma mode)
  // is not averaged in with this person's skin in this light.
  {
    const Eigen::Matrix2d info = cov.inverse();
    std::vector<std::uint8_t> lumas;
    cv::Mat hist(1, 256, CV_32FC1, cv::Scalar(0));
    for (const auto& c : skinSamples_) {
      const Eigen::Vector2d d = Eigen::Vector2d(c[1], c[2]) - mean;
      if (d.dot(info * d) > maxD2) continue;
      lumas.push_back(c[0]);
      hist.at<float>(0, c[0]) += 1.f;
    }
    // Mean and spread (+1: the 8-bit quantisation) of the lumas in [lo, hi].
    auto meanSd = [&](double lo, double hi) {
      double n = 0.0, sy = 0.0, syy = 0.0;
      for (const auto y : lumas)
        if (y >= lo && y <= hi) {
          n += 1.0;
          sy += y;
          syy += static_cast<double>(y) * y;
        }
      const double m = n > 0 ? sy / n : 0.0;
      return std::make_pair(m, n > 0 ? std::sqrt(std::max(0.0, syy / n - m * m)) + 1.0 : 255.0);
    };
    auto [meanY, sdY] = meanSd(0.0, 255.0);
    if (options_.skinLumaFromMode && !lumas.empty()) {
      cv::Mat smoothY;
      cv::GaussianBlur(hist, smoothY, {0, 0}, options_.skinLumaBlur, 0.0);
      cv::Point modeY;
      cv::minMaxLoc(smoothY, nullptr, nullptr, nullptr, &modeY);
      std::tie(meanY, sdY) = meanSd(modeY.x - options_.skinLumaModeRadius, modeY.x + options_.skinLumaModeRadius);
      for (int it = 0; it < options_.skinRefinements; ++it)
        std::tie(meanY, sdY) =
            meanSd(meanY - options_.skinMaxMahalanobis * sdY, meanY + options_.skinMaxMahalanobis * sdY);
    }
    skin_.meanLuma = meanY;
    skin_.sdLuma = sdY;
  }
  skin_.samples = static_cast<int>(w);
  skin_.covariance = cov;
  skin_.mean = mean;
  skin_.learnt = true;
  if (core::Log::enabled("hand", core::Log::Level::Debug))
    core::Log::writef("hand", core::Log::Level::Debug,
                      "skin: mode %d %d, mean %.1f %.1f, cov %.1f %.1f %.1f, luma %.1f sd %.1f, %d px\n", mode.y,
                      mode.x, mean.x(), mean.y(), cov(0, 0), cov(1, 1), cov(0, 1), skin_.meanLuma, skin_.sdLuma,
                      skin_.samples);
}

cv::Mat MarkerFreeHandDetector::skinMask(const cv::Mat& colour_bgr8, bool learnt, double maxMahalanobis) const {
  if (!options_.useSkin || colour_bgr8.empty()) return cv::Mat(colour_bgr8.size(), CV_8UC1, cv::Scalar(255));
  cv::Mat ycrcb = skinYCrCb(colour_bgr8), skin;
  const Options& o = options_;
  if (maxMahalanobis <= 0.0) maxMahalanobis = o.skinMaxMahalanobis;
  // The learnt model judges each pixel by its neighbourhood's mean colour
  // (sensor noise and JPEG's blocks fragment skin pixel by pixel).
  if (learnt && skin_.learnt && o.skinColourBlur_px > 1) cv::blur(ycrcb, ycrcb, {o.skinColourBlur_px, o.skinColourBlur_px});
  if (!learnt || !skin_.learnt) {
    cv::inRange(ycrcb, cv::Scalar(o.skinMinLuma, o.skinPriorCrMin, o.skinPriorCbMin),
                cv::Scalar(255, o.skinPriorCrMax, o.skinPriorCbMax), skin);
    return skin & paleEnough(ycrcb);
  }
  // Look-up table over (Cr, Cb): inside the Gaussian's skinMaxMahalanobis ellipse.
  const Eigen::Matrix2d info = skin_.covariance.inverse();
  const double maxD2 = maxMahalanobis * maxMahalanobis;
  cv::Mat lut(256, 256, CV_8UC1);
  for (int cr = 0; cr < 256; ++cr)
    for (int cb = 0; cb < 256; ++cb) {
      const Eigen::Vector2d d = Eigen::Vector2d(cr, cb) - skin_.mean;
      lut.at<uchar>(cr, cb) = d.dot(info * d) <= maxD2 ? 255 : 0;
    }
  // The luma floor: fixed, or a share of this recording's skin luma (a
  // darker recording, a darker skin: the floor follows the exposure).
  const double floor = o.skinLumaFloorFraction > 0.0
                           ? std::max(o.skinNoiseLuma, o.skinLumaFloorFraction * skin_.meanLuma)
                           : static_cast<double>(o.skinMinLuma);
  const double lumaMin = std::max(floor, skin_.meanLuma - maxMahalanobis * skin_.sdLuma);
  const double lumaMax = skin_.meanLuma + maxMahalanobis * skin_.sdLuma;
  skin = cv::Mat(ycrcb.size(), CV_8UC1);
  for (int v = 0; v < ycrcb.rows; ++v) {
    const cv::Vec3b* c = ycrcb.ptr<cv::Vec3b>(v);
    uchar* m = skin.ptr<uchar>(v);
    for (int u = 0; u < ycrcb.cols; ++u)
      m[u] = c[u][0] >= lumaMin && c[u][0] <= lumaMax ? lut.at<uchar>(c[u][1], c[u][2]) : 0;
  }
  return skin;
}

std::optional<HandObservation> MarkerFreeHandDetector::detect(const rawlog::RgbdFrame& frame) {
  rawlog::RgbdFrame shrunk;
  const rawlog::RgbdFrame& working = atWorkingSize(frame, shrunk);
  std::optional<HandObservation> h = detectAtWorkingSize(working);
  if (shrink_ <= 1) return h;
  const double f = shrink_;
  auto full = [f](Eigen::Vector2d& p_px) { p_px = f * (p_px.array() + 0.5) - 0.5; };
  full(geometry_.entry_px);
  full(geometry_.wrist_px);
  full(geometry_.farEnd_px);
  full(geometry_.palm_px);
  if (h) {
    full(h->palm_px);
    if (!lastMask_.empty()) {  // the working size's whole blocks: at most f - 1 columns/rows short of the frame
      cv::Mat up;
      cv::resize(lastMask_, up, {}, f, f, cv::INTER_NEAREST);
      lastMaskFull_ = cv::Mat::zeros(frame.depth_m.size(), CV_8UC1);
      up.copyTo(lastMaskFull_(cv::Rect(0, 0, up.cols, up.rows)));
    }
  }
  return h;
}

std::optional<HandObservation> MarkerFreeHandDetector::detectAtWorkingSize(const rawlog::RgbdFrame& frame) {
  geometry_ = Geometry{};
  ++frameCount_;
  if (!previewDepth_mm_.empty()) finishPreview();
  if (cameraMoves_) {
    const core::Pose3 X_camera0_camera = previewPose(frame.index);
    backgroundInView(X_camera0_camera, backgroundDepth_m_, &backgroundColour_);
    fillNarrowGaps(backgroundDepth_m_, backgroundColour_,
                   static_cast<int>(std::lround(options_.movingBackgroundGap * frame.depth_m.cols)));
    if (options_.enterThroughStillArm) enteringBackground_ = enteringBackground(backgroundDepth_m_, X_camera0_camera);
  }
  if (!backgroundDepth_m_.empty() && backgroundDepth_m_.size() != frame.depth_m.size())
    throw core::InvalidInputError("MarkerFreeHandDetector: frame " + std::to_string(frame.index) + " is " +
                                  std::to_string(frame.depth_m.cols) + "x" + std::to_string(frame.depth_m.rows) +
                                  ", the background " + std::to_string(backgroundDepth_m_.cols) + "x" +
                                  std::to_string(backgroundDepth_m_.rows) + ": a demo must come from one camera setting");
  if (backgroundDepth_m_.empty()) {
    depthHistory_.push_back(frame.depth_m.clone());
    colourHistory_.push_back(frame.colour_bgr8.clone());
    if (static_cast<int>(depthHistory_.size()) < options_.backgroundFrames) return std::nullopt;
    backgroundDepth_m_ = medianDepth(depthHistory_);
    view_ = depthFieldOfView(backgroundDepth_m_, options_.minFieldOfViewValid);
    // Colour background: the mean is enough (it is only used where depth is missing).
    cv::Mat acc(frame.colour_bgr8.size(), CV_32FC3, cv::Scalar::all(0));
    for (const auto& c : colourHistory_) cv::accumulate(c, acc);
    acc.convertTo(backgroundColour_, CV_8UC3, 1.0 / static_cast<double>(colourHistory_.size()));
    estimateIlluminant(backgroundColour_);
    depthHistory_.clear();
    colourHistory_.clear();
    return std::nullopt;  // background frames show no hand by assumption
  }

  // ---- the arm: the largest foreground component, preferring one at the border
  const cv::Mat mask = foregroundMask(frame);
  cv::Mat labels, stats, centroids;
  const int n = cv::connectedComponentsWithStats(mask, labels, stats, centroids, 8, CV_32S);
  zonePoints_ = borderZone(frame.depth_m);
  const std::vector<char> atBorder = labelsInZone(labels, n, zonePoints_);
  int bestLabel = -1, bestArea = 0;
  bool bestTouches = false;
  for (int l = 1; l < n; ++l) {
    const int area = stats.at<int>(l, cv::CC_STAT_AREA);
    if (area < options_.minPixels) continue;
    const bool touches = atBorder[static_cast<std::size_t>(l)];
    // Prefer components the arm connects to the border; then size.
    if ((touches && !bestTouches) || (touches == bestTouches && area > bestArea)) {
      bestLabel = l;
      bestArea = area;
      bestTouches = touches;
    }
  }
  const bool trace = core::Log::enabled("hand", core::Log::Level::Debug);
  if (trace)
    for (int l = 1; l < n; ++l)
      if (stats.at<int>(l, cv::CC_STAT_AREA) >= options_.minPixels)
        core::Log::writef("hand", core::Log::Level::Debug,
                          "frame %d: component %d px, box %d %d %d %d, view %d %d %d %d\n", frame.index,
                          stats.at<int>(l, cv::CC_STAT_AREA), stats.at<int>(l, 0), stats.at<int>(l, 1),
                          stats.at<int>(l, 2), stats.at<int>(l, 3), view_.x, view_.y, view_.width, view_.height);
  if (bestLabel < 0) {
    if (trace)
      core::Log::writef("hand", core::Log::Level::Debug, "frame %d: no foreground component of %d px\n", frame.index,
                        options_.minPixels);
    return std::nullopt;
  }
  const cv::Mat arm = (labels == bestLabel);

  // ---- the hand: the arm's skin part
  HandBlob hand;
  hand.mask = handMask(frame, arm);
  if (hand.mask.empty()) {
    if (trace)
      core::Log::writef("hand", core::Log::Level::Debug, "frame %d: arm %d px (border %d), skin on it below %d px\n",
                        frame.index, bestArea, bestTouches, options_.minHandPixels);
    return std::nullopt;
  }
  if (!bestTouches && cv::countNonZero(hand.mask) < options_.minIslandSkinFraction * bestArea) {
    // Foreground that reaches no border and is mostly not skin: a part about to be moved (the
    // whole-recording background shows what stood there later), a shaded side of skin-like colour.
    if (trace) std::fprintf(stderr, "frame %d: foreground away from the border, mostly not skin\n", frame.index);
    return std::nullopt;
  }
  lastMask_ = hand.mask;

  // Entry point: mean of the arm's border pixels (none: the arm's centroid).
  Eigen::Vector2d entry = Eigen::Vector2d::Zero();
  int nBorder = 0;
  for (const auto& p : zonePoints_)
    if (arm.at<uchar>(p)) {
      entry += Eigen::Vector2d(p.x, p.y);
      ++nBorder;
    }
  if (nBorder > 0) entry /= nBorder;
  else entry = {centroids.at<double>(bestLabel, 0), centroids.at<double>(bestLabel, 1)};
  geometry_.entry_px = entry;

  const cv::Mat sleeve = sleeveMask(arm, hand.mask);
  const auto handAxis = principalAxis(hand.mask, cv::Mat(), entry, options_.axisStride_px, options_.minElongation);
  if (!handAxis) return std::nullopt;
  const Eigen::Vector2d handMean = handAxis->mean;
  // Depth of the hand (median of its valid pixels) for the pixel scale.
  std::optional<double> z_hand = medianDepthInDisc(frame.depth_m, hand.mask, handMean, 1e4, options_.minDepthSamples);
  if (!z_hand && lastDepth_m_ > 0.0) z_hand = lastDepth_m_;
  if (!z_hand) return std::nullopt;  // no scale yet: the first frames of the hand are all depth holes
  hand.z_m = *z_hand;
  hand.pxPerM = frame.intrinsics.fx_px / hand.z_m;

  // ---- the palm's anchor: far end of a bare forearm, else the cuff, else the fingertips
  bool refused = false, entering = false;
  // A sleeve's cuff in view, in a recording without bare forearms: the wrist
  // is seen, whatever lengthens the skin beyond a hand (a held part of a
  // skin-like colour, its shaded faces).
  std::optional<Anchor> anchor;
  if (options_.cuffFirst && !bareForearms_) anchor = cuffAnchor(frame, hand.mask, sleeve, entry);
  if (!anchor) anchor = bareForearmAnchor(frame, arm, entry, hand, refused, entering);
  if (refused) {
    if (trace)
      core::Log::writef("hand", core::Log::Level::Debug, "frame %d: skin only near the body's entry, no palm\n",
                        frame.index);
    return std::nullopt;
  }
  if (!anchor && !entering) anchor = cuffAnchor(frame, hand.mask, sleeve, entry);
  if (!anchor) anchor = fingertipAnchor(hand.mask, entry, handMean, handAxis->dir, handAxis->elongated);
  geometry_.axis = anchor->dir;
  HandObservation h = placePalm(frame, *anchor, hand, handMean, bestArea);
  if (!h.hasDepth || options_.maxPalmSpeed_mps <= 0.0) return h;
  // Motion prior: after a track of palms, a palm farther from the last one
  // than the hand can move in the time between them is refused (a skin
  // patch on the face or the toy while the hand's skin is lost).
  // Measured across the ray (the palm's pixel shift at its depth): the
  // palm's depth along the ray jumps with the depth under the palm disc.
  if (palmTrack_ >= options_.minPalmTrack) {
    const double dt_s = std::max(0.0, frame.t_s - lastPalmT_s_);
    const double shift_m = (h.palm_px - lastPalm_px_).norm() * h.p_camera_palm_m.z() / frame.intrinsics.fx_px;
    if (shift_m > options_.maxPalmSpeed_mps * dt_s) {
      if (trace)
        core::Log::writef("hand", core::Log::Level::Debug, "frame %d: palm refused, %.3f m from the last in %.3f s\n",
                          frame.index, shift_m, dt_s);
      if (++palmRefusals_ <= options_.maxPalmRefusals) return std::nullopt;
      palmTrack_ = 0;  // refused too often: the track itself may be wrong, start a new one
    }
  }
  palmRefusals_ = 0;
  ++palmTrack_;
  lastPalm_px_ = h.palm_px;
  lastPalmT_s_ = frame.t_s;
  return h;
}

std::vector<cv::Point> MarkerFreeHandDetector::borderZone(const cv::Mat& depth_m) const {
  // Within borderMargin_px of the image edge, and where the depth's field of
  // view ends inside the image (view_ leaves a band on that side), within
  // borderMargin_px of this frame's band: the run of depth-less pixels from
  // the image edge along each row (column). The band's inner edge moves with
  // the depth (the depth camera sees from beside the colour camera): an arm
  // 1 m away ends 7 px farther out than the wall behind it on HRT1's camera.
  const int m = options_.borderMargin_px, W = depth_m.cols, H = depth_m.rows;
  cv::Mat zone(depth_m.size(), CV_8UC1, cv::Scalar(0));
  std::vector<cv::Point> points;
  auto add = [&](int u, int v) {
    if (!view_.contains({u, v})) return;  // no foreground outside the field of view
    uchar& z = zone.ptr<uchar>(v)[u];
    if (!z) {
      z = 255;
      points.emplace_back(u, v);
    }
  };
  for (int v = 0; v < H; ++v) {
    if (v < m || v >= H - m) {
      for (int u = 0; u < W; ++u) add(u, v);
    } else {
      for (int u = 0; u < std::min(m, W); ++u) add(u, v);
      for (int u = std::max(0, W - m); u < W; ++u) add(u, v);
    }
  }
  // Runs of depth-less pixels from each side with a band; the zone takes the
  // pixels within m of a run (a (2m+1)-square dilation of the staircase the
  // runs form: per row the longest run of the rows within m, plus m).
  // A run counts up to the band's width plus maxBandParallax_px: farther in,
  // the pixels lack depth for another reason (a wall beyond the sensor's
  // range behind the arm, seen from the side), and the arm's edge there is
  // not where it enters.
  auto mark = [&](bool alongRows, bool fromEnd, int band) {
    const int n = alongRows ? H : W, len = alongRows ? W : H;
    const int maxRun = options_.maxBandParallax_px >= 0 ? std::min(len, band + options_.maxBandParallax_px) : len;
    auto depthAt = [&](int i, int j) { return alongRows ? depth_m.ptr<float>(i)[j] : depth_m.ptr<float>(j)[i]; };
    std::vector<int> run(static_cast<std::size_t>(n), 0);
    for (int i = 0; i < n; ++i) {
      int k = 0;
      while (k < maxRun && depthAt(i, fromEnd ? len - 1 - k : k) <= 0.f) ++k;
      run[static_cast<std::size_t>(i)] = k;
    }
    for (int i = 0; i < n; ++i) {
      int longest = 0;
      for (int d = std::max(0, i - m); d <= std::min(n - 1, i + m); ++d)
        longest = std::max(longest, run[static_cast<std::size_t>(d)]);
      if (longest == 0) continue;
      for (int k = 0; k < std::min(len, longest + m); ++k) {
        const int j = fromEnd ? len - 1 - k : k;
        if (alongRows) add(j, i);
        else add(i, j);
      }
    }
  };
  // Under a moving camera, the background through which an arm in view in every frame enters.
  if (!enteringBackground_.empty() && enteringBackground_.size() == depth_m.size())
    for (int v = 0; v < H; ++v) {
      const uchar* e = enteringBackground_.ptr<uchar>(v);
      for (int u = 0; u < W; ++u)
        if (e[u]) add(u, v);
    }
  if (view_.x > 0) mark(true, false, view_.x);
  if (view_.x + view_.width < W) mark(true, true, W - view_.x - view_.width);
  if (view_.y > 0) mark(false, false, view_.y);
  if (view_.y + view_.height < H) mark(false, true, H - view_.y - view_.height);
  return points;
}

cv::Mat MarkerFreeHandDetector::foregroundMask(const rawlog::RgbdFrame& frame) const {
  // Foreground by depth (the whole arm, sleeve included, reaches the border);
  // the hand is its skin-coloured part.
  const cv::Mat& depth = frame.depth_m;
  const bool hasColour = !frame.colour_bgr8.empty();
  const bool farWithoutDepth = options_.farWithoutDepth && !cameraMoves_;  // moving: no background = not seen
  cv::Mat mask(depth.size(), CV_8UC1, cv::Scalar(0));
  for (int v = 0; v < depth.rows; ++v) {
    const float* z = depth.ptr<float>(v);
    const float* bg = backgroundDepth_m_.ptr<float>(v);
    uchar* m = mask.ptr<uchar>(v);
    for (int u = 0; u < depth.cols; ++u) {
      if (z[u] > 0.f && bg[u] > 0.f) m[u] = (bg[u] - z[u] > options_.minForeground_m) ? 255 : 0;
      else if (z[u] > 0.f && farWithoutDepth) m[u] = 255;  // a depth where the background has none
      else if (z[u] <= 0.f && hasColour && !backgroundColour_.empty() && (bg[u] > 0.f || !cameraMoves_)) {
        // (A moving camera's background has a colour only where it has a depth.)
        // A hole (moving hand): foreground when the colour changed.
        const cv::Vec3b a = frame.colour_bgr8.at<cv::Vec3b>(v, u), b = backgroundColour_.at<cv::Vec3b>(v, u);
        const int diff = std::abs(a[0] - b[0]) + std::abs(a[1] - b[1]) + std::abs(a[2] - b[2]);
        m[u] = diff > options_.holeColourChange ? 255 : 0;
      }
    }
  }
  // Outside the depth's field of view every pixel is a hole: no evidence there.
  mask.rowRange(0, view_.y).setTo(0);
  mask.rowRange(view_.y + view_.height, mask.rows).setTo(0);
  mask.colRange(0, view_.x).setTo(0);
  mask.colRange(view_.x + view_.width, mask.cols).setTo(0);
  cv::morphologyEx(mask, mask, cv::MORPH_OPEN, disc(options_.openDiameter_px));
  return mask;
}

cv::Mat MarkerFreeHandDetector::handMask(const rawlog::RgbdFrame& frame, const cv::Mat& arm) const {
  // The recording's skin model for a bare forearm; the prior box for a glove
  // and sleeve (the cuff rule's lengths were measured with it).
  const cv::Mat skin = !frame.colour_bgr8.empty() ? skinMask(frame.colour_bgr8, bareForearms_)
                                                  : cv::Mat(arm.size(), CV_8UC1, cv::Scalar(255));
  cv::Mat hand = arm & skin;
  if (bareForearms_ && skin_.learnt && options_.skinGrowMahalanobis > options_.skinMaxMahalanobis) {
    // Hysteresis: arm pixels inside the wider ellipse join the skin they
    // touch (a forearm in shadow or noise fragments the strict skin).
    const cv::Mat weak = arm & skinMask(frame.colour_bgr8, true, options_.skinGrowMahalanobis);
    cv::Mat wl;
    const int nw = cv::connectedComponents(weak, wl, 8, CV_32S);
    std::vector<char> seeded(static_cast<std::size_t>(nw), 0);
    for (int v = 0; v < arm.rows; ++v) {
      const int* l = wl.ptr<int>(v);
      const uchar* h = hand.ptr<uchar>(v);
      for (int u = 0; u < arm.cols; ++u)
        if (h[u]) seeded[static_cast<std::size_t>(l[u])] = 1;
    }
    for (int v = 0; v < arm.rows; ++v) {
      const int* l = wl.ptr<int>(v);
      uchar* h = hand.ptr<uchar>(v);
      for (int u = 0; u < arm.cols; ++u)
        if (l[u] > 0 && seeded[static_cast<std::size_t>(l[u])]) h[u] = 255;
    }
  }
  cv::Mat allowed = arm.clone();  // where the hand may lie: the arm, and skin the depth lags behind
  if (bareForearms_ && options_.maxDepthLag_px > 0) {
    // Depth lagging colour (a fast arm): skin within maxDepthLag_px of the
    // arm, whose colour changed strongly from the background's, counts when
    // it is connected to skin the depth puts on the arm (a dark hand over the
    // bright wall changes by far more than a shadow moving on the wall).
    cv::Mat distance_px;  // from the arm (a distance transform: a 61 px dilation costs ~8 ms)
    cv::distanceTransform(~arm, distance_px, cv::DIST_L2, cv::DIST_MASK_5);
    cv::Mat near = (distance_px <= options_.maxDepthLag_px) & skin;
    if (!backgroundColour_.empty())
      for (int v = 0; v < arm.rows; ++v) {
        uchar* n = near.ptr<uchar>(v);
        const uchar* a = arm.ptr<uchar>(v);
        const cv::Vec3b* c = frame.colour_bgr8.ptr<cv::Vec3b>(v);
        const cv::Vec3b* b = backgroundColour_.ptr<cv::Vec3b>(v);
        for (int u = 0; u < arm.cols; ++u)
          if (n[u] && !a[u] &&
              std::abs(c[u][0] - b[u][0]) + std::abs(c[u][1] - b[u][1]) + std::abs(c[u][2] - b[u][2]) <=
                  options_.minLagColourChange)
            n[u] = 0;
      }
    cv::Mat cl;
    const int nc = cv::connectedComponents(near, cl, 8, CV_32S);
    std::vector<int> onArm(nc, 0);
    for (int v = 0; v < arm.rows; ++v) {
      const int* l = cl.ptr<int>(v);
      const uchar* h = hand.ptr<uchar>(v);
      for (int u = 0; u < arm.cols; ++u)
        if (h[u]) ++onArm[l[u]];
    }
    for (int v = 0; v < arm.rows; ++v) {
      const int* l = cl.ptr<int>(v);
      uchar* h = hand.ptr<uchar>(v);
      for (int u = 0; u < arm.cols; ++u)
        if (l[u] > 0 && onArm[l[u]] >= options_.minHandPixels) h[u] = allowed.at<uchar>(v, u) = 255;
    }
  }
  if (options_.skinGapClose_m > 0.0) closeSkinGaps(frame, arm, hand);
  cv::morphologyEx(hand, hand, cv::MORPH_OPEN, disc(options_.openDiameter_px));
  if (cv::countNonZero(hand) < options_.minHandPixels) return cv::Mat();
  // Fill holes (a held object, a badge on the glove): the palm disc's depth
  // and the sleeve (the arm's non-skin part) must not include them.
  std::vector<std::vector<cv::Point>> contours;
  cv::findContours(hand.clone(), contours, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_SIMPLE);
  cv::drawContours(hand, contours, -1, cv::Scalar(255), cv::FILLED);
  hand &= allowed;
  return hand;
}

void MarkerFreeHandDetector::closeSkinGaps(const rawlog::RgbdFrame& frame, const cv::Mat& arm, cv::Mat& skin) const {
  // The disc's diameter in pixels at the arm's median valid depth (a disc past the image: every arm pixel).
  const auto z_m = medianDepthInDisc(frame.depth_m, arm, Eigen::Vector2d(arm.cols / 2.0, arm.rows / 2.0), 1e4,
                                     options_.minDepthSamples);
  if (!z_m) return;
  const int diameter_px = static_cast<int>(std::lround(options_.skinGapClose_m * frame.intrinsics.fx_px / *z_m));
  if (diameter_px < 2) return;
  cv::Mat closed;
  cv::morphologyEx(skin, closed, cv::MORPH_CLOSE, disc(diameter_px | 1));
  // Closed across a wire or a patch on the arm, not past the arm's outline, and only added: the skin the
  // depth lags behind (outside the arm, a fast hand's fingers) stays.
  skin |= closed & arm;
}

cv::Mat MarkerFreeHandDetector::sleeveMask(const cv::Mat& arm, const cv::Mat& hand) const {
  // The sleeve: the non-skin part of the arm that reaches the border (a
  // carried object under the hand does not).
  const cv::Mat rest = arm & ~hand;
  cv::Mat sl, ss, sc;
  const int ns = cv::connectedComponentsWithStats(rest, sl, ss, sc, 8, CV_32S);
  const std::vector<char> atBorder = labelsInZone(sl, ns, zonePoints_);
  int best = -1, area = options_.minSleevePixels;
  for (int l = 1; l < ns; ++l)
    if (ss.at<int>(l, cv::CC_STAT_AREA) > area && atBorder[static_cast<std::size_t>(l)]) {
      best = l;
      area = ss.at<int>(l, cv::CC_STAT_AREA);
    }
  return best > 0 ? cv::Mat(sl == best) : cv::Mat(arm.size(), CV_8UC1, cv::Scalar(0));
}

std::optional<MarkerFreeHandDetector::Anchor> MarkerFreeHandDetector::bareForearmAnchor(
    const rawlog::RgbdFrame& frame, const cv::Mat& arm, const Eigen::Vector2d& entry, HandBlob& hand, bool& refused,
    bool& entering) {
  // Bare forearm: the skin component that reaches farthest from the body
  // (see farthestSkinComponent; the largest when the geodesic is off), when it
  // is longer than a hand (skin from the elbow or a short sleeve to the
  // fingers), ends in the hand at the end farther from the arm's entry.
  const auto& k = frame.intrinsics;
  cv::Mat cl, cs, cc;
  const int nc = cv::connectedComponentsWithStats(hand.mask, cl, cs, cc, 8, CV_32S);
  int best = -1, bestArea = 0;
  for (int l = 1; l < nc; ++l)
    if (cs.at<int>(l, cv::CC_STAT_AREA) > bestArea) {
      best = l;
      bestArea = cs.at<int>(l, cv::CC_STAT_AREA);
    }
  int reachCells = -1, bodyReachCells = -1;
  if (options_.geodesicStep_px > 0 && (nc > 2 || options_.minSkinReach_m > 0.0)) {
    const int far = farthestSkinComponent(arm | hand.mask, cl, nc, cs, &reachCells, &bodyReachCells);
    if (far > 0) {
      best = far;
      bestArea = cs.at<int>(far, cv::CC_STAT_AREA);
    }
  }
  if (best <= 0 || bestArea < options_.minHandPixels) return std::nullopt;
  const cv::Mat comp = cl == best;
  const auto ax = principalAxis(comp, cv::Mat(), entry, options_.axisStride_px, options_.minElongation);
  if (!ax) return std::nullopt;
  const int stride = options_.axisStride_px;
  std::vector<Eigen::Vector2d> pts;
  for (int v = 0; v < comp.rows; v += stride) {
    const uchar* p = comp.ptr<uchar>(v);
    for (int u = 0; u < comp.cols; u += stride)
      if (p[u]) pts.emplace_back(u, v);
  }
  Eigen::Vector2d axis = ax->dir;
  double sMin = 1e9, sMax = -1e9;
  for (const auto& p : pts) {
    sMin = std::min(sMin, (p - ax->mean).dot(axis));
    sMax = std::max(sMax, (p - ax->mean).dot(axis));
  }
  if ((ax->mean + sMin * axis - entry).norm() > (ax->mean + sMax * axis - entry).norm()) {
    axis = -axis;
    std::swap(sMin, sMax);
    sMin = -sMin;
    sMax = -sMax;
  }
  const double z_comp = medianDepthInDisc(frame.depth_m, comp, ax->mean, 1e4, options_.minDepthSamples).value_or(hand.z_m);
  const double compPxPerM = k.fx_px / z_comp;
  if (core::Log::enabled("hand", core::Log::Level::Debug))
    core::Log::writef("hand", core::Log::Level::Debug,
                      "frame %d: comp area %d of %d, extent %.0f px = %.3f m at z %.2f, entry %.0f %.0f\n", frame.index,
                      bestArea, nc - 1, sMax - sMin, (sMax - sMin) / compPxPerM, z_comp, entry.x(), entry.y());
  // Its length in 3D (a forearm pointing at the camera looks short).
  auto endPoint = [&](double sEnd) {
    const Eigen::Vector2d e = ax->mean + sEnd * axis;
    const double z = medianDepthInDisc(frame.depth_m, comp, e, options_.palmRadius_m * compPxPerM, options_.minDepthSamples)
                         .value_or(z_comp);
    return pixelToCamera(k, e.x(), e.y(), z);
  };
  const double length3d_m = (endPoint(sMax) - endPoint(sMin)).norm();
  if (core::Log::enabled("hand", core::Log::Level::Debug))
    core::Log::writef("hand", core::Log::Level::Debug, "  3D length %.3f m\n", length3d_m);
  if (!(length3d_m > options_.maxHandLength_m || bareForearms_)) return std::nullopt;
  if (length3d_m <= options_.maxHandLength_m && options_.handFirstAtTheBorder) {
    // No longer than a hand and its skin on the border: the hand entering or leaving the view, fingers
    // first or last, its forearm out of view; no far end of a forearm.
    int onBorder = 0;
    for (const auto& p : zonePoints_)
      if (comp.at<uchar>(p)) ++onBorder;
    if (onBorder >= options_.minCuffPixels) {
      entering = true;
      return std::nullopt;
    }
  }
  // The hand is the arm's far end over the workspace: skin that reaches no
  // farther than minSkinReach_m from where the body enters the view (along
  // the body) is the face, the neck or the shoulder, with the forearm's skin
  // lost (dark light): no palm rather than one on the head.
  const double reach_m = reachCells >= 0 ? reachCells * options_.geodesicStep_px / compPxPerM : -1.0;
  if (core::Log::enabled("hand", core::Log::Level::Debug))
    core::Log::writef("hand", core::Log::Level::Debug, "frame %d: skin reach %.3f m (%d cells), body reach %d cells\n",
                      frame.index, reach_m, reachCells, bodyReachCells);
  if (options_.minSkinReach_m > 0.0 && reachCells >= 0 && reach_m < options_.minSkinReach_m) {
    refused = true;
    return std::nullopt;
  }
  // The hand's own axis and centre line: the last maxHandLength_m.
  const double from = sMax - options_.maxHandLength_m * compPxPerM;
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  Eigen::Matrix2d scatter = Eigen::Matrix2d::Zero();
  int count = 0;
  for (const auto& p : pts)
    if ((p - ax->mean).dot(axis) >= from) {
      mean += p;
      scatter += p * p.transpose();
      ++count;
    }
  mean /= count;
  scatter = scatter / count - mean * mean.transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(scatter);
  Eigen::Vector2d local = eig.eigenvectors().col(1).normalized();
  if (local.dot(axis) < 0) local = -local;
  double tip = -1e9;
  for (const auto& p : pts)
    if ((p - ax->mean).dot(axis) >= from) tip = std::max(tip, (p - mean).dot(local));
  Anchor a;
  a.anchor_px = mean + tip * local;
  a.dir = local;
  a.length_m = -options_.palmFromFarEnd_m;
  a.closedFarEnd = true;
  geometry_.farEnd_px = a.anchor_px;
  if (options_.farEndOpenHand) {
    const double zEnd = endPoint(sMax).z();
    const Eigen::Vector3d farEnd_m = pixelToCamera(k, a.anchor_px.x(), a.anchor_px.y(), zEnd);
    if (openHandAtFarEnd(frame, arm, comp, farEnd_m, a.anchor_px, local)) {
      a.length_m = -options_.palmFromFingertips_m;
      a.closedFarEnd = false;
    }
  }
  hand.mask = comp;
  hand.z_m = z_comp;
  hand.pxPerM = compPxPerM;
  lastMask_ = hand.mask;
  geometry_.bareForearm = true;
  return a;
}

bool MarkerFreeHandDetector::openHandAtFarEnd(const rawlog::RgbdFrame& frame, const cv::Mat& arm, const cv::Mat& comp,
                                              const Eigen::Vector3d& farEnd_m, const Eigen::Vector2d& farEnd_px,
                                              const Eigen::Vector2d& dir) const {
  const auto& k = frame.intrinsics;
  // A hand holding a part is closed round it: the arm's foreground that is not skin, joined to the
  // hand, reaching past the skin's far end by more than palmRadius_m (the part; a few fingertip pixels
  // the skin model missed reach less) makes the far end the curled fingers.
  {
    cv::Mat labels;
    cv::connectedComponents(arm | comp, labels, 8, CV_32S);
    std::vector<int> count;
    for (int v = 0; v < comp.rows; ++v) {
      const uchar* c = comp.ptr<uchar>(v);
      const int* l = labels.ptr<int>(v);
      for (int u = 0; u < comp.cols; ++u)
        if (c[u]) {
          if (static_cast<std::size_t>(l[u]) >= count.size()) count.resize(static_cast<std::size_t>(l[u]) + 1, 0);
          ++count[static_cast<std::size_t>(l[u])];
        }
    }
    const int body = static_cast<int>(std::max_element(count.begin(), count.end()) - count.begin());
    double beyond_px = 0.0;
    for (int v = 0; v < labels.rows; ++v) {
      const int* l = labels.ptr<int>(v);
      const uchar* c = comp.ptr<uchar>(v);
      for (int u = 0; u < labels.cols; ++u)
        if (l[u] == body && !c[u]) beyond_px = std::max(beyond_px, (Eigen::Vector2d(u, v) - farEnd_px).dot(dir));
    }
    const double beyond_m = beyond_px * farEnd_m.z() / k.fx_px;
    if (beyond_m > options_.palmRadius_m) {
      if (core::Log::enabled("hand", core::Log::Level::Debug))
        core::Log::writef("hand", core::Log::Level::Debug,
                          "frame %d: the arm reaches %.3f m past the skin's far end: a held part, closed hand\n",
                          frame.index, beyond_m);
      return false;
    }
  }
  // Open or closed: the far end is the fingertips of an open hand (palmFromFingertips_m from the palm
  // centre) or the curled fingers of a closed one (palmFromFarEnd_m). The palm is the hand's thickest
  // part: the distance transform's maximum, in metres (each pixel at its own depth), among the skin
  // within maxHandLength_m of the far end (in 3D: a hand pointing away from the camera is
  // foreshortened). Lying past the middle of the two lengths (and within palmRadius_m of the open
  // hand's palm centre), the hand may be open; farther back it is the forearm (the hand on its edge).
  const cv::Rect box = cv::boundingRect(comp);
  cv::Mat padded(box.height + 2, box.width + 2, CV_8UC1, cv::Scalar(0)), distance;
  comp(box).copyTo(padded(cv::Rect(1, 1, box.width, box.height)));
  cv::distanceTransform(padded, distance, cv::DIST_L2, cv::DIST_MASK_5);
  auto backFromFarEnd_m = [&](int x, int y, float z) {
    return (pixelToCamera(k, x, y, z) - farEnd_m).norm();
  };
  double thickest_m = 0.0, thickestBack_m = 0.0;
  for (int v = 0; v < box.height; ++v) {
    const float* d = distance.ptr<float>(v + 1) + 1;
    const float* z = frame.depth_m.ptr<float>(box.y + v);
    for (int u = 0; u < box.width; ++u) {
      const int x = box.x + u, y = box.y + v;
      if (d[u] <= 0.f || z[x] <= 0.f || d[u] * z[x] / k.fx_px <= thickest_m ||
          (farEnd_px - Eigen::Vector2d(x, y)).dot(dir) < 0.0)
        continue;
      const double back_m = backFromFarEnd_m(x, y, z[x]);
      if (back_m > options_.maxHandLength_m) continue;
      thickest_m = d[u] * z[x] / k.fx_px;
      thickestBack_m = back_m;
    }
  }
  // An open hand's palm is wider than its wrist: behind it (2-3 palm radii farther from the far end,
  // inside the view, not cut by its edge) the skin is narrower. A closed hand whose palm the held part
  // hides at its sides is thickest at its wrist, with the forearm as thick behind it.
  double behind_m = -1.0;
  const cv::Rect inner = inset(view_, options_.borderMargin_px);
  for (int v = 0; v < box.height; ++v) {
    const float* d = distance.ptr<float>(v + 1) + 1;
    const float* z = frame.depth_m.ptr<float>(box.y + v);
    for (int u = 0; u < box.width; ++u) {
      const int x = box.x + u, y = box.y + v;
      if (d[u] <= 0.f || z[x] <= 0.f || !inner.contains(cv::Point(x, y))) continue;
      const double back_m = backFromFarEnd_m(x, y, z[x]);
      if (back_m >= thickestBack_m + 2.0 * options_.palmRadius_m && back_m <= thickestBack_m + 3.0 * options_.palmRadius_m)
        behind_m = std::max(behind_m, static_cast<double>(d[u] * z[x] / k.fx_px));
    }
  }
  // The thickest point alone does not tell an open hand from a hand hanging from a flexed wrist (seen
  // from the side, its fingers curled down towards the table): the distance transform is largest in
  // the corner where the forearm meets the hanging hand, 10 cm from its far end, and grows steadily
  // towards it as over an open hand's fingers. The hand's breadth across the axis does: an open hand is
  // broadest at its palm (and thumb), past the middle of the two lengths from its fingertips, and
  // narrower over its fingers; a closed hand is broadest within palmFromFarEnd_m of its far end (the
  // knuckles, the curled fingers, the hanging hand's span across the forearm).
  const double middle_m = 0.5 * (options_.palmFromFarEnd_m + options_.palmFromFingertips_m);
  constexpr double kSlice_m = 0.01;  // a finger's width: the breadth's steps along the axis
  const int slices = static_cast<int>(std::ceil((options_.palmFromFingertips_m + options_.palmRadius_m) / kSlice_m));
  Anchor back;  // from the far end backwards, for the hand's depth profile
  back.anchor_px = farEnd_px;
  back.dir = dir;
  back.length_m = -(options_.palmFromFingertips_m + options_.palmRadius_m);
  HandBlob blob;
  blob.mask = comp;
  blob.z_m = farEnd_m.z();
  blob.pxPerM = k.fx_px / farEnd_m.z();
  const Eigen::Vector2d line = handTilt(frame, back, blob).value_or(Eigen::Vector2d(farEnd_m.z(), 0.0));
  const std::vector<double> breadth_m = breadthFromEnd(comp, k, farEnd_px, dir, line, kSlice_m, slices);
  const auto broadest = std::max_element(breadth_m.begin(), breadth_m.end()) - breadth_m.begin();
  const double broadestBack_m = (static_cast<double>(broadest) + 0.5) * kSlice_m;
  const bool open = thickestBack_m > middle_m && thickestBack_m <= options_.palmFromFingertips_m + options_.palmRadius_m &&
                    behind_m > 0.0 && behind_m < options_.maxWristToPalm * thickest_m && broadestBack_m > middle_m;
  if (core::Log::enabled("hand", core::Log::Level::Debug)) {
    std::string row;
    for (const double b : breadth_m) row += " " + std::to_string(std::lround(1e3 * b));
    core::Log::writef("hand", core::Log::Level::Debug,
                      "frame %d: thickest %.3f m, %.3f m from the far end, %.3f m behind; broadest %.3f m from the "
                      "far end (breadth per cm [mm]:%s): %s\n",
                      frame.index, thickest_m, thickestBack_m, behind_m, broadestBack_m, row.c_str(),
                      open ? "open hand" : "closed hand");
  }
  return open;
}

int MarkerFreeHandDetector::farthestSkinComponent(const cv::Mat& region, const cv::Mat& labels, int n,
                                                  const cv::Mat& stats, int* reachCells, int* bodyReachCells) const {
  // Geodesic distance inside the body's foreground (arm and hand) from where
  // it enters the view (the border zone), on a grid of geodesicStep_px
  // (a cell belongs to the region when any of its pixels does; 8-neighbour
  // steps). The hand is the far end of the arm reaching over the workspace:
  // trousers, a face or a neck of skin colour lie near where the body enters.
  const int step = options_.geodesicStep_px;
  const cv::Rect box = cv::boundingRect(region);  // cells on the region's box only
  const int W = (box.width + step - 1) / step, H = (box.height + step - 1) / step;
  cv::Mat cellRegion;
  cv::resize(region(box), cellRegion, {W, H}, 0, 0, cv::INTER_AREA);
  std::vector<int> dist(static_cast<std::size_t>(W * H), -1), queue;
  queue.reserve(dist.size());
  for (const auto& p : zonePoints_) {
    if (!box.contains(p) || !region.at<uchar>(p)) continue;
    const int c = ((p.y - box.y) / step) * W + (p.x - box.x) / step;
    if (dist[static_cast<std::size_t>(c)] == 0) continue;
    dist[static_cast<std::size_t>(c)] = 0;
    queue.push_back(c);
  }
  if (queue.empty()) return -1;  // the body does not enter the view here: no direction to go by
  for (std::size_t head = 0; head < queue.size(); ++head) {
    const int c = queue[head], cu = c % W, cv_ = c / W;
    for (int dv = -1; dv <= 1; ++dv)
      for (int du = -1; du <= 1; ++du) {
        const int u = cu + du, v = cv_ + dv;
        if (u < 0 || v < 0 || u >= W || v >= H || !cellRegion.at<uchar>(v, u)) continue;
        int& d = dist[static_cast<std::size_t>(v * W + u)];
        if (d >= 0) continue;
        d = dist[static_cast<std::size_t>(c)] + 1;
        queue.push_back(v * W + u);
      }
  }
  // Each component's farthest cell; the largest component among those that
  // reach within one cell of the farthest.
  std::vector<int> reach(static_cast<std::size_t>(n), -1);
  for (int k = 1; k < n; ++k) {
    if (stats.at<int>(k, cv::CC_STAT_AREA) < options_.minHandPixels) continue;
    const int x0 = stats.at<int>(k, cv::CC_STAT_LEFT), y0 = stats.at<int>(k, cv::CC_STAT_TOP);
    for (int v = y0; v < y0 + stats.at<int>(k, cv::CC_STAT_HEIGHT); ++v) {
      const int* l = labels.ptr<int>(v);
      for (int u = x0; u < x0 + stats.at<int>(k, cv::CC_STAT_WIDTH); ++u)
        if (l[u] == k)
          reach[static_cast<std::size_t>(k)] =
              std::max(reach[static_cast<std::size_t>(k)],
                       dist[static_cast<std::size_t>(((v - box.y) / step) * W + (u - box.x) / step)]);
    }
  }
  int best = -1;
  for (int l = 1; l < n; ++l) {
    if (stats.at<int>(l, cv::CC_STAT_AREA) < options_.minHandPixels || reach[static_cast<std::size_t>(l)] < 0) continue;
    if (best < 0 || reach[static_cast<std::size_t>(l)] > reach[static_cast<std::size_t>(best)]) best = l;
  }
  if (reachCells) *reachCells = best > 0 ? reach[static_cast<std::size_t>(best)] : -1;
  if (bodyReachCells) *bodyReachCells = *std::max_element(dist.begin(), dist.end());
  if (core::Log::enabled("hand", core::Log::Level::Debug))
    for (int l = 1; l < n; ++l)
      core::Log::writef("hand", core::Log::Level::Debug, "  skin component %d: %d px, reach %d cells%s\n", l,
                        stats.at<int>(l, cv::CC_STAT_AREA), reach[static_cast<std::size_t>(l)],
                        l == best ? " (picked)" : "");
  return best;
}

std::optional<MarkerFreeHandDetector::Anchor> MarkerFreeHandDetector::cuffAnchor(const rawlog::RgbdFrame& frame,
                                                                                  const cv::Mat& hand,
                                                                                  const cv::Mat& sleeve,
                                                                                  const Eigen::Vector2d& entry) {
  // Wrist: the cuff line, skin pixels next to the sleeve. Not when the skin
  // itself reaches the border (the hand entering or leaving: the cuff is out
  // of view, the "sleeve" may be something else).
  const int margin = options_.borderMargin_px;
  int handOnBorder = 0;
  const cv::Rect& w = view_;
  for (int v = w.y; v < w.y + w.height; ++v) {
    const uchar* p = hand.ptr<uchar>(v);
    if (v < w.y + margin || v >= w.y + w.height - margin) {
      handOnBorder += cv::countNonZero(hand.row(v).colRange(w.x, w.x + w.width));
    } else {
      bool left = false, right = false;
      for (int i = 0; i < margin; ++i) {
        left = left || p[w.x + i];
        right = right || p[w.x + w.width - 1 - i];
      }
      handOnBorder += left + right;
    }
  }
  if (handOnBorder >= options_.minCuffPixels || cv::countNonZero(sleeve) == 0) return std::nullopt;
  cv::Mat near;
  cv::dilate(sleeve, near, disc(options_.openDiameter_px));
  near &= hand;
  Eigen::Vector2d wrist = Eigen::Vector2d::Zero();
  int nCuff = 0;
  for (int v = 0; v < near.rows; ++v) {
    const uchar* p = near.ptr<uchar>(v);
    for (int u = 0; u < near.cols; ++u)
      if (p[u]) {
        wrist += Eigen::Vector2d(u, v);
        ++nCuff;
      }
  }
  if (nCuff < options_.minCuffPixels) return std::nullopt;
  // The palm a fixed length from the cuff towards the hand's thickest point
  // (cuffTowardsThickest; else along the arm's, sleeve + hand, axis).
  Anchor a;
  a.anchor_px = wrist / nCuff;
  a.dir = principalAxis(hand, sleeve, entry, options_.axisStride_px, options_.minElongation)->dir;
  if (options_.cuffTowardsThickest) {
    if (const auto thickest = thickestPoint(hand);
        thickest && (*thickest - a.anchor_px).norm() > options_.openDiameter_px)
      a.dir = (*thickest - a.anchor_px).normalized();
  }
  a.length_m = options_.palmFromWrist_m;
  if (options_.cuffAtSleeveEdge) {
    // The sleeve's edge along the cuff line: its pixels next to the hand.
    cv::Mat edge;
    cv::dilate(hand, edge, disc(options_.openDiameter_px));
    edge &= sleeve;
    if (const auto z = medianDepthInDisc(frame.depth_m, edge, a.anchor_px, 1e4, options_.minDepthSamples)) a.depth_m = *z;
  }
  geometry_.haveWrist = true;
  geometry_.wrist_px = a.anchor_px;
  return a;
}

MarkerFreeHandDetector::Anchor MarkerFreeHandDetector::fingertipAnchor(const cv::Mat& hand,
                                                                       const Eigen::Vector2d& entry,
                                                                       const Eigen::Vector2d& handMean,
                                                                       const Eigen::Vector2d& handDir,
                                                                       bool elongated) const {
  // The palm a fixed length back from the fingertips along the hand's axis
  // (or, for a short blob, the inward normal of the border the arm enters
  // from), on the hand's centre line.
  Eigen::Vector2d dir = handDir;
  if (!elongated) {
    const double du = std::min(entry.x(), hand.cols - 1 - entry.x()), dv = std::min(entry.y(), hand.rows - 1 - entry.y());
    dir = du < dv ? Eigen::Vector2d(entry.x() < hand.cols / 2 ? 1 : -1, 0)
                  : Eigen::Vector2d(0, entry.y() < hand.rows / 2 ? 1 : -1);
  }
  double tip = -1e9;
  const int stride = options_.axisStride_px;
  for (int v = 0; v < hand.rows; v += stride) {
    const uchar* p = hand.ptr<uchar>(v);
    for (int u = 0; u < hand.cols; u += stride)
      if (p[u]) tip = std::max(tip, (Eigen::Vector2d(u, v) - handMean).dot(dir));
  }
  Anchor a;
  a.anchor_px = handMean + tip * dir;
  a.dir = dir;
  a.length_m = -options_.palmFromFingertips_m;
  return a;
}

HandObservation MarkerFreeHandDetector::placePalm(const rawlog::RgbdFrame& frame, const Anchor& a,
                                                  const HandBlob& hand, const Eigen::Vector2d& handMean,
                                                  int armArea) {
  // The palm is placed in metres: from the anchor (far end, cuff line or
  // fingertips) a fixed length along the axis, walked on the hand's depth
  // profile (handTilt: a hand seen obliquely, as from the demonstrator's
  // head, is foreshortened in the image), then at the palm's own depth. (The
  // cuff's own depth is no help: the median there is the sleeve's,
  // centimetres above the wrist's skin.)
  const auto& k = frame.intrinsics;
  auto backProject = [&](const Eigen::Vector2d& p, double z_m) {
    return pixelToCamera(k, p.x(), p.y(), z_m);
  };
  auto project = [&](const Eigen::Vector3d& p) {
    return Eigen::Vector2d(k.fx_px * p.x() / p.z() + k.cx_px, k.fy_px * p.y() / p.z() + k.cy_px);
  };
  Eigen::Vector2d palm;
  const std::optional<Eigen::Vector2d> tilt = options_.walkOnDepth ? handTilt(frame, a, hand) : std::nullopt;
  geometry_.anchor_camera_m = geometry_.axis_camera = geometry_.normal_camera = Eigen::Vector3d::Zero();
  geometry_.palmFromAnchor_m = std::abs(a.length_m);
  if (tilt) {
    // Depth z(s) = tilt(0) + tilt(1) s along the axis (s in pixels from the anchor): walk until the
    // 3D distance from the anchor is the length.
    const double sign = a.length_m < 0.0 ? -1.0 : 1.0;
    double target = std::abs(a.length_m);
    const Eigen::Vector3d p0 = backProject(a.anchor_px, (*tilt)(0));
    // a.dir points towards the fingers from every anchor (the far end and the fingertips are walked
    // back from, the cuff forwards); the profile's s is the distance walked.
    geometry_.anchor_camera_m = p0;
    geometry_.axis_camera = (backProject(a.anchor_px + a.dir, (*tilt)(0) + (*tilt)(1) * sign) - p0).normalized();
    if (a.depth_m > 0.0 && a.depth_m < (*tilt)(0)) {
      // The sleeve's edge stands nearer than the hand there: it hides the wrist's start, by the gap
      // between them along the hand's axis (in 3D, on the depth profile).
      const Eigen::Vector3d axis_m =
          (backProject(a.anchor_px + sign * a.dir, (*tilt)(0) + (*tilt)(1)) - p0).normalized();
      target -= std::max(0.0, (p0 - backProject(a.anchor_px, a.depth_m)).dot(sign * axis_m));
    }
    // A bare forearm's far end read closed (not farEndOpenHand's open hand): its length by the view.
    if (geometry_.bareForearm && !geometry_.haveWrist && options_.palmFromFarEndAlongRay_m > 0.0 &&
        options_.palmFromFarEndAcrossRay_m > 0.0 && a.closedFarEnd)
      target = palmFromFarEndByView(p0, geometry_.axis_camera);
    geometry_.palmFromAnchor_m = target;
    palm = walkOnProfile(k, a, *tilt, target, hand.pxPerM);
  } else {
    const Eigen::Vector2d dir_m = Eigen::Vector2d(a.dir.x() / k.fx_px, a.dir.y() / k.fy_px).normalized();
    const Eigen::Vector3d p = backProject(a.anchor_px, hand.z_m + options_.palmDepth_m) +
                              a.length_m * Eigen::Vector3d(dir_m.x(), dir_m.y(), 0.0);
    palm = project(p);
  }
  HandObservation h;
  h.confidence = std::min(1.0, armArea / options_.confidenceFullArea_px) *
                 (geometry_.haveWrist ? 1.0 : options_.noWristConfidence);
  std::optional<double> z =
      medianDepthInDisc(frame.depth_m, hand.mask, palm, options_.palmRadius_m * hand.pxPerM, options_.minDepthSamples);
  // No depth on the palm (a hole, or the palm out of view while the fingers
  // enter or leave): the last palm depth if it is a few frames old (the caller
  // carries it along the ray), else the whole hand's (biased by the fingers'
  // and the wrist's tilt, but the best there is).
  if (z || lastDepth_m_ <= 0.0 || frameCount_ - lastDepthFrame_ > options_.maxCarryFrames) {
    if (!z) z = medianDepthInDisc(frame.depth_m, hand.mask, handMean, 1e4, options_.minDepthSamples);
    if (z) {
      // The palm centre lies palmDepth_m under the visible back of the hand:
      // along the back's normal where the palm disc's depths give one (a
      // hand seen obliquely), else along the ray.
      const std::optional<Eigen::Vector3d> n =
          options_.palmAlongNormal ? surfaceNormal(frame, hand.mask, palm, options_.palmRadius_m * hand.pxPerM)
                                   : std::nullopt;
      // A silhouette narrower than the palm (the hand seen on its edge): the centre lies deeper behind
      // the surface along the ray than half the palm's thickness (silhouetteDepth).
      const double extra_m =
          silhouetteDepth(hand.mask, palm, a.dir, frame.intrinsics.fx_px / *z, frame.index) - options_.palmDepth_m;
      if (n) {
        geometry_.normal_camera = *n;
        h.p_camera_palm_m = backProject(palm, *z) - options_.palmDepth_m * *n;
        palm = project(h.p_camera_palm_m);
      } else {
        h.p_camera_palm_m = backProject(palm, *z + options_.palmDepth_m);
      }
      if (extra_m > 0.0) h.p_camera_palm_m += extra_m * h.p_camera_palm_m.normalized();
      h.hasDepth = true;
      lastDepth_m_ = *z;
      lastDepthFrame_ = frameCount_;
    }
  }
  h.palm_px = palm;
  geometry_.palm_px = palm;
  return h;
}

Eigen::Vector2d MarkerFreeHandDetector::walkOnProfile(const core::CameraIntrinsics& k, const Anchor& a,
                                                      const Eigen::Vector2d& tilt, double length_m,
                                                      double pxPerM) const {
  const double sign = a.length_m < 0.0 ? -1.0 : 1.0;
  const Eigen::Vector3d p0 = pixelToCamera(k, a.anchor_px.x(), a.anchor_px.y(), tilt(0));
  const double maxS = options_.maxWalkFactor * length_m * pxPerM;
  double s = 0.0;
  for (; s < maxS; s += 0.5) {
    const double z = tilt(0) + tilt(1) * sign * s;
    const Eigen::Vector2d p = a.anchor_px + sign * s * a.dir;
    if (z <= 0.0 || (pixelToCamera(k, p.x(), p.y(), z) - p0).norm() >= length_m) break;
  }
  return a.anchor_px + sign * s * a.dir;
}

double MarkerFreeHandDetector::palmFromFarEndByView(const Eigen::Vector3d& farEnd_m,
                                                    const Eigen::Vector3d& axis) const {
  // Seen along the hand (from above and behind it), the far end is the curled fingers seen end-on, just
  // past the knuckles; seen across it (from the side, across the table), the fingers hang or stretch out
  // of the palm in full and the far end is their tips.
  const double along = std::abs(axis.dot(farEnd_m.normalized()));
  return options_.palmFromFarEndAcrossRay_m +
         (options_.palmFromFarEndAlongRay_m - options_.palmFromFarEndAcrossRay_m) * std::min(1.0, along);
}

double MarkerFreeHandDetector::silhouetteDepth(const cv::Mat& mask, const Eigen::Vector2d& palm_px,
                                              const Eigen::Vector2d& dir, double pxPerM, int frameIndex) const {
  // Cross-sections across the axis (1-px steps along it) within palmRadius_m of the palm: the run of mask
  // pixels through the palm's centre line, or, where the centre line lies beside the hand (a palm pixel off
  // a silhouette seen on its edge), the nearest run on the one side that has any. A centre line off the mask
  // with the hand on both sides of it (a tag or a badge cut out of the skin) is no cross-section: the skin
  // beside such a hole is no whole palm. None when a run reaches the edge of the view (the hand entering or
  // leaving: cut, not narrow).
  if (options_.palmHalfWidth_m <= 0.0) return options_.palmDepth_m;
  const double reach_px = options_.palmRadius_m * pxPerM;
  const int span_px = static_cast<int>(std::ceil(options_.palmHalfWidth_m * pxPerM * 2.0));
  const cv::Rect view = view_.area() > 0 ? view_ : cv::Rect(0, 0, mask.cols, mask.rows);
  const cv::Rect inner = inset(view, options_.borderMargin_px);
  const Eigen::Vector2d across(-dir.y(), dir.x());
  std::vector<uchar> line(static_cast<std::size_t>(2 * span_px + 1)), cut(line.size());
  std::vector<double> width_px;
  for (double s = -reach_px; s <= reach_px; s += 1.0) {
    const Eigen::Vector2d c = palm_px + s * dir;
    for (int t = -span_px; t <= span_px; ++t) {
      const Eigen::Vector2d q = c + t * across;
      const int u = static_cast<int>(std::lround(q.x())), v = static_cast<int>(std::lround(q.y()));
      const bool in = u >= 0 && v >= 0 && u < mask.cols && v < mask.rows && mask.at<uchar>(v, u);
      line[static_cast<std::size_t>(t + span_px)] = in;
      cut[static_cast<std::size_t>(t + span_px)] = in && !inner.contains(cv::Point(u, v));
    }
    auto at = [&](int t) { return line[static_cast<std::size_t>(t + span_px)] != 0; };
    int t0 = 0;
    if (!at(0)) {
      int left = 1, right = 1;
      while (left <= span_px && !at(-left)) ++left;
      while (right <= span_px && !at(right)) ++right;
      const bool hasLeft = left <= span_px, hasRight = right <= span_px;
      if (hasLeft == hasRight) continue;  // a hole in the hand, or no hand on this cross-section
      t0 = hasLeft ? -left : right;
    }
    int lo = t0, hi = t0;
    while (lo > -span_px && at(lo - 1)) --lo;
    while (hi < span_px && at(hi + 1)) ++hi;
    for (int t = lo; t <= hi; ++t)
      if (cut[static_cast<std::size_t>(t + span_px)]) return options_.palmDepth_m;
    width_px.push_back(hi - lo + 1.0);
  }
  // Too few cross-sections (a tag or a badge over the palm): no silhouette of the palm.
  if (width_px.empty() || static_cast<double>(width_px.size()) < options_.minPalmCrossSections * (2.0 * reach_px + 1.0))
    return options_.palmDepth_m;
  std::nth_element(width_px.begin(), width_px.begin() + width_px.size() / 2, width_px.end());
  const double halfWidth_m = 0.5 * width_px[width_px.size() / 2] / pxPerM;
  // An ellipse of half-axes A (width) and B (thickness) seen at angle phi from B: silhouette half-width
  // h = sqrt(A^2 cos^2 phi + B^2 sin^2 phi), surface to centre along the central ray A B / h.
  const double depth_m = std::clamp(options_.palmHalfWidth_m * options_.palmDepth_m / std::max(halfWidth_m, 1e-6),
                                    options_.palmDepth_m, std::max(options_.palmDepth_m, options_.palmHalfWidth_m));
  if (core::Log::enabled("hand", core::Log::Level::Debug))
    core::Log::writef("hand", core::Log::Level::Debug,
                      "frame %d: palm silhouette half-width %.1f mm (%zu cross-sections): centre %.1f mm behind\n",
                      frameIndex, 1e3 * halfWidth_m, width_px.size(), 1e3 * depth_m);
  return depth_m;
}

std::optional<Eigen::Vector3d> MarkerFreeHandDetector::surfaceNormal(const rawlog::RgbdFrame& frame,
                                                                     const cv::Mat& mask,
                                                                     const Eigen::Vector2d& centre_px,
                                                                     double radius_px) const {
  // The smallest principal direction of the disc's 3D points, towards the camera.
  const auto& k = frame.intrinsics;
  const int r = static_cast<int>(std::ceil(radius_px));
  const int cu = static_cast<int>(std::lround(centre_px.x())), cv_ = static_cast<int>(std::lround(centre_px.y()));
  const int stride = options_.axisStride_px;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  Eigen::Matrix3d second = Eigen::Matrix3d::Zero();
  int n = 0;
  for (int v = std::max(0, cv_ - r); v <= std::min(mask.rows - 1, cv_ + r); v += stride) {
    const uchar* m = mask.ptr<uchar>(v);
    const float* z = frame.depth_m.ptr<float>(v);
    for (int u = std::max(0, cu - r); u <= std::min(mask.cols - 1, cu + r); u += stride) {
      if (!m[u] || z[u] <= 0.f || (Eigen::Vector2d(u, v) - centre_px).squaredNorm() > radius_px * radius_px) continue;
      const Eigen::Vector3d p = pixelToCamera(k, u, v, z[u]);
      mean += p;
      second += p * p.transpose();
      ++n;
    }
  }
  if (n < options_.minTiltSamples) return std::nullopt;
  mean /= n;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(second / n - mean * mean.transpose());
  // A disc, not a line or a blob: the two in-plane spreads clearly above the normal's.
  if (eig.eigenvalues()(0) > options_.maxNormalFlatness * eig.eigenvalues()(1)) return std::nullopt;
  Eigen::Vector3d normal = eig.eigenvectors().col(0).normalized();
  if (normal.dot(mean) > 0.0) normal = -normal;
  return normal;
}

std::optional<Eigen::Vector2d> MarkerFreeHandDetector::handTilt(const rawlog::RgbdFrame& frame, const Anchor& a,
                                                                const HandBlob& hand) const {
  // The hand's valid depths between the anchor and a little beyond the
  // palm's length along the axis, as a line z = c0 + c1 s in the pixel
  // distance s from the anchor (least squares, then once more without the
  // samples farther than tiltInlier_m from the first line: the fingers
  // curled round a part, a depth edge).
  const double sign = a.length_m < 0.0 ? -1.0 : 1.0;
  const double reach_px = (std::abs(a.length_m) + options_.palmRadius_m) * hand.pxPerM;
  std::vector<Eigen::Vector2d> samples;  // (s, z)
  const int stride = options_.axisStride_px;
  for (int v = 0; v < hand.mask.rows; v += stride) {
    const uchar* m = hand.mask.ptr<uchar>(v);
    const float* z = frame.depth_m.ptr<float>(v);
    for (int u = 0; u < hand.mask.cols; u += stride) {
      if (!m[u] || z[u] <= 0.f) continue;
      const double s = sign * (Eigen::Vector2d(u, v) - a.anchor_px).dot(a.dir);
      if (s >= 0.0 && s <= reach_px) samples.emplace_back(s, z[u]);
    }
  }
  auto fit = [&](const std::optional<Eigen::Vector2d>& first) -> std::optional<Eigen::Vector2d> {
    Eigen::Matrix2d ata = Eigen::Matrix2d::Zero();
    Eigen::Vector2d atb = Eigen::Vector2d::Zero();
    int n = 0;
    double sMin = 1e9, sMax = -1e9;
    for (const auto& q : samples) {
      if (first && std::abs((*first)(0) + (*first)(1) * q.x() - q.y()) > options_.tiltInlier_m) continue;
      const Eigen::Vector2d r(1.0, q.x());
      ata += r * r.transpose();
      atb += r * q.y();
      sMin = std::min(sMin, q.x());
      sMax = std::max(sMax, q.x());
      ++n;
    }
    // Enough samples spread over at least half the reach.
    if (n < options_.minTiltSamples || sMax - sMin < 0.5 * reach_px) return std::nullopt;
    return Eigen::Vector2d(ata.ldlt().solve(atb));
  };
  const auto first = fit(std::nullopt);
  if (!first) return std::nullopt;
  const auto line = fit(first);
  if (!line || (*line)(0) <= 0.0) return std::nullopt;
  return line;
}

}  // namespace srp::perception
