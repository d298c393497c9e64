#include "srp/perception/ObjectPoseFitter.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>

#include "srp/core/Error.h"

namespace srp::perception {

/// Nearest model sample per cell of a grid around the model (object frame),
/// filled by a multi-source breadth-first search (approximate Voronoi).
struct ObjectPoseFitter::Impl {
  Eigen::Vector3d origin;
  Eigen::Vector3i size;
  double cell = 0.002;
  double invCell = 500.0;
  std::vector<int> nearest;

  // The hottest call of a fit (once per point and iteration): truncation
  // instead of floor is the same after the clamp (below 0 clamps to 0 either way).
  inline int lookup(const Eigen::Vector3d& p_object) const {
    const int x = std::clamp(static_cast<int>((p_object.x() - origin.x()) * invCell), 0, size.x() - 1);
    const int y = std::clamp(static_cast<int>((p_object.y() - origin.y()) * invCell), 0, size.y() - 1);
    const int z = std::clamp(static_cast<int>((p_object.z() - origin.z()) * invCell), 0, size.z() - 1);
    return nearest[(static_cast<std::size_t>(z) * size.y() + y) * size.x() + x];
  }
};

ObjectPoseFitter::ObjectPoseFitter(const ObjectModel& model) : ObjectPoseFitter(model, Options{}) {}

ObjectPoseFitter::ObjectPoseFitter(const ObjectModel& model, const Options& options)
    : model_(model), options_(options), impl_(std::make_unique<Impl>()) {
  core::require(!model.surface.empty(), "ObjectPoseFitter: model '" + model.name + "' has no surface samples");
  // Centre of the model's yaw symmetry: the samples' mean along the plane.
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  for (const auto& s : model.surface) centre += s.p_m.head<2>() / static_cast<double>(model.surface.size());
  symmetryCentre_xy_ = centre;
  Eigen::AlignedBox3d box;
  for (const auto& s : model.surface) {
    // A NaN would be skipped by the box (min/max ignore it) and then index the grid at random.
    if (!s.p_m.allFinite() || !s.n.allFinite())
      throw core::InvalidInputError("ObjectPoseFitter: model '" + model.name +
                                    "' has a non-finite surface sample (a mesh with NaN or Inf vertices)");
    box.extend(s.p_m);
  }
  core::require(options.gridCell_m > 0.0 && options.maxGridCells >= 8,
                "ObjectPoseFitter: gridCell_m must be > 0 and maxGridCells >= 8");
  const double margin = 0.03;
  // Cells per axis in double first: a huge model must not overflow an int; the
  // cell grows until the grid fits maxGridCells.
  const Eigen::Vector3d extent = box.sizes() + Eigen::Vector3d::Constant(2 * margin);
  double cell = options.gridCell_m;
  const auto cellsOf = [&extent](double c) { return ((extent / c).array().ceil() + 1.0).matrix().eval(); };
  while (cellsOf(cell).prod() > static_cast<double>(options.maxGridCells)) cell *= 1.25;
  impl_->cell = cell;
  impl_->invCell = 1.0 / cell;
  impl_->origin = box.min() - Eigen::Vector3d::Constant(margin);
  impl_->size = cellsOf(cell).cast<int>();
  const std::size_t n = static_cast<std::size_t>(impl_->size.x()) * static_cast<std::size_t>(impl_->size.y()) *
                        static_cast<std::size_t>(impl_->size.z());
  impl_->nearest.assign(n, -1);
  std::deque<std::size_t> queue;
  auto index = [this](const Eigen::Vector3i& c) {
    return (static_cast<std::size_t>(c.z()) * impl_->size.y() + c.y()) * impl_->size.x() + c.x();
  };
  for (std::size_t i = 0; i < model.surface.size(); ++i) {
    const Eigen::Vector3i c = ((model.surface[i].p_m - impl_->origin) / impl_->cell).array().floor().cast<int>();
    const std::size_t k = index(c);
    if (impl_->nearest[k] < 0) {
      impl_->nearest[k] = static_cast<int>(i);
      queue.push_back(k);
    }
  }
  const int sx = impl_->size.x(), sy = impl_->size.y(), sz = impl_->size.z();
  while (!queue.empty()) {
    const std::size_t k = queue.front();
    queue.pop_front();
    const int x = static_cast<int>(k % sx), y = static_cast<int>((k / sx) % sy), z = static_cast<int>(k / (static_cast<std::size_t>(sx) * sy));
    const int dirs[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    for (const auto& d : dirs) {
      const int nx = x + d[0], ny = y + d[1], nz = z + d[2];
      if (nx < 0 || ny < 0 || nz < 0 || nx >= sx || ny >= sy || nz >= sz) continue;
      const std::size_t kk = index({nx, ny, nz});
      if (impl_->nearest[kk] >= 0) continue;
      impl_->nearest[kk] = impl_->nearest[k];
      queue.push_back(kk);
    }
  }
}

ObjectPoseFitter::~ObjectPoseFitter() = default;

bool ObjectPoseFitter::hasOffCentreSymmetry() const {
  constexpr double kOffCentre_m = 5e-4;  // well below a pixel's footprint; the star's is 2.6 mm
  return model_.yawSymmetry_rad < 2 * 3.14159265358979323846 - 1e-6 && symmetryCentre_xy_.norm() > kOffCentre_m;
}

std::vector<core::Pose3> ObjectPoseFitter::symmetricBranches(const core::Pose3& X_camera_object) const {
  const int n = std::max(1, static_cast<int>(std::lround(2 * 3.14159265358979323846 / model_.yawSymmetry_rad)));
  const Eigen::Vector3d c(symmetryCentre_xy_.x(), symmetryCentre_xy_.y(), 0.0);
  std::vector<core::Pose3> out;
  for (int k = 0; k < n; ++k) {
    // X * T(c) * Rz(k * symmetry) * T(-c): turned about the symmetry centre.
    core::Pose3 turn = core::Pose3::Identity();
    turn.linear() = Eigen::AngleAxisd(k * model_.yawSymmetry_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    turn.translation() = c - turn.linear() * c;
    out.push_back(X_camera_object * turn);
  }
  return out;
}
ObjectPoseFitter::ObjectPoseFitter(ObjectPoseFitter&&) noexcept = default;
ObjectPoseFitter& ObjectPoseFitter::operator=(ObjectPoseFitter&&) noexcept = default;

namespace {

// The model's camera-facing surface samples at X_camera_object, projected
// and compared with the measured depth depthAt(v, u) [m].
template <class DepthAt>
ObjectPoseFitter::SurfaceEvidence surfaceEvidenceOf(const ObjectModel& model, const core::Pose3& X_camera_object,
                                                    const core::CameraIntrinsics& k, int cols, int rows,
                                                    double inlierTol_m, double occluderMargin_m, DepthAt depthAt) {
  ObjectPoseFitter::SurfaceEvidence e;
  const std::size_t step = std::max<std::size_t>(1, model.surface.size() / 2000);
  for (std::size_t i = 0; i < model.surface.size(); i += step) {
    const Eigen::Vector3d p = X_camera_object * model.surface[i].p_m;
    const Eigen::Vector3d n = X_camera_object.linear() * model.surface[i].n;
    if (p.z() <= 0 || n.dot(p.normalized()) > -0.15) continue;  // back-facing or grazing
    const int u = static_cast<int>(std::lround(k.fx_px * p.x() / p.z() + k.cx_px));
    const int v = static_cast<int>(std::lround(k.fy_px * p.y() / p.z() + k.cy_px));
    if (u < 0 || v < 0 || u >= cols || v >= rows) continue;
    ++e.inView;
    const float zObs = depthAt(v, u);
    if (!(zObs > 0.f)) continue;  // no depth: no evidence
    const double dz = zObs - p.z();
    if (dz < -occluderMargin_m) ++e.occluded;
    else if (std::abs(dz) < inlierTol_m) ++e.supported;
    else if (dz > 0) ++e.seenThrough;  // the camera sees through where the model should be
    // otherwise something in front within the margin: no evidence
  }
  return e;
}

}  // namespace

ObjectPoseFitter::SurfaceEvidence ObjectPoseFitter::surfaceEvidence(const core::Pose3& X_camera_object,
                                                                    const cv::Mat& cloud,
                                                                    const CameraModel& camera) const {
  return surfaceEvidenceOf(model_, X_camera_object, camera.intrinsics(), cloud.cols, cloud.rows,
                           options_.inlierTol_m, std::numeric_limits<double>::infinity(),
                           [&](int v, int u) { return cloud.at<cv::Vec3f>(v, u)[2]; });
}

ObjectPoseFitter::SurfaceEvidence ObjectPoseFitter::surfaceEvidenceInDepth(const core::Pose3& X_camera_object,
                                                                           const cv::Mat& depth_m,
                                                                           const core::CameraIntrinsics& intrinsics,
                                                                           double occluderMargin_m) const {
  return surfaceEvidenceOf(model_, X_camera_object, intrinsics, depth_m.cols, depth_m.rows, options_.inlierTol_m,
                           occluderMargin_m, [&](int v, int u) { return depth_m.at<float>(v, u); });
}

double ObjectPoseFitter::coverage(const core::Pose3& X_camera_object, const cv::Mat& cloud,
                                  const CameraModel& camera) const {
  const SurfaceEvidence e = surfaceEvidence(X_camera_object, cloud, camera);
  return e.total() > 0 ? static_cast<double>(e.supported) / e.total() : 0.0;
}

ObjectPoseFit ObjectPoseFitter::evaluate(const std::vector<Eigen::Vector3d>& points_camera,
                                         const core::Pose3& X_camera_object, const cv::Mat& cloud,
                                         const CameraModel& camera) const {
  ObjectPoseFit f;
  f.X_camera_object = X_camera_object;
  if (points_camera.empty()) return f;
  const core::Pose3 X_object_camera = X_camera_object.inverse();
  const std::size_t step = std::max<std::size_t>(1, points_camera.size() / static_cast<std::size_t>(options_.maxPoints));
  int used = 0, inliers = 0;
  double sq = 0.0;
  for (std::size_t i = 0; i < points_camera.size(); i += step, ++used) {
    const Eigen::Vector3d po = X_object_camera * points_camera[i];
    const double d = (po - model_.surface[static_cast<std::size_t>(impl_->lookup(po))].p_m).norm();
    if (d < options_.inlierTol_m) {
      ++inliers;
      sq += d * d;
    }
  }
  f.inlierRatio = static_cast<double>(inliers) / used;
  f.rms_m = inliers > 0 ? std::sqrt(sq / inliers) : 0.0;
  f.coverage = coverage(X_camera_object, cloud, camera);
  f.score = f.inlierRatio * f.coverage;
  return f;
}

ObjectPoseFitter::PlanePoints ObjectPoseFitter::toPlaneFrame(const std::vector<Eigen::Vector3d>& points_camera,
                                                             const core::Pose3& X_plane_camera) const {
  PlanePoints out;
  const std::size_t step = std::max<std::size_t>(1, points_camera.size() / static_cast<std::size_t>(options_.maxPoints));
  for (std::size_t i = 0; i < points_camera.size(); i += step) out.q.push_back(X_plane_camera * points_camera[i]);
  out.centroid = Eigen::Vector3d::Zero();
  std::vector<double> heights;
  for (const auto& p : out.q) {
    out.centroid += p;
    heights.push_back(p.z());
  }
  out.centroid /= static_cast<double>(out.q.size());
  // Robust top (topPercentile): flying pixels above edges do not count.
  const std::size_t iTop =
      heights.size() - 1 - static_cast<std::size_t>((1.0 - options_.topPercentile) * static_cast<double>(heights.size()));
  std::nth_element(heights.begin(), heights.begin() + static_cast<long>(iTop), heights.end());
  out.top_m = heights[iTop];
  return out;
}

std::vector<Eigen::Vector4d> ObjectPoseFitter::startPoses(const PlanePoints& points, const core::Pose3& X_plane_camera,
                                                          const core::Pose3* initial) const {
  std::vector<Eigen::Vector4d> starts;  // x, y, z, yaw in the plane frame
  if (initial) {
    const core::Pose3 X = X_plane_camera * *initial;
    starts.emplace_back(X.translation().x(), X.translation().y(), X.translation().z(),
                        std::atan2(X.linear()(1, 0), X.linear()(0, 0)));
    return starts;
  }
  const double z0 = std::max(0.0, points.top_m - model_.dimensions_m.z());
  const double step = options_.yawStep_rad;
  const int nYaw = std::max(1, static_cast<int>(std::ceil(model_.yawSymmetry_rad / step - 1e-9)));
  for (int i = 0; i < nYaw; ++i) {
    starts.emplace_back(points.centroid.x(), points.centroid.y(), z0, i * step);
    // Also standing on the plane itself, unless the top says otherwise by far.
    if (z0 > options_.onPlaneStartMinHeight_m) starts.emplace_back(points.centroid.x(), points.centroid.y(), 0.0, i * step);
  }
  return starts;
}

Eigen::Vector4d ObjectPoseFitter::icpFourDof(const std::vector<Eigen::Vector3d>& q, const Eigen::Vector4d& s,
                                             int iterations, std::size_t stride) const {
  const double tol = options_.inlierTol_m;
  Eigen::Vector3d t = s.head<3>();
  double yaw = s[3];
  for (int it = 0; it < iterations; ++it) {
    const Eigen::Matrix3d R = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    // Later iterations trust only close matches (outliers: other objects, the hand).
    const double gate = it < iterations / 2 ? options_.earlyGate_m : options_.lateGate_tol * tol;
    // Point-to-plane (along the model normal; free of the sampling's
    // spacing) plus a weak point-to-point term that keeps faces from sliding.
    // The Jacobian of a residual e = p - (R m0 + t) in (t, yaw) is
    // J = [-I | -c], c = (-m.y, m.x, 0); J^T J = [[I, c], [c^T, c.c]] is
    // summed as its parts (sum w, sum w c, sum w c.c), the plane term as a
    // rank-one update: the same normal equations at a fraction of the cost.
    const double kPointWeight = options_.pointToPointWeight;
    Eigen::Matrix4d H = Eigen::Matrix4d::Zero();
    Eigen::Vector4d g = Eigen::Vector4d::Zero();
    double sumW = 0.0, sumWcc = 0.0;
    Eigen::Vector3d sumWc = Eigen::Vector3d::Zero();
    for (std::size_t i = 0; i < q.size(); i += stride) {
      const Eigen::Vector3d& p = q[i];
      const Eigen::Vector3d po = R.transpose() * (p - t);
      const kb::SurfacePoint& sp = model_.surface[static_cast<std::size_t>(impl_->lookup(po))];
      const Eigen::Vector3d m = R * sp.p_m;
      const Eigen::Vector3d e = p - (m + t);
      const double dist2 = e.squaredNorm();
      if (dist2 > gate * gate) continue;
      const double dist = std::sqrt(dist2);
      const double w = dist < tol ? 1.0 : tol / dist;  // Huber
      const Eigen::Vector3d c(-m.y(), m.x(), 0.0);
      const Eigen::Vector3d n = R * sp.n;
      const Eigen::Vector4d a(-n.x(), -n.y(), -n.z(), -n.dot(c));  // n^T J
      H.noalias() += (w * a) * a.transpose();
      g += (w * n.dot(e)) * a;
      sumW += w;
      sumWc += w * c;
      sumWcc += w * c.squaredNorm();
      g.head<3>() -= (kPointWeight * w) * e;
      g(3) -= kPointWeight * w * c.dot(e);
    }
    H.topLeftCorner<3, 3>().diagonal().array() += kPointWeight * sumW;
    H.topRightCorner<3, 1>() += kPointWeight * sumWc;
    H.bottomLeftCorner<1, 3>() += kPointWeight * sumWc.transpose();
    H(3, 3) += kPointWeight * sumWcc;
    // Weak prior keeping the start's height: side faces alone cannot tell
    // the height (an open box's walls fit raised as well); the starts try both
    // "on the plane" and "top at the data's top", and coverage picks.
    const double zPrior = options_.heightPriorWeight * H(0, 0);
    H(2, 2) += zPrior;
    g(2) += zPrior * (t.z() - s[2]);
    const double damping = options_.icpDamping;
    H.diagonal() += Eigen::Vector4d(damping, damping, damping, damping);
    const Eigen::Vector4d delta = -H.ldlt().solve(g);
    t += delta.head<3>();
    yaw += std::clamp(delta[3], -options_.maxYawStep_rad, options_.maxYawStep_rad);
    if (delta.head<3>().norm() < options_.icpConvergence && std::abs(delta[3]) < options_.icpConvergence) break;
  }
  return Eigen::Vector4d(t.x(), t.y(), t.z(), yaw);
}

ObjectPoseFit ObjectPoseFitter::scoreFourDof(const std::vector<Eigen::Vector3d>& q, const Eigen::Vector4d& x,
                                             const core::Pose3& X_camera_plane, const cv::Mat& cloud,
                                             const CameraModel& camera) const {
  const double tol = options_.inlierTol_m;
  const Eigen::Matrix3d R = Eigen::AngleAxisd(x[3], Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Eigen::Vector3d t = x.head<3>();
  int inliers = 0;
  double sq = 0.0;
  for (const auto& p : q) {
    const Eigen::Vector3d po = R.transpose() * (p - t);
    const double d = (po - model_.surface[static_cast<std::size_t>(impl_->lookup(po))].p_m).norm();
    if (d < tol) {
      ++inliers;
      sq += d * d;
    }
  }
  core::Pose3 X_plane_object = core::Pose3::Identity();
  X_plane_object.linear() = R;
  X_plane_object.translation() = t;
  ObjectPoseFit f;
  f.X_camera_object = X_camera_plane * X_plane_object;
  f.inlierRatio = static_cast<double>(inliers) / static_cast<double>(q.size());
  f.rms_m = inliers > 0 ? std::sqrt(sq / inliers) : 0.0;
  f.coverage = coverage(f.X_camera_object, cloud, camera);
  f.score = f.inlierRatio * f.coverage;
  return f;
}

std::optional<ObjectPoseFit> ObjectPoseFitter::refineTiltSixDof(const std::vector<Eigen::Vector3d>& q,
                                                                const ObjectPoseFit& best,
                                                                const core::Pose3& X_camera_plane,
                                                                const cv::Mat& cloud,
                                                                const CameraModel& camera) const {
  // 6-DOF refinement from the 4-DOF pose: the object may tilt a little
  // against the fitted plane (a plane fit error, an uneven support).
  // Rotation linearised about the object origin: X' = (exp(w) R, t + v).
  const double tol = options_.inlierTol_m;
  core::Pose3 X = best.X_camera_object;
  for (int it = 0; it < options_.iterations; ++it) {
    const core::Pose3 Xinv = X.inverse();
    // J = [[r]x | -I] per point; J^T J = [[|r|^2 I - r r^T, [r]x], [-[r]x, I]]
    // and J^T e = [e x r; -e] are summed as their parts.
    double sumW = 0.0, sumWrr = 0.0;
    Eigen::Vector3d sumWr = Eigen::Vector3d::Zero(), sumWe = Eigen::Vector3d::Zero(),
                    sumWexr = Eigen::Vector3d::Zero();
    Eigen::Matrix3d sumWrrT = Eigen::Matrix3d::Zero();
    const Eigen::Matrix3d X_object_plane_R = Xinv.linear() * X_camera_plane.linear();
    const Eigen::Vector3d X_object_plane_t = Xinv.linear() * X_camera_plane.translation() + Xinv.translation();
    for (const auto& pp : q) {
      const Eigen::Vector3d p = X_camera_plane * pp;
      const Eigen::Vector3d m =
          X * model_.surface[static_cast<std::size_t>(impl_->lookup(X_object_plane_R * pp + X_object_plane_t))].p_m;
      const Eigen::Vector3d e = p - m;
      const double dist2 = e.squaredNorm();
      if (dist2 > options_.tiltGate_tol * options_.tiltGate_tol * tol * tol) continue;
      const double dist = std::sqrt(dist2);
      const double w = dist < tol ? 1.0 : tol / dist;
      const Eigen::Vector3d r = m - X.translation();
      sumW += w;
      sumWr += w * r;
      sumWrr += w * r.squaredNorm();
      sumWrrT.noalias() += (w * r) * r.transpose();
      sumWe += w * e;
      sumWexr += w * e.cross(r);
    }
    const Eigen::Matrix3d S = (Eigen::Matrix3d() << 0, -sumWr.z(), sumWr.y(), sumWr.z(), 0, -sumWr.x(), -sumWr.y(),
                               sumWr.x(), 0)
                                  .finished();  // sum w [r]x
    Eigen::Matrix<double, 6, 6> H;
    H.topLeftCorner<3, 3>() = sumWrr * Eigen::Matrix3d::Identity() - sumWrrT;
    H.topRightCorner<3, 3>() = S;
    H.bottomLeftCorner<3, 3>() = -S;
    H.bottomRightCorner<3, 3>() = sumW * Eigen::Matrix3d::Identity();
    Eigen::Matrix<double, 6, 1> g;
    g.head<3>() = sumWexr;
    g.tail<3>() = -sumWe;
    H.diagonal().array() += options_.tiltDamping;
    const Eigen::Matrix<double, 6, 1> d = -H.ldlt().solve(g);
    const Eigen::Vector3d wv = d.head<3>();
    if (wv.norm() > 1e-12) X.linear() = Eigen::AngleAxisd(wv.norm(), wv.normalized()).toRotationMatrix() * X.linear();
    X.translation() += d.tail<3>();
    if (d.norm() < options_.tiltConvergence) break;
  }
  // Only a pose that stays near the plane's normal.
  const double tilt = std::acos(std::clamp((X.linear().col(2)).dot(X_camera_plane.linear().col(2)), -1.0, 1.0));
  if (tilt >= options_.maxTilt_rad) return std::nullopt;
  ObjectPoseFit f = best;
  f.X_camera_object = X;
  int inliers = 0;
  double sq = 0.0;
  const core::Pose3 Xinv = X.inverse();
  for (const auto& pp : q) {
    const Eigen::Vector3d po = Xinv * (X_camera_plane * pp);
    const double dd = (po - model_.surface[static_cast<std::size_t>(impl_->lookup(po))].p_m).norm();
    if (dd < tol) {
      ++inliers;
      sq += dd * dd;
    }
  }
  f.inlierRatio = static_cast<double>(inliers) / static_cast<double>(q.size());
  f.rms_m = inliers > 0 ? std::sqrt(sq / inliers) : 0.0;
  f.coverage = coverage(X, cloud, camera);
  f.score = f.inlierRatio * f.coverage;
  return f;
}

ObjectPoseFit ObjectPoseFitter::fit(const std::vector<Eigen::Vector3d>& points_camera, const Plane& support,
                                    const cv::Mat& cloud, const CameraModel& camera,
                                    const core::Pose3* initial, double giveUpBelow) const {
  ObjectPoseFit best;
  if (points_camera.size() < static_cast<std::size_t>(options_.minPoints)) return best;
  const core::Pose3 X_camera_plane = support.X_camera_plane();
  const core::Pose3 X_plane_camera = X_camera_plane.inverse();
  const PlanePoints points = toPlaneFrame(points_camera, X_plane_camera);
  const std::vector<Eigen::Vector3d>& q = points.q;
  const std::vector<Eigen::Vector4d> starts = startPoses(points, X_plane_camera, initial);
  auto score = [&](const Eigen::Vector4d& x) { return scoreFourDof(q, x, X_camera_plane, cloud, camera); };

  // Coarse: every start, a few iterations on every coarseStride-th point;
  // fine: the fineStarts best starts, fully.
  std::vector<std::pair<double, Eigen::Vector4d>> coarse;
  const std::size_t coarseStride = starts.size() > 1 ? static_cast<std::size_t>(options_.coarseStride) : 1;
  for (const Eigen::Vector4d& s : starts) {
    const Eigen::Vector4d x = icpFourDof(q, s, starts.size() > 1 ? options_.coarseIterations : 0, coarseStride);
    coarse.emplace_back(score(x).score, x);
  }
  std::sort(coarse.begin(), coarse.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  if (coarse.front().first < giveUpBelow) return score(coarse.front().second);
  for (std::size_t k = 0; k < std::min<std::size_t>(static_cast<std::size_t>(options_.fineStarts), coarse.size()); ++k) {
    const Eigen::Vector4d x = icpFourDof(q, coarse[k].second, options_.iterations, 1);
    const ObjectPoseFit f = score(x);
    if (f.score > best.score) best = f;
    // Height check: the same footprint standing on the plane (side faces do
    // not fix the height; the coverage of what is below does).
    if (!initial && std::abs(x[2]) > options_.heightCheck_m) {
      Eigen::Vector4d onPlane = x;
      onPlane[2] = 0.0;
      const ObjectPoseFit g = score(icpFourDof(q, onPlane, options_.iterations / 2, 1));
      if (g.score > best.score) best = g;
    }
  }
  if (options_.refineTilt && best.score > 0.0) {
    // Kept when it explains the data at least as well (within tiltScoreSlack).
    const std::optional<ObjectPoseFit> tilted = refineTiltSixDof(q, best, X_camera_plane, cloud, camera);
    if (tilted && tilted->score >= best.score - options_.tiltScoreSlack) best = *tilted;
  }
  return best;
}

}  // namespace srp::perception
