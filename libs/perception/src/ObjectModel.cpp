#include "srp/perception/ObjectModel.h"

#include <cmath>

#include "srp/core/Angles.h"
#include "srp/core/Error.h"
#include "srp/kb/KnowledgeBase.h"

namespace srp::perception {
namespace {

using core::kPi;

/// Yaw symmetry order n (2 pi / n maps the samples onto themselves).
int yawSymmetryOrder(const std::vector<kb::SurfacePoint>& pts, double tol_m) {
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

ObjectModel ObjectModel::fromMesh(const std::string& name, const kb::TriangleMesh& mesh_mesh, double spacing_m) {
  ObjectModel model;
  model.name = name;
  // Model frame: the bounding box's bottom-face centre (identity for the
  // generated, bottom-centred meshes).
  const Eigen::AlignedBox3d box = mesh_mesh.bounds();
  model.X_model_mesh.translation() = -Eigen::Vector3d(box.center().x(), box.center().y(), box.min().z());
  const kb::TriangleMesh m = mesh_mesh.transformed(model.X_model_mesh);
  model.dimensions_m = box.sizes();
  model.surface = m.sampleSurface(spacing_m);
  model.mesh = m;
  model.yawSymmetry_rad = 2 * kPi / yawSymmetryOrder(model.surface, 0.75 * spacing_m + 1e-3);
  return model;
}

ObjectModel ObjectModel::fromCatalogue(const core::ObjectClass& cls, double spacing_m) {
  ObjectModel model = fromMesh(cls.name, kb::loadClassMesh(cls), spacing_m);
  model.classId = cls.classId;
  model.kind = cls.kind;
  model.rgb = cls.rgb;
  model.useColour = cls.hasColour;
  return model;
}

}  // namespace srp::perception
