#pragma once
// Footprint geometry shared by the placement context, the relations, the after-placement
// checks and the joint refinement (private to srp::execution). Frames: world = table
// frame, z up, metres; a footprint is the part's bounding box seen from above.

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>
#include <string>

#include "srp/core/Pose.h"
#include "srp/execution/CellDescription.h"

namespace srp::execution::placement {

using srp::core::Pose3;

inline double yawOfPose(const Pose3& X) { return srp::core::yawOf(X.linear()); }

inline Pose3 uprightPose(const Eigen::Vector3d& p, double yaw) {
  Pose3 X = Pose3::Identity();
  X.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  X.translation() = p;
  return X;
}

/// Footprint rectangle corners of a box of `size` at X (world x, y), grown by `inflate` on every side.
inline std::array<Eigen::Vector2d, 4> footprint(const Eigen::Vector3d& size, const Pose3& X, double inflate) {
  std::array<Eigen::Vector2d, 4> c;
  const double hx = size.x() / 2 + inflate, hy = size.y() / 2 + inflate;
  int i = 0;
  for (double sx : {-1.0, 1.0})
    for (double sy : {-1.0, 1.0}) c[i++] = (X * Eigen::Vector3d(sx * hx, sy * hy, 0)).head<2>();
  return c;
}

/// Largest gap between two footprints along the four rectangle axes (separating-axis
/// test): > 0 apart by at least that much along one axis, <= 0 overlapping.
inline double separation(const std::array<Eigen::Vector2d, 4>& a, const Pose3& Xa,
                         const std::array<Eigen::Vector2d, 4>& b, const Pose3& Xb) {
  const Eigen::Vector2d axes[4] = {Xa.linear().col(0).head<2>(), Xa.linear().col(1).head<2>(),
                                   Xb.linear().col(0).head<2>(), Xb.linear().col(1).head<2>()};
  double best = -1e9;
  for (const auto& axis : axes) {
    double amin = 1e9, amax = -1e9, bmin = 1e9, bmax = -1e9;
    for (const auto& p : a) amin = std::min(amin, p.dot(axis)), amax = std::max(amax, p.dot(axis));
    for (const auto& p : b) bmin = std::min(bmin, p.dot(axis)), bmax = std::max(bmax, p.dot(axis));
    best = std::max(best, std::max(bmin - amax, amin - bmax));
  }
  return best;
}

/// Do two footprints overlap (touching counts as apart)?
inline bool overlaps(const std::array<Eigen::Vector2d, 4>& a, const Pose3& Xa, const std::array<Eigen::Vector2d, 4>& b,
                     const Pose3& Xb) {
  return separation(a, Xa, b, Xb) <= 0.0;
}

/// Half-width of a rectangle of `size` with yaw `yaw` along world direction d.
inline double support(const Eigen::Vector3d& size, double yaw, const Eigen::Vector2d& d) {
  const Eigen::Vector2d ax(std::cos(yaw), std::sin(yaw)), ay(-std::sin(yaw), std::cos(yaw));
  return std::abs(d.dot(ax)) * size.x() / 2 + std::abs(d.dot(ay)) * size.y() / 2;
}

inline double support(const CellObject& o, const Eigen::Vector2d& d) {
  return support(o.size_m, yawOfPose(o.X_world_object), d);
}

inline Eigen::Vector2d centre(const CellObject& o) { return o.X_world_object.translation().head<2>(); }

/// Vertical extents [bottom, top] overlap (1 mm slack: parts resting on each other touch).
inline bool verticalOverlap(const CellObject& a, double za, const CellObject& b) {
  const double zb = b.X_world_object.translation().z();
  return za < zb + b.size_m.z() - 1e-3 && zb < za + a.size_m.z() - 1e-3;
}

/// Smallest distance of the footprint of a box of `size` at X to `container`'s inner
/// walls (negative: over a wall).
inline double marginToInnerWalls(const Eigen::Vector3d& size, const Pose3& X, const CellObject& container) {
  const Pose3 X_c = container.X_world_object.inverse() * X;
  const double yc = yawOfPose(X_c);
  const double c = std::abs(std::cos(yc)), s = std::abs(std::sin(yc));
  const double ex = c * size.x() / 2 + s * size.y() / 2, ey = s * size.x() / 2 + c * size.y() / 2;
  return std::min(container.size_m.x() / 2 - container.wallThickness_m - std::abs(X_c.translation().x()) - ex,
                  container.size_m.y() / 2 - container.wallThickness_m - std::abs(X_c.translation().y()) - ey);
}

/// The suction tool comes down vertically onto the placed part's top, its axis through
/// the part's centre (TaskExecutor: grasped at the top's centre, a straight descent to
/// the release), so it passes level with `container`'s walls unless the part's top lies at
/// least `gap_m` above the walls' top. `bottom_z`: the placed part's bottom (world z); the
/// container stands upright with its origin at its bottom.
inline bool toolLevelWithWalls(const Eigen::Vector3d& partSize, double bottom_z, const CellObject& container,
                               double gap_m) {
  const double wallTop_z = container.X_world_object.translation().z() + container.size_m.z();
  return bottom_z + partSize.z() < wallTop_z + gap_m;
}

/// The distance a part of `partSize` resting at `bottom_z` keeps between its centre and
/// `container`'s walls: `toolClearance_m` (PlacementContext::Options::toolClearance_m) where the tool
/// comes level with them (within `levelGap_m`, PlacementContext::Options::minClearance_m), else 0.
inline double toolClearanceFrom(double toolClearance_m, double levelGap_m, const Eigen::Vector3d& partSize,
                                double bottom_z, const CellObject& container) {
  return toolLevelWithWalls(partSize, bottom_z, container, levelGap_m) ? toolClearance_m : 0.0;
}

/// Horizontal distance of p_world from `container`'s nearest wall: its inner walls when p
/// lies inside them, else its outer outline.
inline double distanceToWalls(const CellObject& container, const Eigen::Vector2d& p_world) {
  const Eigen::Vector3d p = container.X_world_object.inverse() * Eigen::Vector3d(p_world.x(), p_world.y(), 0.0);
  const double innerX = container.size_m.x() / 2 - container.wallThickness_m;
  const double innerY = container.size_m.y() / 2 - container.wallThickness_m;
  if (std::abs(p.x()) <= innerX && std::abs(p.y()) <= innerY)
    return std::min(innerX - std::abs(p.x()), innerY - std::abs(p.y()));
  const double dx = std::max(std::abs(p.x()) - container.size_m.x() / 2, 0.0);
  const double dy = std::max(std::abs(p.y()) - container.size_m.y() / 2, 0.0);
  return std::hypot(dx, dy);  // 0 on or in the wall itself
}

/// "12.5 mm" for 0.0125.
inline std::string fmt(double v_m) {
  std::ostringstream s;
  s.precision(1);
  s << std::fixed << v_m * 1000.0 << " mm";
  return s.str();
}

}  // namespace srp::execution::placement
