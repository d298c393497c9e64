#include "srp/execution/DemonstrationScene.h"

#include <cmath>
#include <cstdio>
#include <limits>

#include "srp/core/Error.h"

namespace srp::execution {

namespace {
// The camera's foot point must be this far from the table centre to say which
// edge is opposite it; nearer (a camera straight above), the image's bottom
// edge decides.
constexpr double kMinCameraOffset_m = 0.05;
}  // namespace

srp::core::Pose3 defaultRobotBase(const taskdb::PerceivedScene& scene) {
  const Eigen::Vector2d foot = scene.X_table_camera.translation().head<2>();
  Eigen::Vector2d away = -foot;  // from the centre, away from the camera
  if (foot.norm() < kMinCameraOffset_m) {
    away = scene.X_table_camera.linear().col(1).head<2>();  // the image's y axis (down) on the table
    if (away.norm() < 1e-9) away = -Eigen::Vector2d::UnitY();
  }
  away.normalize();
  const Eigen::Vector2d half = scene.tableSize_m / 2;
  double toEdge = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 2; ++k)
    if (std::abs(away[k]) > 1e-12) toEdge = std::min(toEdge, half[k] / std::abs(away[k]));
  const Eigen::Vector2d p = std::max(0.0, toEdge - kDefaultBaseInset_m) * away;
  srp::core::Pose3 X = srp::core::Pose3::Identity();
  X.linear() = Eigen::AngleAxisd(std::atan2(-away.y(), -away.x()), Eigen::Vector3d::UnitZ()).toRotationMatrix();
  X.translation() = Eigen::Vector3d(p.x(), p.y(), 0.0);
  return X;
}

RobotPlacement RobotPlacement::of(const taskdb::PerceivedScene& scene,
                                  const std::optional<srp::core::Pose3>& X_base_camera, const std::string& source) {
  RobotPlacement r;
  if (X_base_camera) {
    r.X_world_base = scene.X_table_camera * X_base_camera->inverse();
    r.isDefault = false;
    r.description = "from the camera-to-robot calibration" + (source.empty() ? std::string() : " " + source);
    return r;
  }
  r.X_world_base = defaultRobotBase(scene);
  const Eigen::Vector3d t = r.X_world_base.translation();
  char where[96];
  std::snprintf(where, sizeof where, " (%.3f, %.3f) m in the table frame", t.x(), t.y());
  r.description = std::string("default placement at the table edge opposite the camera") + where +
                  " (no camera-to-robot calibration: give --extrinsics calib/extrinsics.json)";
  return r;
}

srp::core::Scene demonstrationScene(const taskdb::PerceivedScene& p, const RobotPlacement& placement,
                                    srp::core::Scene s) {
  s.cataloguePath = p.catalogue;
  s.tableSize_m = p.tableSize_m;
  s.X_world_camera = p.X_table_camera;
  s.X_world_base = placement.X_world_base;
  s.objects.clear();
  for (const auto& o : p.objects) {
    srp::core::SceneObject so;
    so.id = o.objectId;
    so.className = o.className;
    so.X_world_object = o.X_table_object;
    if (o.colour) so.colour = *o.colour;
    so.rgb = o.rgb;
    s.objects.push_back(so);
  }
  s.observedClasses = p.observedClasses;
  return s;
}

srp::core::Scene demonstrationScene(const taskdb::TaskModel& model, const RobotPlacement& placement) {
  if (!model.scene)
    throw srp::core::InvalidInputError(
        "task model " + std::to_string(model.info.id) + " ('" + model.info.name +
        "') stores no perceived scene (programmed by an older srp, or its demonstration showed no table plane); "
        "give the scene to execute in with --scene FILE");
  srp::core::Scene s;
  s.name = "demonstration of task model " + std::to_string(model.info.id);  // a usable scene name (Scene.h)
  if (model.info.intrinsics) s.intrinsics = *model.info.intrinsics;
  s.fps = model.info.frameRate_hz;
  return demonstrationScene(*model.scene, placement, s);
}

}  // namespace srp::execution
