#include "srp/kb/TriangleMesh.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <tuple>

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

TriangleMesh TriangleMesh::loadStl(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw srp::core::FileError(path, "cannot open STL mesh (run `srp kb build` to generate the bundled ones)");
  char head[80];
  std::uint32_t count = 0;
  in.read(head, sizeof(head));
  in.read(reinterpret_cast<char*>(&count), sizeof(count));
  if (!in) throw srp::core::FileError(path, "not a binary STL file (shorter than its 84-byte header)");
  in.seekg(0, std::ios::end);
  const auto size = static_cast<std::uint64_t>(in.tellg());
  if (size != 84ull + 50ull * count)
    throw srp::core::FileError(path, "not a binary STL file: " + std::to_string(count) +
                                         " triangles need " + std::to_string(84ull + 50ull * count) +
                                         " bytes, the file has " + std::to_string(size) +
                                         " (ASCII STL is not supported)");
  in.seekg(84);
  TriangleMesh mesh;
  mesh.triangles_.reserve(count);
  for (std::uint32_t i = 0; i < count; ++i) {
    float record[12];
    std::uint16_t attribute = 0;
    in.read(reinterpret_cast<char*>(record), sizeof(record));
    in.read(reinterpret_cast<char*>(&attribute), sizeof(attribute));
    Triangle t;
    for (int v = 0; v < 3; ++v)
      t[v] = Eigen::Vector3d(record[3 + 3 * v], record[4 + 3 * v], record[5 + 3 * v]);
    mesh.triangles_.push_back(t);
  }
  if (!in) throw srp::core::FileError(path, "truncated STL file");
  return mesh;
}

}  // namespace srp::kb
