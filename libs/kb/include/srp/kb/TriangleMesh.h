#pragma once
/// \file TriangleMesh.h
/// \brief A triangle soup in an object's frame, read from and written to
/// binary STL: the CAD model format of the knowledge base.

#include <Eigen/Geometry>
#include <array>
#include <string>
#include <vector>

namespace srp::kb {

/// A triangle mesh as a list of triangles (vertices in metres, in the frame of
/// the object the mesh describes). Vertices are ordered counter-clockwise seen
/// from outside, so the right-hand normal points out of the solid (the STL
/// convention).
///
/// \code
///   srp::kb::TriangleMesh mesh = srp::kb::TriangleMesh::loadStl("datasets/kb/meshes/star.stl");
///   Eigen::AlignedBox3d box = mesh.bounds();   // 0.05 x 0.05 x 0.025 m
/// \endcode
class TriangleMesh {
 public:
  using Triangle = std::array<Eigen::Vector3d, 3>;

  TriangleMesh() = default;
  explicit TriangleMesh(std::vector<Triangle> triangles) : triangles_(std::move(triangles)) {}

  const std::vector<Triangle>& triangles() const { return triangles_; }
  std::size_t size() const { return triangles_.size(); }
  bool empty() const { return triangles_.empty(); }

  void addTriangle(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c);
  /// Adds the planar convex-or-star-shaped quad a b c d (counter-clockwise) as two triangles.
  void addQuad(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
               const Eigen::Vector3d& d);
  void append(const TriangleMesh& other);

  /// Unit outward normal of triangle i (zero for a degenerate triangle).
  Eigen::Vector3d normal(std::size_t i) const;
  /// Axis-aligned bounding box of all vertices [m].
  Eigen::AlignedBox3d bounds() const;
  /// Enclosed volume [m^3] by the divergence theorem (meaningful for closed meshes).
  double volume() const;
  /// True when every edge is shared by exactly two triangles in opposite
  /// directions (a closed, consistently oriented surface), comparing vertices
  /// to within `tolerance_m`.
  bool isClosed(double tolerance_m = 1e-9) const;

  /// Writes binary STL (float32, little-endian); throws FileError naming the path.
  void saveStl(const std::string& path, const std::string& header = "srp") const;
  /// Reads binary STL; throws FileError naming the path when missing, truncated
  /// or ASCII.
  static TriangleMesh loadStl(const std::string& path);

 private:
  std::vector<Triangle> triangles_;
};

}  // namespace srp::kb
