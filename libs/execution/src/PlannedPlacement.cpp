#include "srp/execution/PlannedPlacement.h"

namespace srp::execution {

CellDescription withPartAt(CellDescription scene, const std::string& name, const srp::core::Pose3& X_world_part) {
  for (auto& o : scene.objects)
    if (o.name == name) o.X_world_object = X_world_part;
  return scene;
}

CellDescription sceneAfterPlacements(const CellDescription& scene, const std::vector<PlannedPlacement>& steps) {
  CellDescription now = scene;
  for (const auto& s : steps)
    if (s.placement.X_world_object) now = withPartAt(now, s.part, *s.placement.X_world_object);
  return now;
}

}  // namespace srp::execution
