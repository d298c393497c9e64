#pragma once
/// \file ObjectCatalogue.h
/// \brief The knowledge base of object classes (thesis ch. 6.3): what the robot
/// can recognise and handle, read from `datasets/kb/catalogue.json`.
///
/// Object frame of every class: origin at the centre of the bottom face of the
/// bounding box, z up (so an object resting on a surface at height h has its
/// origin at z = h), x along the longest horizontal side. Metres, kilograms.
/// A user adds a part by adding a mesh and a catalogue entry; a class given by
/// its CAD file alone (no "shape") has the mesh file's own frame as its
/// object frame, and its size and mass come from the mesh (kb::loadCatalogue):
/// `{"name": "cube", "class_id": 0, "noun": "cube", "kind": "part", "mesh": "cube.obj"}`.
///
/// \code{.json}
/// {"schema_version": 1,
///  "classes": [{"name": "blue box", "class_id": 1, "noun": "box", "color_name": "blue",
///               "kind": "container", "rgb": [0.15, 0.3, 0.8], "dimensions_m": [0.2, 0.16, 0.06],
///               "wall_thickness_m": 0.005, "mass_kg": 0.3, "mesh": "meshes/blue_box.stl",
///               "grasp_axis": [0, 1, 0], "shape": "open_box"}]}
/// \endcode
///
/// Generator shapes: "cuboid" (a box), "star", "parallelogram", "octagon",
/// "open_box" (a container: floor and walls of wall_thickness_m), and "hull", a
/// prism over an explicit convex footprint ("footprint_m"), which is how a part
/// seen in a demonstration without a CAD file is modelled.

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

namespace srp::core {

enum class ObjectKind { Part, Container };

/// One class of the knowledge base.
struct ObjectClass {
  std::string name;        ///< unique, e.g. "cuboid", "blue box"
  int classId = -1;        ///< as in the task database (Appendix C: 0 gray box, 1 blue box, ...)
  std::string noun;        ///< head noun in instructions, e.g. "box" for "blue box"
  std::string colourName;   ///< e.g. "blue"; empty when the colour does not identify it
  ObjectKind kind = ObjectKind::Part;
  std::string shape;       ///< generator shape: "cuboid", "star", "parallelogram", "octagon", "open_box", ...; empty: the mesh file alone
  Eigen::Vector3d rgb = Eigen::Vector3d::Constant(0.5);      ///< linear RGB in [0, 1]
  bool hasColour = true;   ///< false: the entry gave no "rgb" (e.g. a mesh-only class, a box added without --rgb); `rgb` is then a neutral grey
  Eigen::Vector3d dimensions_m = Eigen::Vector3d::Zero();   ///< bounding box x, y, z; zero for a mesh-only class until kb::loadCatalogue measures it
  double wallThickness_m = 0.0;                             ///< containers only
  double mass_kg = 0.0;    ///< zero for a mesh-only class without "mass_kg" until kb::loadCatalogue estimates it
  std::string meshPath;    ///< absolute (resolved against the catalogue's folder); may not exist yet
  double meshScale = 1.0;  ///< metres per unit of the mesh file (JSON "mesh_scale"; 0.001: drawn in millimetres)
  bool flat = false;       ///< a flat part (a sheet, a label) whose mesh encloses no volume (JSON "flat")
  Eigen::Vector3d graspAxis_object = Eigen::Vector3d::UnitY();  ///< gripper closing direction
  /// Footprint of shape "hull" (a prism from z = 0 to dimensions_m.z()):
  /// convex polygon in the object frame, counter-clockwise, metres, inside the
  /// x/y extent of dimensions_m. JSON "footprint_m": [[x, y], ...]. Empty for
  /// every other shape.
  std::vector<Eigen::Vector2d> footprint_object;
  /// True for a class built from what a demonstration showed (no CAD file):
  /// shape "hull" for a part, "open_box" for a container, measured from the
  /// observed points; it lives in the task model that observed it, not in the
  /// catalogue file. JSON "observed": true.
  bool observed = false;
};

/// The catalogue: classes by name and id. A catalogue file is read by
/// kb::loadCatalogue (the one loader: it checks every field and measures the
/// classes given by their mesh alone).
class ObjectCatalogue {
 public:
  ObjectCatalogue() = default;
  explicit ObjectCatalogue(std::vector<ObjectClass> classes);

  /// The shipped catalogue, `datasets/kb/catalogue.json` of srp's data folder
  /// (DataPaths). Throws FileError when it is not there.
  static std::string defaultPath();

  const std::vector<ObjectClass>& classes() const { return classes_; }
  const ObjectClass* find(const std::string& name) const;
  const ObjectClass* findById(int classId) const;
  /// Grounds an instruction's noun phrase: exact name, then noun + colour, then
  /// noun alone when exactly one class has it. nullptr when nothing fits.
  const ObjectClass* ground(const std::string& noun, const std::string& colour = "") const;
  /// Like find() but throws InvalidInputError listing the known names.
  const ObjectClass& at(const std::string& name) const;

 private:
  std::vector<ObjectClass> classes_;
};

std::string toString(ObjectKind kind);

}  // namespace srp::core
