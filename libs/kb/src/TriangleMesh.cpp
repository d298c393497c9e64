#include "srp/kb/TriangleMesh.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <tuple>

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include "srp/core/Error.h"

namespace srp::kb {

void TriangleMesh::addTriangle(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                               const Eigen::Vector3d& c) {
  triangles_.push_back({a, b, c});
}

void TriangleMesh::addQuad(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                           const Eigen::Vector3d& c, const Eigen::Vector3d& d) {
  addTriangle(a, b, c);
  addTriangle(a, c, d);
}

void TriangleMesh::append(const TriangleMesh& other) {
  triangles_.insert(triangles_.end(), other.triangles_.begin(), other.triangles_.end());
}

Eigen::Vector3d TriangleMesh::normal(std::size_t i) const {
  const Triangle& t = triangles_.at(i);
  const Eigen::Vector3d n = (t[1] - t[0]).cross(t[2] - t[0]);
  const double len = n.norm();
  return len > 0.0 ? Eigen::Vector3d(n / len) : Eigen::Vector3d::Zero();
}

Eigen::AlignedBox3d TriangleMesh::bounds() const {
  Eigen::AlignedBox3d box;
  for (const Triangle& t : triangles_)
    for (const Eigen::Vector3d& v : t) box.extend(v);
  return box;
}

double TriangleMesh::volume() const {
  double sixV = 0.0;
  for (const Triangle& t : triangles_) sixV += t[0].dot(t[1].cross(t[2]));
  return sixV / 6.0;
}

bool TriangleMesh::isClosed(double tolerance_m) const {
  // Quantise vertices so that equal positions map to equal keys.
  const double q = tolerance_m > 0.0 ? tolerance_m : 1e-9;
  using Key = std::tuple<long long, long long, long long>;
  auto key = [q](const Eigen::Vector3d& v) {
    return Key{std::llround(v.x() / q), std::llround(v.y() / q), std::llround(v.z() / q)};
  };
  // Directed edge counts: a closed oriented surface has each directed edge once
  // and its reverse once.
  std::map<std::pair<Key, Key>, int> directed;
  for (const Triangle& t : triangles_)
    for (int k = 0; k < 3; ++k) ++directed[{key(t[k]), key(t[(k + 1) % 3])}];
  for (const auto& [edge, count] : directed) {
    if (count != 1) return false;
    const auto reverse = directed.find({edge.second, edge.first});
    if (reverse == directed.end() || reverse->second != 1) return false;
  }
  return !triangles_.empty();
}

// Binary STL: 80-byte header, uint32 count, per triangle 12 float32 (normal,
// three vertices) and a uint16 attribute. Little-endian (the host order here).
void TriangleMesh::saveStl(const std::string& path, const std::string& header) const {
  const std::filesystem::path p(path);
  if (p.has_parent_path()) {
    std::error_code ec;
    std::filesystem::create_directories(p.parent_path(), ec);
  }
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) throw srp::core::FileError(path, "cannot open for writing");
  char head[80] = {};
  std::strncpy(head, header.c_str(), sizeof(head) - 1);
  out.write(head, sizeof(head));
  const auto count = static_cast<std::uint32_t>(triangles_.size());
  out.write(reinterpret_cast<const char*>(&count), sizeof(count));
  for (std::size_t i = 0; i < triangles_.size(); ++i) {
    float record[12];
    const Eigen::Vector3d n = normal(i);
    for (int k = 0; k < 3; ++k) record[k] = static_cast<float>(n[k]);
    for (int v = 0; v < 3; ++v)
      for (int k = 0; k < 3; ++k) record[3 + 3 * v + k] = static_cast<float>(triangles_[i][v][k]);
    out.write(reinterpret_cast<const char*>(record), sizeof(record));
    const std::uint16_t attribute = 0;
    out.write(reinterpret_cast<const char*>(&attribute), sizeof(attribute));
  }
  if (!out) throw srp::core::FileError(path, "write failed");
}

TriangleMesh TriangleMesh::load(const std::string& path) {
  if (!std::filesystem::is_regular_file(path))
    throw srp::core::FileError(path, "mesh file not found (a catalogue's \"mesh\" is relative to the catalogue file; "
                                     "run `srp kb build` to generate the bundled ones)");
  Assimp::Importer importer;
  // The object frame is the file's own: no up-axis conversion.
  importer.SetPropertyBool(AI_CONFIG_IMPORT_COLLADA_IGNORE_UP_DIRECTION, true);
  // Whole faces only: points and lines are no surface.
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE, aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  const aiScene* scene = importer.ReadFile(path, aiProcess_Triangulate | aiProcess_PreTransformVertices |
                                                     aiProcess_SortByPType | aiProcess_FindDegenerates);
  if (!scene || (scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE))
    throw srp::core::FileError(path, std::string("cannot read the mesh (") + importer.GetErrorString() +
                                         "); give an STL, OBJ, PLY, glTF or COLLADA file");
  TriangleMesh mesh;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh* am = scene->mMeshes[m];
    for (unsigned f = 0; f < am->mNumFaces; ++f) {
      const aiFace& face = am->mFaces[f];
      if (face.mNumIndices != 3) continue;
      Triangle t;
      for (int k = 0; k < 3; ++k) {
        const aiVector3D& v = am->mVertices[face.mIndices[k]];
        t[k] = Eigen::Vector3d(v.x, v.y, v.z);
      }
      mesh.triangles_.push_back(t);
    }
  }
  if (mesh.triangles_.empty()) throw srp::core::FileError(path, "the mesh file holds no triangles");
  return mesh;
}

std::vector<SurfacePoint> TriangleMesh::sampleSurface(double spacing_m) const {
  std::vector<SurfacePoint> out;
  for (const Triangle& t : triangles_) {
    const Eigen::Vector3d &a = t[0], &b = t[1], &c = t[2];
    Eigen::Vector3d n = (b - a).cross(c - a);
    const double area2 = n.norm();
    if (area2 < 1e-14) continue;
    n /= area2;
    // Barycentric grid: steps along the two edges from a.
    const int steps = std::max(1, static_cast<int>(std::ceil(std::max((b - a).norm(), (c - a).norm()) / spacing_m)));
    bool any = false;
    for (int i = 0; i <= steps; ++i)
      for (int j = 0; i + j <= steps; ++j) {
        const double s = (i + 1.0 / 3.0) / (steps + 1.0), r = (j + 1.0 / 3.0) / (steps + 1.0);
        if (s + r > 1.0) continue;
        out.push_back({a + s * (b - a) + r * (c - a), n});
        any = true;
      }
    if (!any) out.push_back({(a + b + c) / 3.0, n});
  }
  return out;
}

TriangleMesh TriangleMesh::transformed(const Eigen::Isometry3d& X) const {
  TriangleMesh m = *this;
  for (Triangle& t : m.triangles_)
    for (Eigen::Vector3d& v : t) v = X * v;
  return m;
}

}  // namespace srp::kb
