#include "srp/kb/ShapeMeshes.h"

#include <cmath>

#include "srp/core/Angles.h"
#include "srp/core/Error.h"

namespace srp::kb {
namespace {

using core::kPi;

// Scales and centres an outline so that its bounding box is exactly size_m.
std::vector<Eigen::Vector2d> fitToBox(std::vector<Eigen::Vector2d> polygon, const Eigen::Vector2d& size_m) {
  Eigen::Vector2d lo = polygon.front(), hi = polygon.front();
  for (const auto& p : polygon) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const Eigen::Vector2d centre = 0.5 * (lo + hi);
  const Eigen::Vector2d scale = size_m.cwiseQuotient(hi - lo);
  for (auto& p : polygon) p = (p - centre).cwiseProduct(scale);
  return polygon;
}

}  // namespace

TriangleMesh makeBoxMesh(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  const std::vector<Eigen::Vector2d> rect = {
      {lo.x(), lo.y()}, {hi.x(), lo.y()}, {hi.x(), hi.y()}, {lo.x(), hi.y()}};
  TriangleMesh mesh;
  // Caps and sides as in makePrismMesh, offset to lo.z.
  const Eigen::Vector3d dz(0, 0, lo.z());
  const double h = hi.z() - lo.z();
  const TriangleMesh prism = makePrismMesh(rect, h);
  for (const auto& t : prism.triangles()) mesh.addTriangle(t[0] + dz, t[1] + dz, t[2] + dz);
  return mesh;
}

TriangleMesh makePrismMesh(const std::vector<Eigen::Vector2d>& polygon, double height_m) {
  srp::core::require(polygon.size() >= 3, "makePrismMesh: a polygon needs at least 3 vertices");
  srp::core::require(height_m > 0.0, "makePrismMesh: height must be positive");
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
  for (const auto& p : polygon) centroid += p;
  centroid /= static_cast<double>(polygon.size());
  TriangleMesh mesh;
  const std::size_t n = polygon.size();
  const Eigen::Vector3d cBottom(centroid.x(), centroid.y(), 0.0), cTop(centroid.x(), centroid.y(), height_m);
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d& a = polygon[i];
    const Eigen::Vector2d& b = polygon[(i + 1) % n];
    const Eigen::Vector3d a0(a.x(), a.y(), 0.0), b0(b.x(), b.y(), 0.0);
    const Eigen::Vector3d a1(a.x(), a.y(), height_m), b1(b.x(), b.y(), height_m);
    mesh.addTriangle(cTop, a1, b1);        // top cap, normal +z
    mesh.addTriangle(cBottom, b0, a0);     // bottom cap, normal -z
    mesh.addQuad(a0, b0, b1, a1);          // side, outward for a CCW polygon
  }
  return mesh;
}

TriangleMesh makeOpenBoxMesh(const Eigen::Vector3d& d, double wall_m) {
  srp::core::require(wall_m > 0.0 && 2.0 * wall_m < d.x() && 2.0 * wall_m < d.y() && wall_m < d.z(),
                     "makeOpenBoxMesh: wall thickness must be positive and smaller than half the box");
  const double X = 0.5 * d.x(), Y = 0.5 * d.y(), H = d.z();
  const double x = X - wall_m, y = Y - wall_m, t = wall_m;
  TriangleMesh mesh;
  const std::vector<Eigen::Vector2d> outer = {{-X, -Y}, {X, -Y}, {X, Y}, {-X, Y}};
  const std::vector<Eigen::Vector2d> inner = {{-x, -y}, {x, -y}, {x, y}, {-x, y}};
  auto at = [](const Eigen::Vector2d& p, double z) { return Eigen::Vector3d(p.x(), p.y(), z); };
  // Bottom (normal -z) and inner floor (normal +z).
  mesh.addQuad(at(outer[0], 0), at(outer[3], 0), at(outer[2], 0), at(outer[1], 0));
  mesh.addQuad(at(inner[0], t), at(inner[1], t), at(inner[2], t), at(inner[3], t));
  for (int i = 0; i < 4; ++i) {
    const int j = (i + 1) % 4;
    mesh.addQuad(at(outer[i], 0), at(outer[j], 0), at(outer[j], H), at(outer[i], H));  // outer wall
    mesh.addQuad(at(inner[j], t), at(inner[i], t), at(inner[i], H), at(inner[j], H));  // inner wall, faces inwards
    mesh.addQuad(at(outer[i], H), at(outer[j], H), at(inner[j], H), at(inner[i], H));  // rim
  }
  return mesh;
}

std::vector<Eigen::Vector2d> shapeOutline(const std::string& shape, const Eigen::Vector2d& size_m) {
  std::vector<Eigen::Vector2d> p;
  if (shape == "star") {
    // Five points, one along +x; inner radius half the outer (a chunky, graspable star).
    for (int k = 0; k < 10; ++k) {
      const double r = (k % 2 == 0) ? 1.0 : 0.5;
      const double a = k * kPi / 5.0;
      p.emplace_back(r * std::cos(a), r * std::sin(a));
    }
  } else if (shape == "parallelogram") {
    p = {{-1.0, -1.0}, {0.5, -1.0}, {1.0, 1.0}, {-0.5, 1.0}};
  } else if (shape == "octagon") {
    for (int k = 0; k < 8; ++k) {
      const double a = kPi / 8.0 + k * kPi / 4.0;
      p.emplace_back(std::cos(a), std::sin(a));
    }
  } else if (shape == "cuboid") {
    p = {{-1.0, -1.0}, {1.0, -1.0}, {1.0, 1.0}, {-1.0, 1.0}};
  } else {
    throw srp::core::InvalidInputError("shapeOutline: unknown shape '" + shape +
                                       "' (known: cuboid, star, parallelogram, octagon, open_box, hull)");
  }
  return fitToBox(p, size_m);
}

TriangleMesh makeClassMesh(const srp::core::ObjectClass& c) {
  const std::string what = "class '" + c.name + "'";
  srp::core::require((c.dimensions_m.array() > 0.0).all(), what + ": dimensions_m must be positive");
  if (c.shape == "open_box") {
    srp::core::require(c.wallThickness_m > 0.0, what + ": shape open_box needs wall_thickness_m > 0");
    return makeOpenBoxMesh(c.dimensions_m, c.wallThickness_m);
  }
  if (c.shape == "cuboid") {
    const Eigen::Vector3d half(0.5 * c.dimensions_m.x(), 0.5 * c.dimensions_m.y(), 0.0);
    return makeBoxMesh(-half, half + Eigen::Vector3d(0, 0, c.dimensions_m.z()));
  }
  if (c.shape == "hull") {
    srp::core::require(c.footprint_object.size() >= 3, what + ": shape hull needs a footprint of at least 3 points");
    return makePrismMesh(c.footprint_object, c.dimensions_m.z());
  }
  try {
    return makePrismMesh(shapeOutline(c.shape, c.dimensions_m.head<2>()), c.dimensions_m.z());
  } catch (const srp::core::InvalidInputError& e) {
    throw srp::core::InvalidInputError(what + ": " + e.what());
  }
}

}  // namespace srp::kb
