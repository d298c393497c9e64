#include "srp/core/DefaultScene.h"
#include "srp/execution/CellDescription.h"
#include "srp/kb/KnowledgeBase.h"

#include <algorithm>
#include <cmath>

namespace srp::execution {

bool isInside(const CellObject& part, const CellObject& container) {
  const Eigen::Vector3d p = container.X_world_object.inverse() * part.X_world_object.translation();
  return std::abs(p.x()) <= container.size_m.x() / 2 - container.wallThickness_m &&
         std::abs(p.y()) <= container.size_m.y() / 2 - container.wallThickness_m;
}

double WorldBox::signedDistance(const Eigen::Vector3d& p_world_m) const {
  const Eigen::Vector3d p = X_world_box.inverse() * p_world_m;
  const Eigen::Vector3d d = p.cwiseAbs() - halfExtents_m;
  const double outside = d.cwiseMax(0.0).norm();
  const double inside = std::min(d.maxCoeff(), 0.0);
  return outside + inside;
}

srp::core::ViewFrame CellDescription::viewFrame(srp::core::Viewpoint viewpoint) const {
  if (viewpoint == srp::core::Viewpoint::Demonstrator && X_world_camera)
    return srp::core::ViewFrame::fromCamera(*X_world_camera);
  return srp::core::ViewFrame::fromRobot(X_world_base, tableCentre_m);
}

const CellObject* CellDescription::find(const std::string& name) const {
  for (const auto& o : objects)
    if (o.name == name) return &o;
  return nullptr;
}

std::vector<WorldBox> CellDescription::containerBoxes(const CellObject& c) {
  const double t = c.wallThickness_m;
  const Eigen::Vector3d s = c.size_m;
  auto box = [&](const Eigen::Vector3d& centre, const Eigen::Vector3d& half) {
    WorldBox b;
    b.owner = c.name;
    b.X_world_box = srp::core::Pose3::Identity();
    b.X_world_box.translation() = centre;
    b.halfExtents_m = half;
    return b;
  };
  return {box({0, 0, t / 2}, {s.x() / 2, s.y() / 2, t / 2}),
          box({s.x() / 2 - t / 2, 0, s.z() / 2}, {t / 2, s.y() / 2, s.z() / 2}),
          box({-s.x() / 2 + t / 2, 0, s.z() / 2}, {t / 2, s.y() / 2, s.z() / 2}),
          box({0, s.y() / 2 - t / 2, s.z() / 2}, {s.x() / 2, t / 2, s.z() / 2}),
          box({0, -s.y() / 2 + t / 2, s.z() / 2}, {s.x() / 2, t / 2, s.z() / 2})};
}

CellDescription CellDescription::fromScene(const srp::core::Scene& scene,
                                           const srp::core::ObjectCatalogue& base) {
  scene.validate(base);
  const srp::core::ObjectCatalogue catalogue = scene.withObservedClasses(base);
  CellDescription cell;
  cell.X_world_base = scene.X_world_base;
  cell.X_world_camera = scene.X_world_camera;
  cell.tableHalfExtents_m = scene.tableSize_m / 2;
  cell.tableCentre_m.setZero();
  for (const auto& so : scene.objects) {
    const srp::core::ObjectClass& c = catalogue.at(so.className);
    CellObject o;
    o.name = so.id;
    o.kind = c.kind == srp::core::ObjectKind::Container ? CellObjectKind::Container : CellObjectKind::Part;
    o.size_m = c.dimensions_m;
    o.mass_kg = c.mass_kg;
    o.wallThickness_m = c.wallThickness_m;
    o.X_world_object = so.X_world_object;
    o.rgb = srp::core::instanceRgb(so, c);
    o.colour = srp::core::instanceColour(so, c);
    o.className = c.name;
    o.noun = c.noun;
    o.classId = c.classId;
    o.meshPath = c.meshPath;
    o.meshScale = c.meshScale;
    if (c.observed) o.observedClass = c;
    cell.objects.push_back(o);
  }
  return cell;
}

CellDescription CellDescription::loadScene(const std::string& scenePath) {
  const srp::core::Scene scene =
      srp::core::Scene::load(scenePath.empty() ? srp::core::defaultScenePath() : scenePath);
  return fromScene(scene, srp::kb::loadCatalogue(scene.cataloguePath));
}

std::vector<WorldBox> CellDescription::staticBoxes() const {
  constexpr double kTableThickness_m = 0.05;
  std::vector<WorldBox> boxes;
  WorldBox table;
  table.owner = "table";
  table.X_world_box.translation() = Eigen::Vector3d(tableCentre_m.x(), tableCentre_m.y(), -kTableThickness_m / 2);
  table.halfExtents_m = Eigen::Vector3d(tableHalfExtents_m.x(), tableHalfExtents_m.y(), kTableThickness_m / 2);
  boxes.push_back(table);
  for (const auto& o : objects) {
    if (o.kind != CellObjectKind::Container) continue;
    for (WorldBox b : containerBoxes(o)) {
      b.X_world_box = o.X_world_object * b.X_world_box;
      boxes.push_back(b);
    }
  }
  return boxes;
}

double CellDescription::carryHeight_m(double clearance_m) const {
  double wallTop_m = 0.0, tallestPart_m = 0.0;
  for (const auto& box : staticBoxes()) {
    if (box.owner == "table") continue;
    const Eigen::Vector3d up = box.X_world_box.linear().transpose().col(2);  // world z in the box frame
    wallTop_m = std::max(wallTop_m, box.X_world_box.translation().z() + up.cwiseAbs().dot(box.halfExtents_m));
  }
  for (const auto& o : objects)
    if (o.kind == CellObjectKind::Part) tallestPart_m = std::max(tallestPart_m, o.size_m.z());
  return wallTop_m > 0.0 ? wallTop_m + tallestPart_m + clearance_m : 0.0;
}

}  // namespace srp::execution
