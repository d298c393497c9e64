#include "srp/perception/ObjectDiscovery.h"
#include "srp/core/Log.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <map>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <set>

#include "srp/core/Error.h"
#include "srp/perception/CameraModel.h"
#include "srp/perception/DepthCloud.h"
#include "srp/perception/PlaneFit.h"
#include "srp/rawlog/RawlogReader.h"

namespace srp::perception {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
/// A segment whose 99th percentile height comes this close to maxHeight_m was cut by the band: part of something taller.
constexpr double kBandCut_m = 0.02;

/// One segment in one frame (table frame, metres).
struct Sighting {
  int frame = 0;                   ///< index in the order added
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();  ///< mean of the feet
  std::vector<cv::Point2f> hull;   ///< the feet's convex hull
  double area_m2 = 0.0;
  double top_m = 0.0, bottom_m = 0.0;  ///< 95th / 5th percentile height
  ColourShares colours{};
  Eigen::Vector3d meanBgr = Eigen::Vector3d::Zero();  ///< [0, 1]
  double handDistance_m = kInf;    ///< nearest point to the palm
  bool nearHand = false;
  int pixels = 0;
  int rest = -1;
};

/// A place where something stands: the sightings alike in place, height and colour.
struct Rest {
  std::vector<int> sightings;
  int anchor = -1;  ///< the sighting with the most pixels: the rest's place, hull, top and colours
  /// The fused cloud (table frame): the points of the largest sightings, those without the hand near first.
  struct Kept {
    int sighting;
    bool nearHand;
    std::vector<Eigen::Vector3f> points;
  };
  std::vector<Kept> kept;
  int first = std::numeric_limits<int>::max(), last = -1;
};

double polygonDistance(const std::vector<cv::Point2f>& polygon, const Eigen::Vector2d& p) {
  if (polygon.size() < 3) return -kInf;
  return cv::pointPolygonTest(polygon, cv::Point2f(static_cast<float>(p.x()), static_cast<float>(p.y())), true);
}

/// Intersection over union of two convex polygons [0, 1].
double overlap(const std::vector<cv::Point2f>& a, const std::vector<cv::Point2f>& b) {
  if (a.size() < 3 || b.size() < 3) return 0.0;
  std::vector<cv::Point2f> both;
  const double inter = cv::intersectConvexConvex(a, b, both, true);
  const double uni = cv::contourArea(a) + cv::contourArea(b) - inter;
  return uni > 0.0 ? std::max(0.0, inter) / uni : 0.0;
}

/// An sRGB value [0, 1] made linear.
double linearOf(double srgb) { return srgb <= 0.04045 ? srgb / 12.92 : std::pow((srgb + 0.055) / 1.055, 2.4); }

double percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  const std::size_t k = std::min(v.size() - 1, static_cast<std::size_t>(q * static_cast<double>(v.size() - 1) + 0.5));
  std::nth_element(v.begin(), v.begin() + static_cast<long>(k), v.end());
  return v[k];
}

std::string describePlace(const Eigen::Vector2d& p) {
  char buf[64];
  std::snprintf(buf, sizeof(buf), "(%.2f, %.2f) m", p.x(), p.y());
  return buf;
}

/// Oriented footprint of table-frame points: the frame at the centre of the
/// minimum-area rectangle of their feet, x along its longer side; the feet's
/// convex hull in that frame; the size (long, short, 95th percentile height).
struct Footprint {
  core::Pose3 X_table_object = core::Pose3::Identity();
  std::vector<Eigen::Vector2d> hull_object;  ///< counter-clockwise
  Eigen::Vector3d size_m = Eigen::Vector3d::Zero();
};

std::optional<Footprint> footprintOf(const std::vector<Eigen::Vector3f>& points) {
  if (points.size() < 10) return std::nullopt;
  std::vector<cv::Point2f> feet;
  std::vector<double> heights;
  feet.reserve(points.size());
  for (const auto& p : points) {
    feet.emplace_back(p.x(), p.y());
    heights.push_back(p.z());
  }
  const cv::RotatedRect r = cv::minAreaRect(feet);
  double yaw = r.angle * M_PI / 180.0;
  double lx = r.size.width, ly = r.size.height;
  if (ly > lx) {
    std::swap(lx, ly);
    yaw += M_PI / 2;
  }
  yaw = std::remainder(yaw, M_PI);  // a rectangle is the same turned by pi
  Footprint f;
  f.X_table_object = core::Pose3::Identity();
  f.X_table_object.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  f.X_table_object.translation() = Eigen::Vector3d(r.center.x, r.center.y, 0.0);
  std::vector<cv::Point2f> hull;
  cv::convexHull(feet, hull, /*clockwise=*/false);
  const core::Pose3 X_object_table = f.X_table_object.inverse();
  for (const auto& h : hull) {
    const Eigen::Vector3d q = X_object_table * Eigen::Vector3d(h.x, h.y, 0.0);
    f.hull_object.emplace_back(q.x(), q.y());
  }
  // Counter-clockwise in the object frame (the turn keeps the orientation; make sure).
  double area2 = 0.0;
  for (std::size_t i = 0; i < f.hull_object.size(); ++i) {
    const auto& a = f.hull_object[i];
    const auto& b = f.hull_object[(i + 1) % f.hull_object.size()];
    area2 += a.x() * b.y() - b.x() * a.y();
  }
  if (area2 < 0) std::reverse(f.hull_object.begin(), f.hull_object.end());
  f.size_m = Eigen::Vector3d(lx, ly, percentile(heights, 0.95));
  return f;
}

/// A frame at a reduced resolution: each pixel's point in the table frame (q),
/// whether it has depth (valid), its depth (z).
struct TableView {
  cv::Mat q, valid, z;
};

TableView tableViewOf(const rawlog::RgbdFrame& frame, const core::Pose3& X_table_camera, int s) {
  const int W = frame.depth_m.cols / s, H = frame.depth_m.rows / s;
  const auto& k = frame.intrinsics;
  TableView view{cv::Mat(H, W, CV_32FC3, cv::Scalar::all(0)), cv::Mat(H, W, CV_8UC1, cv::Scalar(0)),
                 cv::Mat(H, W, CV_32FC1, cv::Scalar(0))};
  const Eigen::Matrix3f R = X_table_camera.linear().cast<float>();
  const Eigen::Vector3f t = X_table_camera.translation().cast<float>();
  for (int v = 0; v < H; ++v)
    for (int u = 0; u < W; ++u) {
      const float d = frame.depth_m.at<float>(v * s, u * s);
      if (!(d > 0.0f) || !std::isfinite(d)) continue;
      const Eigen::Vector3f p(static_cast<float>((u * s - k.cx_px) * d / k.fx_px),
                              static_cast<float>((v * s - k.cy_px) * d / k.fy_px), d);
      const Eigen::Vector3f pt = R * p + t;
      view.q.at<cv::Vec3f>(v, u) = cv::Vec3f(pt.x(), pt.y(), pt.z());
      view.z.at<float>(v, u) = d;
      view.valid.at<uchar>(v, u) = 255;
    }
  return view;
}

/// The pixels of `view` that may belong to something standing on the table:
/// between minHeight_m and maxHeight_m above it, not in `excluded` (the hand),
/// not within handRadius_m of `palm`, not beside a depth step.
cv::Mat candidatesOf(const TableView& view, const ObjectDiscovery::Options& o, const cv::Mat& excluded,
                     const std::optional<Eigen::Vector3d>& palm) {
  const cv::Mat &q = view.q, &valid = view.valid, &z = view.z;
  const int W = q.cols, H = q.rows;
  cv::Mat candidate(H, W, CV_8UC1, cv::Scalar(0));
  for (int v = 0; v < H; ++v)
    for (int u = 0; u < W; ++u) {
      if (!valid.at<uchar>(v, u) || (!excluded.empty() && excluded.at<uchar>(v, u))) continue;
      const cv::Vec3f& p = q.at<cv::Vec3f>(v, u);
      if (p[2] < o.minHeight_m || p[2] > o.maxHeight_m) continue;
      if (palm && (Eigen::Vector3d(p[0], p[1], p[2]) - *palm).norm() < o.handRadius_m) continue;
      const float d = z.at<float>(v, u);
      const float edge = static_cast<float>(o.depthEdge_m) * std::max(1.0f, d);
      if ((u + 1 < W && valid.at<uchar>(v, u + 1) && std::abs(z.at<float>(v, u + 1) - d) > edge) ||
          (v + 1 < H && valid.at<uchar>(v + 1, u) && std::abs(z.at<float>(v + 1, u) - d) > edge))
        continue;
      candidate.at<uchar>(v, u) = 255;
    }
  return candidate;
}

/// The sighting of one segment (`px`, pixels of the reduced frame `q`, points in the table frame) in
/// frame `index`: its feet's hull and centre, heights, colour, distance to the palm; `points`
/// receives its points.
Sighting sightingOf(int index, const cv::Mat& q, const std::vector<cv::Point>& px, const cv::Mat& colour,
                    const std::optional<Eigen::Vector3d>& palm, const ObjectDiscovery::Options& o,
                    std::vector<Eigen::Vector3f>& points) {
  std::vector<cv::Point2f> feet;
  std::vector<double> heights;
  feet.reserve(px.size());
  Sighting sg;
  sg.frame = index;
  sg.pixels = static_cast<int>(px.size());
  for (const auto& p : px) {
    const cv::Vec3f& a = q.at<cv::Vec3f>(p);
    feet.emplace_back(a[0], a[1]);
    heights.push_back(a[2]);
    points.emplace_back(a[0], a[1], a[2]);
    sg.centre += Eigen::Vector2d(a[0], a[1]);
    if (palm) sg.handDistance_m = std::min(sg.handDistance_m, (Eigen::Vector3d(a[0], a[1], a[2]) - *palm).norm());
    if (!colour.empty()) {
      const cv::Vec3b c = colour.at<cv::Vec3b>(p);
      sg.meanBgr += Eigen::Vector3d(c[0], c[1], c[2]) / 255.0;
    }
  }
  sg.centre /= static_cast<double>(px.size());
  sg.meanBgr /= static_cast<double>(px.size());
  cv::convexHull(feet, sg.hull);
  sg.area_m2 = cv::contourArea(sg.hull);
  sg.top_m = percentile(heights, 0.95);
  sg.bottom_m = percentile(heights, 0.05);
  if (!colour.empty()) sg.colours = colourShares(px, colour);
  sg.nearHand = sg.handDistance_m < o.handRadius_m + 0.05;
  return sg;
}

/// SRP_DISCOVERY_TRACE's picture of a frame before its segments are drawn: the colour at the reduced
/// resolution, table points tinted green, the hand mask magenta.
cv::Mat traceBackground(const cv::Mat& colour, const TableView& view, const cv::Mat& hand,
                        const std::vector<cv::Point2f>& table, const ObjectDiscovery::Options& o) {
  const cv::Mat &q = view.q, &valid = view.valid;
  const int W = q.cols, H = q.rows;
  cv::Mat trace = colour.clone();
  for (int v = 0; v < H; ++v)
    for (int u = 0; u < W; ++u) {
      const cv::Vec3f& p = q.at<cv::Vec3f>(v, u);
      if (valid.at<uchar>(v, u) && cv::pointPolygonTest(table, cv::Point2f(p[0], p[1]), false) >= 0 &&
          std::abs(p[2]) < o.tableInlierTol_m)
        trace.at<cv::Vec3b>(v, u) = trace.at<cv::Vec3b>(v, u) / 2 + cv::Vec3b(0, 60, 0);
      if (hand.at<uchar>(v, u)) trace.at<cv::Vec3b>(v, u) = cv::Vec3b(255, 0, 255);
    }
  return trace;
}

}  // namespace

struct ObjectDiscovery::Impl {
  Options o;
  std::vector<UnknownObject> objects;
  std::vector<Sighting> sightings;
  std::vector<Rest> rests;
  std::vector<core::Pose3> X_camera_table;             ///< per frame
  std::vector<std::optional<Eigen::Vector3d>> palm;    ///< per frame, table frame
  std::vector<int> frameNumber;
  std::vector<double> time_s;
  std::vector<cv::Point2f> table;  ///< the table top (table frame), from the first frame
  const bool debug = core::Log::enabled("discovery", core::Log::Level::Debug);

  void findTable(const cv::Mat& q, const cv::Mat& valid);
  /// A segment's pixels (`q`: table-frame points) stand on the table top and below the band.
  bool onTableTop(const cv::Mat& q, const std::vector<cv::Point>& px) const;
  void assign(int s, std::vector<Eigen::Vector3f>&& points);
  std::string describe(const Rest& r) const;
  Eigen::Vector3d restCentre3(const Rest& r) const {
    const Sighting& a = sightings[static_cast<std::size_t>(r.anchor)];
    return Eigen::Vector3d(a.centre.x(), a.centre.y(), 0.5 * a.top_m);
  }
  double handDistanceNear(const Rest& r, int frame) const;
  std::vector<Eigen::Vector3f> fused(const Rest& r) const;
  struct Finish;
};

std::optional<ObjectDiscovery::Measured> ObjectDiscovery::measureAt(const rawlog::RgbdFrame& frame,
                                                                    const core::Pose3& X_camera_table,
                                                                    const Eigen::Vector2d& at_px, const Options& o) {
  if (o.stride < 1) throw core::InvalidInputError("object discovery options: stride must be >= 1");
  const TableView view = tableViewOf(frame, X_camera_table.inverse(), o.stride);
  const cv::Mat candidate = candidatesOf(view, o, cv::Mat(), std::nullopt);
  cv::Mat labels;
  cv::connectedComponents(candidate, labels, 4, CV_32S);
  // The segment at the pixel, else the nearest within 3 sample steps.
  constexpr int kSearch = 3;
  const int u0 = static_cast<int>(std::lround(at_px.x() / o.stride)), v0 = static_cast<int>(std::lround(at_px.y() / o.stride));
  int label = 0, best = std::numeric_limits<int>::max();
  for (int v = std::max(0, v0 - kSearch); v <= std::min(labels.rows - 1, v0 + kSearch); ++v)
    for (int u = std::max(0, u0 - kSearch); u <= std::min(labels.cols - 1, u0 + kSearch); ++u) {
      const int d2 = (u - u0) * (u - u0) + (v - v0) * (v - v0);
      if (labels.at<int>(v, u) > 0 && d2 < best) best = d2, label = labels.at<int>(v, u);
    }
  if (label == 0) return std::nullopt;
  std::vector<cv::Point> px;
  std::vector<Eigen::Vector3f> points;
  for (int v = 0; v < labels.rows; ++v)
    for (int u = 0; u < labels.cols; ++u)
      if (labels.at<int>(v, u) == label) {
        px.emplace_back(u, v);
        const cv::Vec3f& a = view.q.at<cv::Vec3f>(v, u);
        points.emplace_back(a[0], a[1], a[2]);
      }
  const auto fp = footprintOf(points);
  if (!fp) return std::nullopt;
  Measured out;
  out.X_table_object = fp->X_table_object;
  out.size_m = fp->size_m;
  out.footprint_object = fp->hull_object;
  out.points = static_cast<int>(points.size());
  if (!frame.colour_bgr8.empty()) {
    cv::Mat colour;
    cv::resize(frame.colour_bgr8, colour, labels.size(), 0, 0, cv::INTER_NEAREST);
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (const auto& p : px) {
      const cv::Vec3b c = colour.at<cv::Vec3b>(p);
      mean += Eigen::Vector3d(c[2], c[1], c[0]) / 255.0;
    }
    mean /= static_cast<double>(px.size());
    for (int c = 0; c < 3; ++c) out.rgb[c] = linearOf(mean[c]);
    out.colourWord = dominantColourWord(colourShares(px, colour));
  }
  return out;
}

ObjectDiscovery::Measured ObjectDiscovery::measureInRecording(const std::string& rawlogPath, int frame,
                                                              const Eigen::Vector2d& at_px, const Options& options) {
  char where[160];
  std::snprintf(where, sizeof(where), "pixel (%.0f, %.0f) of frame %d of ", at_px.x(), at_px.y(), frame);
  const std::string here = where + rawlogPath;
  if (frame < 0) throw core::InvalidInputError("frame " + std::to_string(frame) + ": frames are counted from 0");
  rawlog::RawlogReader reader(rawlogPath, 0);
  std::optional<rawlog::RgbdFrame> f;
  for (int i = 0; i <= frame; ++i)
    if (!(f = reader.next()))
      throw core::InvalidInputError(rawlogPath + " has " + std::to_string(i) + " RGB-D frames: give a frame below " +
                                    std::to_string(i));
  const auto& k = f->intrinsics;
  if (at_px.x() < 0 || at_px.y() < 0 || at_px.x() > k.width_px - 1 || at_px.y() > k.height_px - 1)
    throw core::InvalidInputError(here + ": outside the " + std::to_string(k.width_px) + " x " +
                                  std::to_string(k.height_px) + " image");
  const auto plane = fitSupportPlane(depthToCloud(f->depth_m, CameraModel(k)));
  if (!plane) throw core::InvalidInputError(here + ": no table plane is seen in that frame; give a frame that shows the table");
  const auto m = measureAt(*f, plane->X_camera_plane(), at_px, options);
  if (!m)
    throw core::InvalidInputError(here + ": nothing stands on the table there (the table top, the background or no "
                                  "depth); give a pixel on the object (srp replay --export shows the frames)");
  return *m;
}

ObjectDiscovery::ObjectDiscovery(std::vector<UnknownObject> objects) : ObjectDiscovery(std::move(objects), Options{}) {}

ObjectDiscovery::ObjectDiscovery(std::vector<UnknownObject> objects, const Options& options)
    : impl_(std::make_unique<Impl>()) {
  if (options.stride < 1 || options.minPixels < 1 || options.keptSightings < 1)
    throw core::InvalidInputError("object discovery options: stride, minPixels and keptSightings must be >= 1");
  impl_->o = options;
  impl_->objects = std::move(objects);
}

ObjectDiscovery::~ObjectDiscovery() = default;

const std::vector<UnknownObject>& ObjectDiscovery::objects() const { return impl_->objects; }

void ObjectDiscovery::Impl::findTable(const cv::Mat& q, const cv::Mat& valid) {
  cv::Mat inliers(q.size(), CV_8UC1, cv::Scalar(0));
  for (int v = 0; v < q.rows; ++v)
    for (int u = 0; u < q.cols; ++u)
      if (valid.at<uchar>(v, u) && std::abs(q.at<cv::Vec3f>(v, u)[2]) < o.tableInlierTol_m) inliers.at<uchar>(v, u) = 255;
  cv::Mat labels, stats, centroids;
  const int n = cv::connectedComponentsWithStats(inliers, labels, stats, centroids, 4, CV_32S);
  int best = 0;
  for (int k = 1; k < n; ++k)
    if (best == 0 || stats.at<int>(k, cv::CC_STAT_AREA) > stats.at<int>(best, cv::CC_STAT_AREA)) best = k;
  if (best == 0) return;
  std::vector<cv::Point2f> feet;
  for (int v = 0; v < q.rows; ++v)
    for (int u = 0; u < q.cols; ++u)
      if (labels.at<int>(v, u) == best) feet.emplace_back(q.at<cv::Vec3f>(v, u)[0], q.at<cv::Vec3f>(v, u)[1]);
  cv::convexHull(feet, table);
}

bool ObjectDiscovery::Impl::onTableTop(const cv::Mat& q, const std::vector<cv::Point>& px) const {
  int inside = 0;
  std::vector<double> heights;
  heights.reserve(px.size());
  for (const auto& p : px) {
    const cv::Vec3f& a = q.at<cv::Vec3f>(p);
    heights.push_back(a[2]);
    if (cv::pointPolygonTest(table, cv::Point2f(a[0], a[1]), true) >= -o.tableMargin_m) ++inside;
  }
  return inside >= o.minInsideShare * static_cast<double>(px.size()) &&
         percentile(heights, 0.99) <= o.maxHeight_m - kBandCut_m;
}

void ObjectDiscovery::add(const rawlog::RgbdFrame& frame, const core::Pose3& X_camera_table,
                          const std::optional<Eigen::Vector3d>& p_camera_palm, const cv::Mat& handMask) {
  Impl& m = *impl_;
  const Options& o = m.o;
  const int index = static_cast<int>(m.frameNumber.size());
  m.frameNumber.push_back(frame.index);
  m.time_s.push_back(frame.t_s);
  m.X_camera_table.push_back(X_camera_table);
  const core::Pose3 X_table_camera = X_camera_table.inverse();
  m.palm.push_back(p_camera_palm ? std::optional<Eigen::Vector3d>(X_table_camera * *p_camera_palm) : std::nullopt);

  // The frame at the reduced resolution: points in the table frame.
  const TableView view = tableViewOf(frame, X_table_camera, o.stride);
  const cv::Mat &q = view.q, &valid = view.valid;
  const int W = q.cols, H = q.rows;
  if (m.table.empty()) m.findTable(q, valid);
  if (m.table.size() < 3) return;  // no table top seen yet

  // Candidates: above the table, not the hand, not across a depth step.
  cv::Mat hand(H, W, CV_8UC1, cv::Scalar(0));
  if (!handMask.empty()) {
    cv::resize(handMask, hand, cv::Size(W, H), 0, 0, cv::INTER_NEAREST);
    if (o.handMaskGrow_px > 0)
      cv::dilate(hand, hand, cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(2 * o.handMaskGrow_px + 1, 2 * o.handMaskGrow_px + 1)));
  }
  const std::optional<Eigen::Vector3d>& palm = m.palm.back();
  cv::Mat candidate = candidatesOf(view, o, hand, handMask.empty() ? palm : std::nullopt);
  cv::Mat labels, stats, centroids;
  int n = 0;
  std::vector<std::vector<cv::Point>> pixels;
  const auto label = [&]() {
    n = cv::connectedComponentsWithStats(candidate, labels, stats, centroids, 4, CV_32S);
    pixels.assign(static_cast<std::size_t>(n), {});
    for (int v = 0; v < H; ++v)
      for (int u = 0; u < W; ++u) {
        const int l = labels.at<int>(v, u);
        if (l > 0 && stats.at<int>(l, cv::CC_STAT_AREA) >= o.minPixels) pixels[static_cast<std::size_t>(l)].emplace_back(u, v);
      }
  };
  label();
  // A segment that reaches off the table top or up to a person, with the palm
  // on it, is a part held by an arm the hand mask did not cover: the arm (its
  // points higher than the palm) is cut off and the rest segmented again.
  if (palm) {
    bool cut = false;
    for (int l = 1; l < n; ++l) {
      const auto& px = pixels[static_cast<std::size_t>(l)];
      if (px.empty() || m.onTableTop(q, px)) continue;
      double nearest = kInf;
      for (const auto& p : px) {
        const cv::Vec3f& a = q.at<cv::Vec3f>(p);
        nearest = std::min(nearest, (Eigen::Vector3d(a[0], a[1], a[2]) - *palm).norm());
      }
      if (nearest > o.handRadius_m) continue;
      for (const auto& p : px)
        if (q.at<cv::Vec3f>(p)[2] > palm->z() + o.armAbovePalm_m) candidate.at<uchar>(p) = 0, cut = true;
    }
    if (cut) label();
  }
  cv::Mat colour;
  if (!frame.colour_bgr8.empty()) cv::resize(frame.colour_bgr8, colour, cv::Size(W, H), 0, 0, cv::INTER_NEAREST);
  cv::Mat trace;  // SRP_DISCOVERY_TRACE=<folder>: each frame's segments drawn (for tuning on a new recording)
  const char* traceDir = std::getenv("SRP_DISCOVERY_TRACE");
  if (traceDir && !colour.empty()) trace = traceBackground(colour, view, hand, m.table, o);
  for (int l = 1; l < n; ++l) {
    const auto& px = pixels[static_cast<std::size_t>(l)];
    if (px.empty() || !m.onTableTop(q, px)) continue;  // off the table top, or part of something taller
    std::vector<Eigen::Vector3f> points;
    const Sighting sg = sightingOf(index, q, px, colour, palm, o, points);
    m.sightings.push_back(sg);
    m.assign(static_cast<int>(m.sightings.size()) - 1, std::move(points));
    if (!trace.empty()) {
      const int r = m.sightings.back().rest;
      const cv::Vec3b c((r * 67) % 256, (r * 141 + 80) % 256, (r * 199 + 40) % 256);
      for (const auto& p : px) trace.at<cv::Vec3b>(p) = c;
      cv::putText(trace, std::to_string(r), px.front(), cv::FONT_HERSHEY_PLAIN, 0.8, cv::Scalar(0, 0, 255));
    }
  }
  if (!trace.empty()) {
    char name[64];
    std::snprintf(name, sizeof(name), "/discovery_%04d.png", frame.index);
    cv::imwrite(traceDir + std::string(name), trace);
  }
}

void ObjectDiscovery::Impl::assign(int si, std::vector<Eigen::Vector3f>&& points) {
  Sighting& s = sightings[static_cast<std::size_t>(si)];
  // Standing on the table, or in something standing there (its footprint
  // holds the centre, its top is not below the bottom); else in the air (an
  // arm, a part being carried): no rest.
  const bool onTable = s.bottom_m <= o.maxStandingBottom_m;
  if (!onTable && std::none_of(rests.begin(), rests.end(), [&](const Rest& r) {
        const Sighting& a = sightings[static_cast<std::size_t>(r.anchor)];
        return polygonDistance(a.hull, s.centre) >= 0 && a.top_m >= s.bottom_m - o.maxStandingBottom_m &&
               a.area_m2 >= o.minHolderAreaRatio * s.area_m2;
      }))
    return;
  int best = -1;
  double bestDistance = kInf;
  for (std::size_t r = 0; r < rests.size(); ++r) {
    // The same place: the same footprint (whatever is on, in or in front of
    // it), or near, as high and alike in colour.
    const Sighting& a = sightings[static_cast<std::size_t>(rests[r].anchor)];
    const double d = (a.centre - s.centre).norm();
    const bool samePlace = overlap(a.hull, s.hull) >= o.minRestOverlap;
    if (!samePlace && (d > o.restRadius_m || std::abs(a.top_m - s.top_m) > o.restTopTol_m ||
                       colourSimilarity(a.colours, s.colours) < o.minColourSimilarity))
      continue;
    if (d < bestDistance) {
      bestDistance = d;
      best = static_cast<int>(r);
    }
  }
  if (best < 0) {
    rests.emplace_back();
    best = static_cast<int>(rests.size()) - 1;
  }
  Rest& r = rests[static_cast<std::size_t>(best)];
  s.rest = best;
  r.sightings.push_back(si);
  r.first = std::min(r.first, s.frame);
  r.last = std::max(r.last, s.frame);
  // The anchor (the rest's place, outline, top and colours): the first
  // sighting, or a larger one of the same standing and height (the same thing seen more fully).
  if (r.anchor < 0) {
    r.anchor = si;
  } else {
    const Sighting& a = sightings[static_cast<std::size_t>(r.anchor)];
    if (s.pixels > a.pixels && onTable == (a.bottom_m <= o.maxStandingBottom_m) &&
        std::abs(s.top_m - a.top_m) <= o.restTopTol_m)
      r.anchor = si;
  }
  // The fused cloud: the largest sightings, those as high as the anchor and then those
  // without the hand near preferred.
  if (static_cast<int>(points.size()) > o.pointsPerSighting) {
    std::vector<Eigen::Vector3f> sub;
    const double step = static_cast<double>(points.size()) / o.pointsPerSighting;
    for (int i = 0; i < o.pointsPerSighting; ++i) sub.push_back(points[static_cast<std::size_t>(i * step)]);
    points.swap(sub);
  }
  const double anchorTop_m = sightings[static_cast<std::size_t>(r.anchor)].top_m;
  const auto asHigh = [&](const Rest::Kept& k) {
    return std::abs(sightings[static_cast<std::size_t>(k.sighting)].top_m - anchorTop_m) <= o.restTopTol_m;
  };
  const auto worse = [&](const Rest::Kept& a, const Rest::Kept& b) {  // a is worse than b
    if (asHigh(a) != asHigh(b)) return !asHigh(a);
    if (a.nearHand != b.nearHand) return a.nearHand;
    return sightings[static_cast<std::size_t>(a.sighting)].pixels < sightings[static_cast<std::size_t>(b.sighting)].pixels;
  };
  Rest::Kept mine{si, s.nearHand, std::move(points)};
  if (static_cast<int>(r.kept.size()) < o.keptSightings) {
    r.kept.push_back(std::move(mine));
  } else {
    auto worst = std::min_element(r.kept.begin(), r.kept.end(), worse);
    if (worse(*worst, mine)) *worst = std::move(mine);
  }
}

std::vector<Eigen::Vector3f> ObjectDiscovery::Impl::fused(const Rest& r) const {
  // Only sightings as high as the anchor (restTopTol_m, the anchor's own rule): a
  // sighting that joins the place by its footprint but rises far above it is the part
  // with the arm that reaches for it (a larger segment, so kept first), not the part.
  const double anchorTop_m = sightings[static_cast<std::size_t>(r.anchor)].top_m;
  const auto asHigh = [&](const Rest::Kept& k) {
    return std::abs(sightings[static_cast<std::size_t>(k.sighting)].top_m - anchorTop_m) <= o.restTopTol_m;
  };
  std::vector<const Rest::Kept*> usable;
  for (const auto& k : r.kept)
    if (asHigh(k)) usable.push_back(&k);
  if (usable.empty())
    for (const auto& k : r.kept) usable.push_back(&k);
  std::vector<Eigen::Vector3f> out;
  const bool anyFree = std::any_of(usable.begin(), usable.end(), [](const Rest::Kept* k) { return !k->nearHand; });
  for (const Rest::Kept* k : usable)
    if (!anyFree || !k->nearHand) out.insert(out.end(), k->points.begin(), k->points.end());
  return out;
}

std::string ObjectDiscovery::Impl::describe(const Rest& r) const {
  const Sighting& a = sightings[static_cast<std::size_t>(r.anchor)];
  const cv::RotatedRect box = cv::minAreaRect(a.hull);
  char buf[200];
  std::snprintf(buf, sizeof(buf), "a %s segment %.0f x %.0f x %.0f cm at %s (frames %d-%d)",
                dominantColourWord(a.colours).c_str(), 100 * std::max(box.size.width, box.size.height),
                100 * std::min(box.size.width, box.size.height), 100 * a.top_m, describePlace(a.centre).c_str(),
                frameNumber[static_cast<std::size_t>(r.first)], frameNumber[static_cast<std::size_t>(r.last)]);
  return buf;
}

double ObjectDiscovery::Impl::handDistanceNear(const Rest& r, int frame) const {
  double best = kInf;
  const Eigen::Vector3d c = restCentre3(r);
  for (int f = std::max(0, frame - o.handNearFrames);
       f <= std::min(static_cast<int>(palm.size()) - 1, frame + o.handNearFrames); ++f)
    if (palm[static_cast<std::size_t>(f)]) best = std::min(best, (*palm[static_cast<std::size_t>(f)] - c).norm());
  return best;
}

/// finish()'s steps: the rests that stay (statics), the moves the hand made, and per unknown
/// object its class and one pose sample per frame.
struct ObjectDiscovery::Impl::Finish {
  /// A rest left with the hand, a rest reached with it, alike.
  struct Move {
    int from, to;
    double similarity;
  };
  /// Per frame: the object's pose in the table frame (none: carry the last one), seen, confidence.
  struct Poses {
    std::vector<std::optional<core::Pose3>> X_table_object;
    std::vector<bool> detected;
    std::vector<double> confidence;
  };

  const Impl& m;
  const Options& o;
  const int N;
  const int window;
  std::vector<int> statics;
  std::vector<Move> moves;
  std::map<std::string, Move> movedBy;  // unknown name -> its move

  explicit Finish(const Impl& impl);
  bool atStart(const Rest& r) const { return r.first < window; }
  bool atEnd(const Rest& r) const { return r.last >= N - window; }
  int sightingsOf(const Rest& r) const { return static_cast<int>(r.sightings.size()); }
  double bottomOf(const Rest& r) const {
    std::vector<double> v;
    for (int s : r.sightings) v.push_back(m.sightings[static_cast<std::size_t>(s)].bottom_m);
    return percentile(v, 0.5);
  }
  bool standing(const Rest& r) const;
  std::string startScene() const;
  std::string describeMove(const Move& mv) const;
  bool colourOk(const Sighting& s, const std::optional<std::string>& word) const {
    return !word || shareOf(s.colours, *word) >= o.minColourShare;
  }
  std::vector<bool> sightedIn(const Rest& r) const {
    std::vector<bool> seen(static_cast<std::size_t>(N), false);
    for (int s : r.sightings) seen[static_cast<std::size_t>(m.sightings[static_cast<std::size_t>(s)].frame)] = true;
    return seen;
  }
  std::optional<Eigen::Vector2d> knownFinal(const std::vector<ObjectTrajectory>& known, const std::string& key,
                                            bool final) const;
  void findMoves();
  void matchMovedObjects();
  const Rest& movedObject(const UnknownObject& u, core::ObjectClass& cls, Poses& poses, Result& result) const;
  const Rest& placeObject(const UnknownObject& u, const std::vector<ObjectTrajectory>& known, core::ObjectClass& cls,
                          Poses& poses, ObjectTrajectory& traj, Result& result) const;
  void colourAndSamples(const UnknownObject& u, const Rest& modelRest, const Poses& poses, core::ObjectClass& cls,
                        ObjectTrajectory& traj) const;
};

// Standing on something: a rest's median bottom on the table, or (for a
// part let go in a container) no higher than the rim of a static rest
// whose footprint holds its centre. Segments in the air (an arm, a part
// being carried) are no rests.
ObjectDiscovery::Impl::Finish::Finish(const Impl& impl)
    : m(impl),
      o(impl.o),
      N(static_cast<int>(impl.frameNumber.size())),
      window(std::max(2, static_cast<int>(std::lround(impl.o.windowShare * N)))) {
  for (std::size_t r = 0; r < m.rests.size(); ++r)
    if (atStart(m.rests[r]) && atEnd(m.rests[r]) && sightingsOf(m.rests[r]) >= 2 &&
        bottomOf(m.rests[r]) <= o.maxStandingBottom_m)
      statics.push_back(static_cast<int>(r));
  if (m.debug)
    for (std::size_t r = 0; r < m.rests.size(); ++r)
      core::Log::writef(
          "discovery", core::Log::Level::Debug, "rest %zu: %s, %d sightings, bottom %.3f%s\n", r,
          m.describe(m.rests[r]).c_str(), sightingsOf(m.rests[r]), bottomOf(m.rests[r]),
          std::find(statics.begin(), statics.end(), static_cast<int>(r)) != statics.end() ? ", static" : "");
}

bool ObjectDiscovery::Impl::Finish::standing(const Rest& r) const {
  const double bottom = bottomOf(r);
  if (bottom <= o.maxStandingBottom_m) return true;
  const Sighting& a = m.sightings[static_cast<std::size_t>(r.anchor)];
  for (int c : statics) {
    const Sighting& sc = m.sightings[static_cast<std::size_t>(m.rests[static_cast<std::size_t>(c)].anchor)];
    if (&sc != &a && polygonDistance(sc.hull, a.centre) >= 0 && bottom <= sc.top_m + o.maxStandingBottom_m) return true;
  }
  return false;
}

std::string ObjectDiscovery::Impl::Finish::startScene() const {
  std::string s;
  for (const auto& r : m.rests)
    if (atStart(r) && sightingsOf(r) >= 2 && standing(r)) s += (s.empty() ? "" : "; ") + m.describe(r);
  return s.empty() ? std::string("nothing") : s;
}

std::string ObjectDiscovery::Impl::Finish::describeMove(const Move& mv) const {
  const Rest& A = m.rests[static_cast<std::size_t>(mv.from)];
  const Rest& B = m.rests[static_cast<std::size_t>(mv.to)];
  return m.describe(A) + ", to " + describePlace(m.sightings[static_cast<std::size_t>(B.anchor)].centre) + " (from frame " +
         std::to_string(m.frameNumber[static_cast<std::size_t>(B.first)]) + ")";
}

// Moved parts: a rest left with the hand, a rest reached with it, alike.
void ObjectDiscovery::Impl::Finish::findMoves() {
  for (std::size_t a = 0; a < m.rests.size(); ++a) {
    const Rest& A = m.rests[a];
    if (!atStart(A) || atEnd(A) || sightingsOf(A) < 2 || !standing(A) || m.handDistanceNear(A, A.last) > o.handNear_m)
      continue;
    const Sighting& sa = m.sightings[static_cast<std::size_t>(A.anchor)];
    std::optional<Move> best;
    for (std::size_t b = 0; b < m.rests.size(); ++b) {
      const Rest& B = m.rests[b];
      if (b == a || atStart(B) || !atEnd(B) || sightingsOf(B) < 2 || B.first <= A.last || !standing(B)) continue;
      const Sighting& sb = m.sightings[static_cast<std::size_t>(B.anchor)];
      const double similarity = colourSimilarity(sa.colours, sb.colours);
      const double ratio = std::max(sa.area_m2, sb.area_m2) / std::max(1e-9, std::min(sa.area_m2, sb.area_m2));
      if ((sa.centre - sb.centre).norm() < o.minMove_m || overlap(sa.hull, sb.hull) >= o.minRestOverlap ||
          similarity < o.minColourSimilarity || ratio > o.maxAreaRatio ||
          m.handDistanceNear(B, B.first) > o.handNear_m)
        continue;
      if (!best || similarity > best->similarity) best = Move{static_cast<int>(a), static_cast<int>(b), similarity};
    }
    if (best) moves.push_back(*best);
  }
  std::sort(moves.begin(), moves.end(), [&](const Move& x, const Move& y) {
    return m.rests[static_cast<std::size_t>(x.from)].last < m.rests[static_cast<std::size_t>(y.from)].last;
  });
}

// Each unknown object found; the places after the moved parts.
void ObjectDiscovery::Impl::Finish::matchMovedObjects() {
  std::set<int> used;
  for (const UnknownObject& u : m.objects) {
    if (u.role != UnknownObject::Role::Moved) continue;
    std::vector<Move> fit;
    for (const Move& mv : moves)
      if (!used.count(mv.from) && colourOk(m.sightings[static_cast<std::size_t>(m.rests[static_cast<std::size_t>(mv.from)].anchor)], u.colour))
        fit.push_back(mv);
    const std::string what = "the " + (u.colour ? *u.colour + " " : std::string()) + u.noun;
    if (fit.empty()) {
      std::string seen;
      for (const Move& mv : moves) seen += (seen.empty() ? "" : "; ") + describeMove(mv);
      throw core::InvalidInputError(
          "looking for " + what + " in the demonstration (the knowledge base does not know it): " +
          (moves.empty() ? "no segment on the table was moved by the hand (left its place with the hand and came to rest "
                           "elsewhere); on the table at the start: " + startScene()
                         : "no segment moved by the hand is " + (u.colour ? *u.colour : std::string("left")) +
                               "; moved: " + seen) +
          "; add the " + u.noun + " to the knowledge base (srp kb add) or check the recording");
    }
    if (fit.size() > 1) {
      std::string list;
      for (const Move& mv : fit) list += (list.empty() ? "" : "; ") + describeMove(mv);
      throw core::InvalidInputError("" + std::to_string(fit.size()) + " segments moved by the hand match '" +
                                    what + "': " + list + " (table frame); say which by colour");
    }
    movedBy[u.name] = fit.front();
    used.insert(fit.front().from);
  }
}

std::optional<Eigen::Vector2d> ObjectDiscovery::Impl::Finish::knownFinal(const std::vector<ObjectTrajectory>& known,
                                                                         const std::string& key, bool final) const {
  for (const auto& t : known) {
    if (t.key() != key) continue;
    const ObjectPoseSample* pick = nullptr;
    for (std::size_t i = 0; i < t.samples.size() && i < m.X_camera_table.size(); ++i)
      if (t.samples[i].detected && (final || !pick)) pick = &t.samples[i];
    if (!pick) return std::nullopt;
    const std::size_t i = static_cast<std::size_t>(pick - t.samples.data());
    const Eigen::Vector3d p = m.X_camera_table[i].inverse() * pick->X_camera_object.translation();
    return Eigen::Vector2d(p.x(), p.y());
  }
  return std::nullopt;
}

const Rest& ObjectDiscovery::Impl::Finish::movedObject(const UnknownObject& u, core::ObjectClass& cls, Poses& poses,
                                                        Result& result) const {
  const Move& mv = movedBy.at(u.name);
  const Rest& A = m.rests[static_cast<std::size_t>(mv.from)];
  const Rest& B = m.rests[static_cast<std::size_t>(mv.to)];
  const auto fp = footprintOf(m.fused(A));
  if (!fp) throw core::InvalidInputError("the " + u.noun + " (" + m.describe(A) + ") shows too few points for a model");
  cls.kind = core::ObjectKind::Part;
  cls.shape = "hull";
  cls.dimensions_m = fp->size_m;
  cls.footprint_object = fp->hull_object;
  double area2 = 0.0;
  for (std::size_t i = 0; i < fp->hull_object.size(); ++i) {
    const auto& a = fp->hull_object[i];
    const auto& b = fp->hull_object[(i + 1) % fp->hull_object.size()];
    area2 += a.x() * b.y() - b.x() * a.y();
  }
  cls.mass_kg = std::max(0.01, 0.5 * std::abs(area2) * fp->size_m.z() * o.partDensity_kg_m3);
  // A's place: the model's; B's: the median of its sightings' footprint
  // centres (not of their points, which lean towards the camera: the far
  // side is not seen), its bottom below its top by the model's height.
  std::vector<double> bx, by, btop;
  for (int s : B.sightings) {
    const Sighting& sb = m.sightings[static_cast<std::size_t>(s)];
    const cv::Point2f c = cv::minAreaRect(sb.hull).center;
    bx.push_back(c.x);
    by.push_back(c.y);
    btop.push_back(sb.top_m);
  }
  core::Pose3 atB = fp->X_table_object;
  atB.translation() = Eigen::Vector3d(percentile(bx, 0.5), percentile(by, 0.5),
                                      std::max(0.0, percentile(btop, 0.5) - fp->size_m.z()));
  const auto seenA = sightedIn(A), seenB = sightedIn(B);
  const Sighting& anchorA = m.sightings[static_cast<std::size_t>(A.anchor)];
  for (int i = 0; i < N; ++i) {
    const auto fi = static_cast<std::size_t>(i);
    if (i <= A.last) {
      poses.X_table_object[fi] = fp->X_table_object;
      poses.detected[fi] = seenA[fi];
      poses.confidence[fi] = seenA[fi] ? 1.0 : 0.0;
    } else if (i >= B.first) {
      poses.X_table_object[fi] = atB;
      poses.detected[fi] = seenB[fi];
      poses.confidence[fi] = seenB[fi] ? 1.0 : 0.0;
    } else {
      // Carried: the sighting nearest the palm, of no static rest, alike in colour.
      const Sighting* best = nullptr;
      for (const Sighting& s : m.sightings) {
        if (s.frame != i || !m.palm[fi] || s.handDistance_m > o.handNear_m ||
            std::find(statics.begin(), statics.end(), s.rest) != statics.end() ||
            colourSimilarity(s.colours, anchorA.colours) < o.minColourSimilarity)
          continue;
        if (!best || s.handDistance_m < best->handDistance_m) best = &s;
      }
      if (best) {
        core::Pose3 X = fp->X_table_object;
        // In the air the part's bottom is in view (in its place or in a container it is not).
        X.translation() = Eigen::Vector3d(best->centre.x(), best->centre.y(), std::max(0.0, best->bottom_m));
        poses.X_table_object[fi] = X;
        poses.detected[fi] = true;
        poses.confidence[fi] = 0.5;
      }
    }
  }
  result.notes.push_back("the " + u.noun + ": " + describeMove(mv));
  if (m.debug)
    for (int i = 0; i < N; ++i) {
      const auto fi = static_cast<std::size_t>(i);
      const Eigen::Vector3d p = poses.X_table_object[fi] ? Eigen::Vector3d(poses.X_table_object[fi]->translation()) : Eigen::Vector3d::Zero();
      const Eigen::Vector3d h = m.palm[fi] ? *m.palm[fi] : Eigen::Vector3d::Zero();
      core::Log::writef("discovery", core::Log::Level::Debug,
                        "%s frame %d: %s (%.3f %.3f %.3f) palm (%.3f %.3f %.3f)\n", u.name.c_str(),
                        m.frameNumber[fi], poses.detected[fi] ? "seen" : "-   ", p.x(), p.y(), p.z(), h.x(), h.y(),
                        h.z());
    }
  return A;
}

const Rest& ObjectDiscovery::Impl::Finish::placeObject(const UnknownObject& u, const std::vector<ObjectTrajectory>& known,
                                                        core::ObjectClass& cls, Poses& poses, ObjectTrajectory& traj,
                                                        Result& result) const {
  // The place where a moved object was let go (or picked up).
  const bool release = u.role == UnknownObject::Role::ReleasePlace;
  std::optional<Eigen::Vector2d> at;
  if (const auto it = movedBy.find(u.of); it != movedBy.end()) {
    const Rest& r = m.rests[static_cast<std::size_t>(release ? it->second.to : it->second.from)];
    std::vector<double> x, y;
    for (int s : r.sightings) {
      x.push_back(m.sightings[static_cast<std::size_t>(s)].centre.x());
      y.push_back(m.sightings[static_cast<std::size_t>(s)].centre.y());
    }
    at = Eigen::Vector2d(percentile(x, 0.5), percentile(y, 0.5));
  } else {
    at = knownFinal(known, u.of, release);
  }
  if (!at)
    throw core::InvalidInputError("the " + u.noun + " is where the " + u.of + " was " +
                                  (release ? "let go" : "picked up") + ", but the " + u.of +
                                  " was not seen there");
  int best = -1;
  double bestDistance = kInf;
  for (int r : statics) {
    const Sighting& a = m.sightings[static_cast<std::size_t>(m.rests[static_cast<std::size_t>(r)].anchor)];
    const double d = -polygonDistance(a.hull, *at);  // negative inside
    if (d <= o.placeRadius_m && (best < 0 || d < bestDistance)) {
      best = r;
      bestDistance = d;
    }
  }
  if (best < 0) {
    std::string list;
    for (int r : statics) list += (list.empty() ? "" : "; ") + m.describe(m.rests[static_cast<std::size_t>(r)]);
    throw core::InvalidInputError("looking for the " + u.noun + " in the demonstration: the " + u.of +
                                  " was " + (release ? "let go" : "picked up") + " at " + describePlace(*at) +
                                  " on the table, not in or on anything that stays there (seen throughout: " +
                                  (list.empty() ? std::string("nothing") : list) + ")");
  }
  const Rest& P = m.rests[static_cast<std::size_t>(best)];
  const Sighting& anchor = m.sightings[static_cast<std::size_t>(P.anchor)];
  if (!colourOk(anchor, u.colour))
    throw core::InvalidInputError("the " + u.of + " was " + (release ? "let go in or on " : "picked up from ") +
                                  m.describe(P) + ", which is not " + *u.colour + " as the instruction's '" +
                                  *u.colour + " " + u.noun + "'");
  const std::vector<Eigen::Vector3f> points = m.fused(P);
  const auto fp = footprintOf(points);
  if (!fp) throw core::InvalidInputError("the " + u.noun + " (" + m.describe(P) + ") shows too few points for a model");
  // Concave: the inner half of the footprint does not rise to the rim.
  int inner = 0, innerHigh = 0;
  const core::Pose3 X_object_table = fp->X_table_object.inverse();
  for (const auto& p : points) {
    const Eigen::Vector3d qo = X_object_table * p.cast<double>();
    if (std::abs(qo.x()) > 0.25 * fp->size_m.x() || std::abs(qo.y()) > 0.25 * fp->size_m.y()) continue;
    ++inner;
    innerHigh += qo.z() > o.innerHighFraction * fp->size_m.z();
  }
  const double highShare = inner > 0 ? static_cast<double>(innerHigh) / inner : 0.0;
  const bool container = highShare < o.maxInnerHighShare;
  if (m.debug)
    core::Log::writef("discovery", core::Log::Level::Debug, "%s: %d inner points, %.2f high -> %s\n",
                      u.name.c_str(), inner, highShare, container ? "container" : "part");
  cls.dimensions_m = fp->size_m;
  if (container) {
    cls.kind = core::ObjectKind::Container;
    cls.shape = "open_box";
    cls.wallThickness_m = o.containerWall_m;
    cls.mass_kg = o.containerMass_kg;
  } else {
    cls.kind = core::ObjectKind::Part;
    cls.shape = "hull";
    cls.footprint_object = fp->hull_object;
    cls.mass_kg = 0.5;
  }
  const auto seen = sightedIn(P);
  for (int i = 0; i < N; ++i) {
    poses.X_table_object[static_cast<std::size_t>(i)] = fp->X_table_object;
    poses.detected[static_cast<std::size_t>(i)] = seen[static_cast<std::size_t>(i)];
    poses.confidence[static_cast<std::size_t>(i)] = seen[static_cast<std::size_t>(i)] ? 1.0 : 0.0;
  }
  traj.isStatic = true;
  result.notes.push_back("the " + u.noun + ": " + m.describe(P) + (container ? ", concave (a container)" : "") +
                         ", where the " + u.of + " was " + (release ? "let go" : "picked up"));
  return P;
}

void ObjectDiscovery::Impl::Finish::colourAndSamples(const UnknownObject& u, const Rest& modelRest, const Poses& poses,
                                                     core::ObjectClass& cls, ObjectTrajectory& traj) const {
  // Colour: the instruction's word when the pixels bear it out (a grey bin
  // under warm light is mostly "brown" but grey in a third of its pixels,
  // and the user called it grey), else the sightings' dominant word; rgb
  // their mean (sRGB to linear).
  const Sighting& anchor = m.sightings[static_cast<std::size_t>(modelRest.anchor)];
  cls.colourName = u.colour && colourOk(anchor, u.colour) ? *u.colour
                                                          : dominantColourWord(anchor.colours, o.minColourShare);
  for (int c = 0; c < 3; ++c) {
    const double srgb = anchor.meanBgr[2 - c];
    cls.rgb[c] = linearOf(srgb);
  }
  cls.graspAxis_object = Eigen::Vector3d::UnitY();
  // One sample per frame: a frame without a pose carries the last one (before the first: the first).
  std::optional<core::Pose3> last;
  for (const auto& X : poses.X_table_object)
    if (X && !last) last = X;
  for (int i = 0; i < N; ++i) {
    const auto fi = static_cast<std::size_t>(i);
    if (poses.X_table_object[fi]) last = poses.X_table_object[fi];
    ObjectPoseSample s;
    s.frame = m.frameNumber[fi];
    s.t_s = m.time_s[fi];
    s.X_camera_object = m.X_camera_table[fi] * *last;
    s.detected = poses.detected[fi];
    s.confidence = poses.confidence[fi];
    traj.samples.push_back(s);
  }
}

ObjectDiscovery::Result ObjectDiscovery::finish(const std::vector<ObjectTrajectory>& known, int firstFreeClassId) const {
  const Impl& m = *impl_;
  const int N = static_cast<int>(m.frameNumber.size());
  Result result;
  if (m.objects.empty()) return result;
  if (N == 0) throw core::InvalidInputError("object discovery: no frames");
  if (m.table.size() < 3)
    throw core::InvalidInputError("looking for the " + m.objects.front().name +
                                  " in the demonstration: no table top was seen (no large plane under the scene)");
  Impl::Finish f(m);
  f.findMoves();
  f.matchMovedObjects();
  int nextId = firstFreeClassId;
  for (const UnknownObject& u : m.objects) {
    core::ObjectClass cls;
    cls.name = u.name;
    cls.noun = u.noun.empty() ? u.name : u.noun;
    cls.classId = u.classId >= 0 ? u.classId : nextId++;
    cls.observed = true;
    cls.hasColour = true;
    ObjectTrajectory traj;
    traj.className = u.name;
    traj.classId = cls.classId;
    Impl::Finish::Poses poses{std::vector<std::optional<core::Pose3>>(static_cast<std::size_t>(N)),
                              std::vector<bool>(static_cast<std::size_t>(N), false),
                              std::vector<double>(static_cast<std::size_t>(N), 0.0)};
    const Rest& modelRest = u.role == UnknownObject::Role::Moved ? f.movedObject(u, cls, poses, result)
                                                                 : f.placeObject(u, known, cls, poses, traj, result);
    f.colourAndSamples(u, modelRest, poses, cls, traj);
    result.classes.push_back(cls);
    result.trajectories.push_back(traj);
  }
  return result;
}

}  // namespace srp::perception
