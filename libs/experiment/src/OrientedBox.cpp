#include "srp/experiment/OrientedBox.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "srp/core/Error.h"

namespace srp::experiment {

namespace {

double signedArea(const std::vector<Eigen::Vector2d>& polygon)
{
  double twice = 0.0;
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const auto& p = polygon[i];
    const auto& q = polygon[(i + 1) % polygon.size()];
    twice += p.x() * q.y() - q.x() * p.y();
  }
  return 0.5 * twice;
}

double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

/// Counter-clockwise copy (in a y-up sense; only the consistency matters).
std::vector<Eigen::Vector2d> counterClockwise(std::vector<Eigen::Vector2d> polygon)
{
  if (signedArea(polygon) < 0.0) std::reverse(polygon.begin(), polygon.end());
  return polygon;
}

}  // namespace

double OrientedBox2d::area_px2() const
{
  return std::abs(signedArea({corners_px.begin(), corners_px.end()}));
}

Eigen::Vector2d OrientedBox2d::centre_px() const
{
  return 0.25 * (corners_px[0] + corners_px[1] + corners_px[2] + corners_px[3]);
}

OrientedBox2d minAreaBox(const std::vector<Eigen::Vector2d>& points_px)
{
  if (points_px.empty()) throw core::InvalidInputError("minAreaBox: no points given; pass at least one image point");
  double bestArea = std::numeric_limits<double>::infinity();
  OrientedBox2d best;
  auto tryDirection = [&](Eigen::Vector2d axis) {
    axis.normalize();
    const Eigen::Vector2d normal(-axis.y(), axis.x());
    double aMin = std::numeric_limits<double>::infinity(), aMax = -aMin, nMin = aMin, nMax = -aMin;
    for (const auto& p : points_px) {
      aMin = std::min(aMin, p.dot(axis));
      aMax = std::max(aMax, p.dot(axis));
      nMin = std::min(nMin, p.dot(normal));
      nMax = std::max(nMax, p.dot(normal));
    }
    const double area = (aMax - aMin) * (nMax - nMin);
    if (area < bestArea) {
      bestArea = area;
      best.corners_px = {aMin * axis + nMin * normal, aMax * axis + nMin * normal, aMax * axis + nMax * normal,
                         aMin * axis + nMax * normal};
    }
  };
  tryDirection(Eigen::Vector2d::UnitX());  // also covers a single point or coincident points
  for (std::size_t i = 0; i < points_px.size(); ++i)
    for (std::size_t j = i + 1; j < points_px.size(); ++j)
      if ((points_px[j] - points_px[i]).norm() > 1e-12) tryDirection(points_px[j] - points_px[i]);
  return best;
}

double convexIntersectionArea(const std::vector<Eigen::Vector2d>& a, const std::vector<Eigen::Vector2d>& b)
{
  if (a.size() < 3 || b.size() < 3) return 0.0;
  // Sutherland–Hodgman: clip `a` by each edge of `b` (both counter-clockwise).
  std::vector<Eigen::Vector2d> clipped = counterClockwise(a);
  const std::vector<Eigen::Vector2d> clipper = counterClockwise(b);
  for (std::size_t e = 0; e < clipper.size() && !clipped.empty(); ++e) {
    const Eigen::Vector2d p0 = clipper[e], p1 = clipper[(e + 1) % clipper.size()];
    const Eigen::Vector2d edge = p1 - p0;
    auto inside = [&](const Eigen::Vector2d& q) { return cross(edge, q - p0) >= 0.0; };
    std::vector<Eigen::Vector2d> input;
    input.swap(clipped);
    for (std::size_t i = 0; i < input.size(); ++i) {
      const Eigen::Vector2d cur = input[i], prev = input[(i + input.size() - 1) % input.size()];
      const bool curIn = inside(cur), prevIn = inside(prev);
      if (curIn != prevIn) {
        // Where prev->cur crosses the clipping line.
        const double dPrev = cross(edge, prev - p0), dCur = cross(edge, cur - p0);
        clipped.push_back(prev + (cur - prev) * (dPrev / (dPrev - dCur)));
      }
      if (curIn) clipped.push_back(cur);
    }
  }
  return clipped.size() < 3 ? 0.0 : std::abs(signedArea(clipped));
}

double orientedBoxIoU(const OrientedBox2d& a, const OrientedBox2d& b)
{
  const double areaA = a.area_px2(), areaB = b.area_px2();
  if (areaA <= 0.0 || areaB <= 0.0) return 0.0;
  const double inter = convexIntersectionArea({a.corners_px.begin(), a.corners_px.end()},
                                              {b.corners_px.begin(), b.corners_px.end()});
  const double uni = areaA + areaB - inter;
  return uni > 0.0 ? std::clamp(inter / uni, 0.0, 1.0) : 0.0;
}

OrientedBox2d projectObjectBox(const core::CameraIntrinsics& intrinsics, const core::Pose3& X_camera_object,
                               const Eigen::Vector3d& dimensions_m)
{
  std::vector<Eigen::Vector2d> corners_px;
  for (int i = 0; i < 8; ++i) {
    const Eigen::Vector3d p_object((i & 1 ? 0.5 : -0.5) * dimensions_m.x(), (i & 2 ? 0.5 : -0.5) * dimensions_m.y(),
                                   i & 4 ? dimensions_m.z() : 0.0);
    const Eigen::Vector3d p_camera = X_camera_object * p_object;
    const auto p_px = intrinsics.project(p_camera);
    if (!p_px)
      throw core::InvalidInputError("projectObjectBox: a box corner is behind the camera (z = " +
                                    std::to_string(p_camera.z()) + " m); check X_camera_object");
    corners_px.push_back(*p_px);
  }
  return minAreaBox(corners_px);
}

}  // namespace srp::experiment
