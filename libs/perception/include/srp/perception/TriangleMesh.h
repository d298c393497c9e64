#pragma once
/// \file TriangleMesh.h
/// \brief A CAD model as a triangle mesh (OBJ or STL), and points sampled on
/// its surface for model-based pose estimation.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <string>
#include <vector>

namespace srp::perception {

/// Oriented surface sample: position and outward unit normal, model frame [m].
struct SurfacePoint {
  Eigen::Vector3d p_m;
  Eigen::Vector3d n;
};

/// Triangles in the model's own frame, metres. Faces wound counter-clockwise
/// seen from outside (as OBJ/STL exporters write them).
class TriangleMesh {
 public:
  std::vector<Eigen::Vector3d> vertices_m;
  std::vector<Eigen::Vector3i> triangles;

  /// Reads Wavefront OBJ (v/f; polygons fan-triangulated) or STL (ASCII or
  /// binary), by extension. Throws FileError naming the file when it is
  /// missing, unreadable or has no triangles.
  static TriangleMesh load(const std::string& path);

  /// Axis-aligned bounds of the vertices.
  Eigen::AlignedBox3d bounds() const;

  /// Points on the surface on a grid of about `spacing_m`, with the face
  /// normal; every triangle gets at least its centroid.
  std::vector<SurfacePoint> sampleSurface(double spacing_m) const;

  /// Returns the mesh moved by X (p' = X p).
  TriangleMesh transformed(const Eigen::Isometry3d& X) const;
};

}  // namespace srp::perception
