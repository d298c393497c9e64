#include "srp/perception/ObjectModel.h"

#include <cmath>
#include <filesystem>

#include "srp/core/Error.h"

namespace srp::perception {
namespace {

constexpr double kPi = 3.14159265358979323846;

/// Closed prism: a convex or star-shaped footprint polygon (CCW) extruded
/// from z0 to z1.
void addPrism(TriangleMesh& m, const std::vector<Eigen::Vector2d>& poly, double z0, double z1) {
  const int n = static_cast<int>(poly.size());
  const int base = static_cast<int>(m.vertices_m.size());
  for (const auto& p : poly) m.vertices_m.emplace_back(p.x(), p.y(), z0);
  for (const auto& p : poly) m.vertices_m.emplace_back(p.x(), p.y(), z1);
  // Caps fan out from the vertices' centroid (inside convex and star-shaped outlines).
  Eigen::Vector2d c = Eigen::Vector2d::Zero();
  for (const auto& p : poly) c += p / static_cast<double>(n);
  const int cBottom = static_cast<int>(m.vertices_m.size());
  m.vertices_m.emplace_back(c.x(), c.y(), z0);
  m.vertices_m.emplace_back(c.x(), c.y(), z1);
  for (int i = 0; i < n; ++i) {
    const int j = (i + 1) % n;
    m.triangles.emplace_back(cBottom, base + j, base + i);              // bottom, facing -z
    m.triangles.emplace_back(cBottom + 1, base + n + i, base + n + j);  // top, facing +z
    m.triangles.emplace_back(base + i, base + j, base + n + j);         // side
    m.triangles.emplace_back(base + i, base + n + j, base + n + i);
  }
}

/// Scales a polygon to span exactly size (x, y), centred on its bounding box.
std::vector<Eigen::Vector2d> fitToBox(std::vector<Eigen::Vector2d> poly, const Eigen::Vector2d& size) {
  Eigen::Vector2d lo = poly.front(), hi = poly.front();
  for (const auto& p : poly) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const Eigen::Vector2d centre = 0.5 * (lo + hi), scale = size.cwiseQuotient(hi - lo);
  for (auto& p : poly) p = (p - centre).cwiseProduct(scale);
  return poly;
}

std::vector<Eigen::Vector2d> rectangle(double sx, double sy, double cx = 0, double cy = 0) {
  return {{cx - sx / 2, cy - sy / 2}, {cx + sx / 2, cy - sy / 2}, {cx + sx / 2, cy + sy / 2}, {cx - sx / 2, cy + sy / 2}};
}

/// Yaw symmetry order n (2 pi / n maps the samples onto themselves).
int yawSymmetryOrder(const std::vector<SurfacePoint>& pts, double tol_m) {
  if (pts.empty()) return 1;
  // Centre on the samples' xy centroid of the bounding box.
  Eigen::AlignedBox3d box;
  for (const auto& s : pts) box.extend(s.p_m);
  const Eigen::Vector3d c = box.center();
  const std::size_t step = std::max<std::size_t>(1, pts.size() / 150);
  for (int n : {8, 6, 5, 4, 3, 2}) {
    const Eigen::Matrix3d R = Eigen::AngleAxisd(2 * kPi / n, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    bool ok = true;
    for (std::size_t i = 0; i < pts.size() && ok; i += step) {
      const Eigen::Vector3d q = R * (pts[i].p_m - c) + c;
      double best = 1e9;
      for (const auto& s : pts) best = std::min(best, (s.p_m - q).squaredNorm());
      ok = best < tol_m * tol_m;
    }
    if (ok) return n;
  }
  return 1;
}

}  // namespace

TriangleMesh ObjectModel::shapeMesh(const std::string& shape, const Eigen::Vector3d& d, double wall_m) {
  TriangleMesh m;
  const double h = d.z();
  if (shape == "cuboid" || shape == "box" || shape == "cube") {
    addPrism(m, rectangle(d.x(), d.y()), 0, h);
  } else if (shape == "octagon") {
    std::vector<Eigen::Vector2d> poly;
    const double r = 0.5 * d.x() / std::cos(kPi / 8);  // flat-to-flat = x size
    for (int i = 0; i < 8; ++i) poly.emplace_back(r * std::cos(kPi / 8 + i * kPi / 4), r * std::sin(kPi / 8 + i * kPi / 4));
    addPrism(m, poly, 0, h);
  } else if (shape == "cylinder") {
    std::vector<Eigen::Vector2d> poly;
    for (int i = 0; i < 32; ++i) poly.emplace_back(0.5 * d.x() * std::cos(i * kPi / 16), 0.5 * d.y() * std::sin(i * kPi / 16));
    addPrism(m, poly, 0, h);
  } else if (shape == "star") {
    // Five points, one along +x, inner radius half the outer, stretched to the box (as srp kb build).
    std::vector<Eigen::Vector2d> poly;
    for (int i = 0; i < 10; ++i) {
      const double r = (i % 2 == 0) ? 1.0 : 0.5;
      poly.emplace_back(r * std::cos(i * kPi / 5), r * std::sin(i * kPi / 5));
    }
    addPrism(m, fitToBox(poly, d.head<2>()), 0, h);
  } else if (shape == "parallelogram") {
    addPrism(m, fitToBox({{-1.0, -1.0}, {0.5, -1.0}, {1.0, 1.0}, {-0.5, 1.0}}, d.head<2>()), 0, h);
  } else if (shape == "open_box") {
    const double t = wall_m > 0 ? wall_m : 0.005;
    addPrism(m, rectangle(d.x(), d.y()), 0, t);  // floor
    addPrism(m, rectangle(d.x(), t, 0, -d.y() / 2 + t / 2), t, h);
    addPrism(m, rectangle(d.x(), t, 0, d.y() / 2 - t / 2), t, h);
    addPrism(m, rectangle(t, d.y() - 2 * t, -d.x() / 2 + t / 2, 0), t, h);
    addPrism(m, rectangle(t, d.y() - 2 * t, d.x() / 2 - t / 2, 0), t, h);
  } else {
    throw core::InvalidInputError("unknown catalogue shape '" + shape +
                                  "' (known: cuboid, star, parallelogram, octagon, open_box, cylinder); give the class a mesh");
  }
  return m;
}

ObjectModel ObjectModel::fromMesh(const std::string& name, const TriangleMesh& mesh,
                                  const Eigen::Isometry3d& X_object_mesh, double spacing_m) {
  ObjectModel model;
  model.name = name;
  const TriangleMesh m = mesh.transformed(X_object_mesh);
  model.dimensions_m = m.bounds().sizes();
  model.surface = m.sampleSurface(spacing_m);
  model.mesh = m;
  model.yawSymmetry_rad = 2 * kPi / yawSymmetryOrder(model.surface, 0.75 * spacing_m + 1e-3);
  return model;
}

ObjectModel ObjectModel::fromCatalogue(const core::ObjectClass& cls, double spacing_m) {
  TriangleMesh mesh;
  if (!cls.meshPath.empty() && std::filesystem::is_regular_file(cls.meshPath)) mesh = TriangleMesh::load(cls.meshPath);
  else mesh = shapeMesh(cls.shape, cls.dimensions_m, cls.wallThickness_m);
  ObjectModel model = fromMesh(cls.name, mesh, Eigen::Isometry3d::Identity(), spacing_m);
  model.classId = cls.classId;
  model.kind = cls.kind;
  model.rgb = cls.rgb;
  model.useColour = true;
  return model;
}

}  // namespace srp::perception
