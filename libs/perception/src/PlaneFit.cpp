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

std::optional<Plane> fitDominantPlane(const cv::Mat& cloud, const PlaneFitOptions& o) {
  std::vector<Eigen::Vector3d> pts;
  for (int v = 0; v < cloud.rows; v += o.sampleStride_px)
    for (int u = 0; u < cloud.cols; u += o.sampleStride_px) {
      const cv::Vec3f& p = cloud.at<cv::Vec3f>(v, u);
      if (p[2] > 0.f) pts.emplace_back(p[0], p[1], p[2]);
    }
  if (pts.size() < 3) return std::nullopt;
  std::mt19937 rng(o.seed);
  std::uniform_int_distribution<std::size_t> pick(0, pts.size() - 1);
  Plane best;
  best.inliers = 0;
  for (int it = 0; it < o.iterations; ++it) {
    const Eigen::Vector3d a = pts[pick(rng)], b = pts[pick(rng)], c = pts[pick(rng)];
    Eigen::Vector3d n = (b - a).cross(c - a);
    if (n.norm() < 1e-9) continue;
    n.normalize();
    double d = -n.dot(a);
    if (d < 0) {
      n = -n;
      d = -d;
    }
    if (o.expectedNormal && std::acos(std::clamp(n.dot(o.expectedNormal->normalized()), -1.0, 1.0)) > o.maxTilt_rad)
      continue;
    int count = 0;
    for (const auto& p : pts) count += std::abs(n.dot(p) + d) < o.inlierTol_m;
    if (count > best.inliers) best = Plane{n, d, count};
  }
  if (best.inliers < 3) return std::nullopt;
  // Least-squares refinement on the inliers (twice, tightening).
  for (int pass = 0; pass < 2; ++pass) {
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    std::vector<Eigen::Vector3d> in;
    for (const auto& p : pts)
      if (std::abs(best.height(p)) < o.inlierTol_m) in.push_back(p);
    if (in.size() < 3) break;
    for (const auto& p : in) mean += p;
    mean /= static_cast<double>(in.size());
    Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
    for (const auto& p : in) cov += (p - mean) * (p - mean).transpose();
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(cov);
    Eigen::Vector3d n = es.eigenvectors().col(0);
    double d = -n.dot(mean);
    if (d < 0) {
      n = -n;
      d = -d;
    }
    best = Plane{n, d, static_cast<int>(in.size())};
  }
  return best;
}

}  // namespace srp::perception
