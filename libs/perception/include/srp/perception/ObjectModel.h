#pragma once
/// \file ObjectModel.h
/// \brief What the object detector knows of one class, computed at start-up
/// from the CAD knowledge base only: surface samples, size, colour, symmetry.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "srp/core/ObjectCatalogue.h"
#include "srp/core/Pose.h"
#include "srp/kb/TriangleMesh.h"

namespace srp::perception {

/// A rigid object class as a cloud of oriented surface samples in its *model
/// frame*: origin at the centre of the bottom face of the mesh's bounding box,
/// z up (the mesh's z), metres; the frame in which the detector fits a part
/// standing on the support plane. For the generated catalogue shapes this is
/// the catalogue's object frame (their meshes are bottom-centred); a class
/// given by its CAD file alone keeps the file's own frame as its object frame,
/// `X_model_mesh` away (its +z is taken as up when the part rests on a table).
struct ObjectModel {
  std::string name;
  int classId = -1;
  core::ObjectKind kind = core::ObjectKind::Part;
  Eigen::Vector3d dimensions_m = Eigen::Vector3d::Zero();  ///< bounding box in the model frame
  Eigen::Vector3d rgb = Eigen::Vector3d::Constant(0.5);   ///< catalogue colour (linear RGB, [0, 1])
  bool useColour = false;                                  ///< colour is known and discriminative
  std::vector<kb::SurfacePoint> surface;                   ///< model frame
  kb::TriangleMesh mesh;                                   ///< model frame (silhouettes)
  /// The mesh file's (= the catalogue class's object) frame in the model
  /// frame: X_camera_mesh = X_camera_model * X_model_mesh. Identity for
  /// bottom-centred meshes.
  core::Pose3 X_model_mesh = core::Pose3::Identity();
  /// Smallest yaw (about model z) [rad] that maps the model onto itself
  /// (2 pi when none): a cube pi/2, a cuboid pi, a five-point star 2 pi/5.
  double yawSymmetry_rad = 2.0 * 3.14159265358979323846;

  /// From a CAD mesh in its own frame: moved to the model frame (bottom
  /// centre of its bounding box, X_model_mesh), surface sampled every
  /// `spacing_m`, yaw symmetry found from the samples.
  static ObjectModel fromMesh(const std::string& name, const kb::TriangleMesh& mesh_mesh, double spacing_m = 0.004);

  /// From a catalogue class: its mesh (kb::loadClassMesh: the file, or the
  /// solid its generator shape describes before `srp kb build`), its colour
  /// when the class has one.
  static ObjectModel fromCatalogue(const core::ObjectClass& cls, double spacing_m = 0.004);
};

}  // namespace srp::perception
