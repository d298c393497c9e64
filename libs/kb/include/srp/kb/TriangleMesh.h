#pragma once
/// \file TriangleMesh.h
/// \brief A triangle soup in an object's frame: the CAD model of a part or
/// container, read from any CAD exchange format Assimp knows (STL, OBJ, PLY,
/// glTF, COLLADA, ...) and written as binary STL (`srp kb build`). The one
/// mesh type synth, perception and execution share.

#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace srp::kb {

/// Oriented surface sample: position [m] and outward unit normal, mesh frame.
struct SurfacePoint {
  Eigen::Vector3d p_m;
  Eigen::Vector3d n;
};

/// A triangle mesh as a list of triangles (vertices in metres, in the frame of
/// the object the mesh describes). Vertices are ordered counter-clockwise seen
/// from outside, so the right-hand normal points out of the solid (the STL
/// convention).
///
/// \code
///   srp::kb::TriangleMesh mesh = srp::kb::TriangleMesh::load("datasets/kb/meshes/star.stl");
///   Eigen::AlignedBox3d box = mesh.bounds();   // 0.05 x 0.05 x 0.025 m
///   auto samples = mesh.sampleSurface(0.004);  // oriented points for pose estimation
/// \endcode
class TriangleMesh {
 public:
  using Triangle = std::array<Eigen::Vector3d, 3>;

  /// Bounds on what load() reads, checked before the file is decoded where the
  /// format declares its counts (PLY element counts, binary STL triangle count:
  /// against the file's size), and while it is read.
  struct LoadOptions {
    std::uintmax_t maxFileBytes = 512ull << 20;  ///< larger files are refused unread
    std::size_t maxTriangles = 4'000'000;       ///< about 290 MB as doubles
  };

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

  /// Points on the surface on a barycentric grid of about `spacing_m`, with
  /// the face normal; every non-degenerate triangle gets at least one sample.
  std::vector<SurfacePoint> sampleSurface(double spacing_m) const;
  /// The mesh moved by X (p' = X p).
  TriangleMesh transformed(const Eigen::Isometry3d& X) const;

  /// Writes binary STL (float32, little-endian); throws FileError naming the path.
  void saveStl(const std::string& path, const std::string& header = "srp") const;
  /// Reads a CAD file through Assimp, the format by its content and extension
  /// (STL ASCII or binary, OBJ, PLY, glTF 2, COLLADA, ...): every mesh of the
  /// file's scene, placed by its node transforms, polygons triangulated;
  /// coordinates as stored (metres expected; COLLADA's up axis is not
  /// applied, so the object frame is the file's own). Throws FileError naming
  /// the path when it is missing, unreadable, truncated, has no triangles, has
  /// a non-finite (NaN, Inf) vertex, or breaks `options` (a header declaring more
  /// than the file can hold is refused before anything is allocated).
  static TriangleMesh load(const std::string& path, const LoadOptions& options);
  static TriangleMesh load(const std::string& path) { return load(path, LoadOptions{}); }

  /// The mesh with every coordinate multiplied by `factor` (a file in millimetres: 0.001).
  TriangleMesh scaled(double factor) const;

 private:
  std::vector<Triangle> triangles_;
};

}  // namespace srp::kb
