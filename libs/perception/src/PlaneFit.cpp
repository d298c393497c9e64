#include "srp/perception/PlaneFit.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace srp::perception {

core::Pose3 Plane::X_camera_plane() const {
  core::Pose3 X = core::Pose3::Identity();
  Eigen::Vector3d x = Eigen::Vector3d::UnitX() - n * n.x();
  if (x.norm() < 1e-6) x = Eigen::Vector3d::UnitY() - n * n.y();
  x.normalize();
  X.linear().col(0) = x;
  X.linear().col(1) = n.cross(x);
  X.linear().col(2) = n;
  // Foot of the optical axis (0, 0, t) on the plane: t n_z + d = 0.
  X.translation() = std::abs(n.z()) > 1e-6 ? Eigen::Vector3d(0, 0, -d / n.z()) : Eigen::Vector3d(-d * n);
  return X;
}

std::optional<double> Plane::rayScaleAtHeight(const Eigen::Vector3d& ray, double height_m) const {
  // n . (s ray) + d = height_m.
  const double along = n.dot(ray);
  if (std::abs(along) < 1e-12) return std::nullopt;
  const double s = (height_m - d) / along;
  if (!(s > 0.0)) return std::nullopt;
  return s;
}

namespace {

/// The least-squares plane through the points within tol_m of `plane`: their mean and the normal of
/// least variance, unoriented (each caller picks the side). nullopt with fewer than 3 such points.
struct InlierFit {
  Eigen::Vector3d n, mean;
  int inliers = 0;
};
std::optional<InlierFit> leastSquaresOnInliers(const std::vector<Eigen::Vector3d>& pts, const Plane& plane,
                                               double tol_m) {
  std::vector<Eigen::Vector3d> in;
  for (const auto& p : pts)
    if (std::abs(plane.height(p)) < tol_m) in.push_back(p);
  if (in.size() < 3) return std::nullopt;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const auto& p : in) mean += p;
  mean /= static_cast<double>(in.size());
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const auto& p : in) cov += (p - mean) * (p - mean).transpose();
  return InlierFit{Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(cov).eigenvectors().col(0), mean,
                   static_cast<int>(in.size())};
}

/// RANSAC over `pts`: per iteration three random points give a normal; `hypothesis(n, a)` orients it
/// (a: one of the three points) and returns the plane, or nullopt to reject it. The plane with the
/// most points within tol_m wins (inliers 0 when every hypothesis was rejected).
template <typename Hypothesis>
Plane ransacPlane(const std::vector<Eigen::Vector3d>& pts, int iterations, unsigned seed, double tol_m,
                  Hypothesis hypothesis) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<std::size_t> pick(0, pts.size() - 1);
  Plane best;
  best.inliers = 0;
  for (int it = 0; it < iterations; ++it) {
    const Eigen::Vector3d a = pts[pick(rng)], b = pts[pick(rng)], c = pts[pick(rng)];
    Eigen::Vector3d n = (b - a).cross(c - a);
    if (n.norm() < 1e-9) continue;
    n.normalize();
    const std::optional<Plane> h = hypothesis(n, a);
    if (!h) continue;
    int count = 0;
    for (const auto& p : pts) count += std::abs(h->n.dot(p) + h->d) < tol_m;
    if (count > best.inliers) best = Plane{h->n, h->d, count};
  }
  return best;
}

}  // namespace

namespace {

std::vector<Eigen::Vector3d> samplePoints(const cv::Mat& cloud, int stride_px) {
  std::vector<Eigen::Vector3d> pts;
  for (int v = 0; v < cloud.rows; v += stride_px)
    for (int u = 0; u < cloud.cols; u += stride_px) {
      const cv::Vec3f& p = cloud.at<cv::Vec3f>(v, u);
      if (p[2] > 0.f) pts.emplace_back(p[0], p[1], p[2]);
    }
  return pts;
}

/// RANSAC (normals oriented to the camera's side, `accept` filtering them),
/// then least squares on the inliers, twice.
template <typename Accept>
std::optional<Plane> fitPlaneTo(const std::vector<Eigen::Vector3d>& pts, const PlaneFitOptions& o, Accept accept) {
  if (pts.size() < 3) return std::nullopt;
  Plane best = ransacPlane(pts, o.iterations, o.seed, o.inlierTol_m,
                           [&](Eigen::Vector3d n, const Eigen::Vector3d& a) -> std::optional<Plane> {
                             double d = -n.dot(a);
                             if (d < 0) {
                               n = -n;
                               d = -d;
                             }
                             if (!accept(n)) return std::nullopt;
                             return Plane{n, d, 0};
                           });
  if (best.inliers < 3) return std::nullopt;
  // Least-squares refinement on the inliers (twice, tightening).
  for (int pass = 0; pass < 2; ++pass) {
    const auto fit = leastSquaresOnInliers(pts, best, o.inlierTol_m);
    if (!fit) break;
    Eigen::Vector3d n = fit->n;
    double d = -n.dot(fit->mean);
    if (d < 0) {
      n = -n;
      d = -d;
    }
    best = Plane{n, d, fit->inliers};
  }
  return best;
}

}  // namespace

std::optional<Plane> fitDominantPlane(const cv::Mat& cloud, const PlaneFitOptions& o) {
  return fitPlaneTo(samplePoints(cloud, o.sampleStride_px), o, [&](const Eigen::Vector3d& n) {
    return !o.expectedNormal ||
           std::acos(std::clamp(n.dot(o.expectedNormal->normalized()), -1.0, 1.0)) <= o.maxTilt_rad;
  });
}

std::optional<Plane> fitSupportPlane(const cv::Mat& cloud, const PlaneFitOptions& o) {
  const std::optional<Plane> dominant = fitDominantPlane(cloud, o);
  if (!dominant || o.expectedNormal) return dominant;
  std::vector<Eigen::Vector3d> rest;
  for (const auto& p : samplePoints(cloud, o.sampleStride_px))
    if (std::abs(dominant->height(p)) >= o.inlierTol_m) rest.push_back(p);
  const double cosMinTurn = std::cos(o.secondPlaneMinTurn_rad);
  // The second plane holds fewer of the points: more hypotheses to draw three of its own.
  PlaneFitOptions secondOptions = o;
  secondOptions.iterations = o.iterations * o.secondPlaneIterationFactor;
  const std::optional<Plane> second = fitPlaneTo(
      rest, secondOptions, [&](const Eigen::Vector3d& n) { return std::abs(n.dot(dominant->n)) <= cosMinTurn; });
  if (second && second->inliers >= o.secondPlaneMinShare * dominant->inliers &&
      second->n.y() <= dominant->n.y() - o.secondPlaneMinUpward)
    return second;
  return dominant;
}

std::optional<Plane> fitLocalPlane(const cv::Mat& cloud, const Plane& global, const cv::Rect& roi_px,
                                   const LocalPlaneOptions& o) {
  const int grow = static_cast<int>(std::lround(o.margin * std::max(roi_px.width, roi_px.height)));
  const cv::Rect roi = cv::Rect(roi_px.x - grow, roi_px.y - grow, roi_px.width + 2 * grow, roi_px.height + 2 * grow) &
                       cv::Rect(0, 0, cloud.cols, cloud.rows);
  std::vector<Eigen::Vector3d> pts;
  for (int v = roi.y; v < roi.y + roi.height; v += o.stride_px) {
    const cv::Vec3f* row = cloud.ptr<cv::Vec3f>(v);
    for (int u = roi.x; u < roi.x + roi.width; u += o.stride_px) {
      if (row[u][2] <= 0.f) continue;
      const Eigen::Vector3d p(row[u][0], row[u][1], row[u][2]);
      if (std::abs(global.height(p)) < o.band_m) pts.push_back(p);
    }
  }
  if (static_cast<int>(pts.size()) < o.minInliers) return std::nullopt;
  const double cosMaxTurn = std::cos(o.maxTurn_rad);
  const Plane best = ransacPlane(pts, o.iterations, o.seed, o.inlierTol_m,
                                 [&](Eigen::Vector3d n, const Eigen::Vector3d& a) -> std::optional<Plane> {
                                   if (n.dot(global.n) < 0) n = -n;  // the camera's side, as the global plane
                                   if (n.dot(global.n) < cosMaxTurn) return std::nullopt;
                                   return Plane{n, -n.dot(a), 0};
                                 });
  if (best.inliers < o.minInliers) return std::nullopt;
  // Least squares on the inliers.
  const auto fit = leastSquaresOnInliers(pts, best, o.inlierTol_m);
  if (!fit) return std::nullopt;
  const Eigen::Vector3d& mean = fit->mean;
  Eigen::Vector3d n = fit->n;
  if (n.dot(global.n) < 0) n = -n;
  if (n.dot(global.n) < cosMaxTurn) return std::nullopt;
  const Plane local{n, -n.dot(mean), fit->inliers};
  // The shift where the part stands: the global plane's point below the roi's centre.
  const cv::Vec3f& centre = cloud.at<cv::Vec3f>(roi_px.y + roi_px.height / 2, roi_px.x + roi_px.width / 2);
  Eigen::Vector3d q = mean;
  if (centre[2] > 0.f) q = Eigen::Vector3d(centre[0], centre[1], centre[2]);
  const Eigen::Vector3d foot = q - global.height(q) * global.n;
  if (std::abs(local.height(foot)) > o.maxShift_m) return std::nullopt;
  return local;
}

}  // namespace srp::perception
