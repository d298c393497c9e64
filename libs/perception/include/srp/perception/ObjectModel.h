#pragma once
/// \file ObjectModel.h
/// \brief What the object detector knows of one class, computed at start-up
/// from the CAD knowledge base only: surface samples, size, colour, symmetry.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "srp/core/ObjectCatalogue.h"
#include "srp/perception/TriangleMesh.h"

namespace srp::perception {

/// A rigid object class as a cloud of oriented surface samples in the
/// catalogue's object frame (origin at the centre of the bottom face, z up,
/// metres; see core/ObjectCatalogue.h).
struct ObjectModel {
  std::string name;
  int classId = -1;
  core::ObjectKind kind = core::ObjectKind::Part;
  Eigen::Vector3d dimensions_m = Eigen::Vector3d::Zero();  ///< bounding box in the object frame
  Eigen::Vector3d rgb = Eigen::Vector3d::Constant(0.5);   ///< catalogue colour (linear RGB, [0, 1])
  bool useColour = false;                                  ///< colour is known and discriminative
  std::vector<SurfacePoint> surface;                       ///< object frame
  TriangleMesh mesh;                                       ///< object frame (silhouettes)
  /// Smallest yaw (about object z) [rad] that maps the model onto itself
  /// (2 pi when none): a cube pi/2, a cuboid pi, a five-point star 2 pi/5.
  double yawSymmetry_rad = 2.0 * 3.14159265358979323846;

  /// From a CAD mesh whose frame is X_object_mesh away from the object frame
  /// (identity when the mesh is already bottom-centred, z up). Surface sampled
  /// every `spacing_m`; yaw symmetry found from the samples.
  static ObjectModel fromMesh(const std::string& name, const TriangleMesh& mesh,
                              const Eigen::Isometry3d& X_object_mesh, double spacing_m = 0.004);

  /// From a catalogue class: its mesh when the file exists, else the solid
  /// its `shape` and dimensions describe (cuboid, star, parallelogram,
  /// octagon, open_box, cylinder), which is what a camera sees of the part.
  static ObjectModel fromCatalogue(const core::ObjectClass& cls, double spacing_m = 0.004);

  /// The solid of a catalogue shape (object frame). Throws InvalidInputError
  /// naming the shape when it is unknown.
  static TriangleMesh shapeMesh(const std::string& shape, const Eigen::Vector3d& dimensions_m,
                                double wallThickness_m);
};

}  // namespace srp::perception
