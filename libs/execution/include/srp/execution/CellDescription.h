#pragma once
/// \file CellDescription.h
/// \brief What is in the simulated cell besides the arm: the table, the containers
/// and the parts, as box-shaped collision geometry.
///
/// Frames: `world` is the table frame (origin on the table top, z up), as in the
/// scene files. An object's frame has its origin at the centre of its bottom face,
/// z up; `size_m` is its bounding box (x, y, z) in that frame. A container is an
/// open box of outer size `size_m` with walls and floor `wallThickness_m` thick.

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "srp/core/ObjectCatalogue.h"
#include "srp/core/Pose.h"
#include "srp/core/Scene.h"
#include "srp/core/ViewFrame.h"

namespace srp::execution {

enum class CellObjectKind { Part, Container };

struct CellObject {
  std::string name;  ///< instance id from the scene, used by the planner ("cuboid", "gray box", "cuboid_red")
  CellObjectKind kind = CellObjectKind::Part;
  Eigen::Vector3d size_m = Eigen::Vector3d::Constant(0.04);
  double mass_kg = 0.05;
  double wallThickness_m = 0.006;  ///< containers only
  srp::core::Pose3 X_world_object = srp::core::Pose3::Identity();
  Eigen::Vector3d rgb = Eigen::Vector3d(0.8, 0.5, 0.2);  ///< colour in [0, 1] for rendering
  std::string colour;  ///< colour word of this instance (the scene's, else its class'), "" if none
  std::string className;  ///< knowledge-base class ("blue box"), "" if unknown
  std::string noun;       ///< head noun in instructions ("box"), "" if unknown
  int classId = -1;       ///< knowledge-base class id
  std::string meshPath;   ///< the class's mesh (object frame, metres) for rendering; "" or missing: drawn as its box
  double meshScale = 1.0; ///< metres per unit of the mesh file (ObjectClass::meshScale)
  /// The class of a part or container seen in a demonstration without a CAD
  /// file (ObjectClass::observed: shape "hull" or "open_box"), carried by the
  /// scene: it is simulated as its box (`size_m`) and rendered as its generated
  /// mesh (kb::makeClassMesh). nullopt for a catalogue class.
  std::optional<srp::core::ObjectClass> observedClass;
};

/// True when the footprint centre of `part` lies inside `container`'s inner walls (x, y in
/// the container's frame; the height is not looked at).
bool isInside(const CellObject& part, const CellObject& container);

/// An oriented box (centre pose and half extents) in the world frame.
struct WorldBox {
  std::string owner;  ///< object name ("table", "gray box")
  srp::core::Pose3 X_world_box = srp::core::Pose3::Identity();
  Eigen::Vector3d halfExtents_m = Eigen::Vector3d::Zero();
  /// Distance [m] from p to the box surface, negative inside.
  double signedDistance(const Eigen::Vector3d& p_world_m) const;
};

struct CellDescription {
  srp::core::Pose3 X_world_base = srp::core::Pose3::Identity();  ///< robot base in the table frame
  Eigen::Vector2d tableHalfExtents_m = Eigen::Vector2d(1.0, 0.8);
  Eigen::Vector2d tableCentre_m = Eigen::Vector2d::Zero();
  /// The demonstrator's camera (from the scene file), which fixes left/right/front/behind
  /// and "the second cube" (srp/core/ViewFrame.h); nullopt when the cell was not built
  /// from a scene: the robot's view is used.
  std::optional<srp::core::Pose3> X_world_camera;
  std::vector<CellObject> objects;

  /// The view frame of this cell for `viewpoint`: the camera's (Demonstrator, when the
  /// cell has a camera) or the robot's, from the base looking at the table centre.
  /// Grounding and placement both read left/right/front/behind in it.
  srp::core::ViewFrame viewFrame(srp::core::Viewpoint viewpoint) const;

  /// The object called `name`, nullptr if absent.
  const CellObject* find(const std::string& name) const;

  /// The fixed collision boxes: the table slab (top face at z = 0) and every container's
  /// floor and four walls.
  std::vector<WorldBox> staticBoxes() const;

  /// The tcp height [m, world z] at which a Move crosses between places: the top
  /// of the highest container wall (its boxes' highest corner) + the tallest part
  /// (a part is held at its top) + `clearance_m`, so that any part carried clears
  /// any wall by `clearance_m`; 0 when the cell has no container.
  double carryHeight_m(double clearance_m = kCarriedAboveWalls_m) const;
  static constexpr double kCarriedAboveWalls_m = 0.02;

  /// Floor and walls of one container, in its own object frame (centre pose, half extents).
  static std::vector<WorldBox> containerBoxes(const CellObject& container);

  /// The cell of a scene file: robot base, table and every object with its
  /// class (kind, size, wall, mass, colour) from the catalogue or the scene's
  /// own observed classes (Scene::observedClasses). Throws InvalidInputError
  /// (from Scene::validate) naming an object whose class is unknown.
  static CellDescription fromScene(const srp::core::Scene& scene, const srp::core::ObjectCatalogue& catalogue);

  /// fromScene() of a scene file with the catalogue it names; "" = sim/scenes/default.json.
  static CellDescription loadScene(const std::string& scenePath = "");
};

}  // namespace srp::execution
