#include "srp/perception/TriangleMesh.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "srp/core/Error.h"

namespace srp::perception {
namespace {

std::string lowerExtension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

TriangleMesh loadObj(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw core::FileError(path, "cannot open OBJ mesh");
  TriangleMesh mesh;
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream ls(line);
    std::string tag;
    ls >> tag;
    if (tag == "v") {
      Eigen::Vector3d v;
      ls >> v.x() >> v.y() >> v.z();
      if (!ls) throw core::FileError(path, "bad vertex line: '" + line + "'");
      mesh.vertices_m.push_back(v);
    } else if (tag == "f") {
      std::vector<int> idx;
      std::string tok;
      while (ls >> tok) {
        int i = std::stoi(tok.substr(0, tok.find('/')));
        if (i < 0) i = static_cast<int>(mesh.vertices_m.size()) + i + 1;  // relative index
        idx.push_back(i - 1);
      }
      for (std::size_t k = 2; k < idx.size(); ++k) mesh.triangles.emplace_back(idx[0], idx[k - 1], idx[k]);
    }
  }
  for (const auto& t : mesh.triangles)
    for (int c = 0; c < 3; ++c)
      if (t[c] < 0 || t[c] >= static_cast<int>(mesh.vertices_m.size()))
        throw core::FileError(path, "face refers to a vertex that does not exist");
  return mesh;
}

TriangleMesh loadStl(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw core::FileError(path, "cannot open STL mesh");
  std::string data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  TriangleMesh mesh;
  auto addTriangle = [&mesh](const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
    const int base = static_cast<int>(mesh.vertices_m.size());
    mesh.vertices_m.insert(mesh.vertices_m.end(), {a, b, c});
    mesh.triangles.emplace_back(base, base + 1, base + 2);
  };
  bool binary = data.size() >= 84;
  if (binary) {
    std::uint32_t n = 0;
    std::memcpy(&n, data.data() + 80, 4);
    binary = data.size() == 84 + static_cast<std::size_t>(n) * 50;
    if (binary) {
      for (std::uint32_t i = 0; i < n; ++i) {
        const char* rec = data.data() + 84 + i * 50 + 12;
        float f[9];
        std::memcpy(f, rec, sizeof(f));
        addTriangle({f[0], f[1], f[2]}, {f[3], f[4], f[5]}, {f[6], f[7], f[8]});
      }
    }
  }
  if (!binary) {
    std::istringstream ss(data);
    std::string tok;
    std::vector<Eigen::Vector3d> corners;
    while (ss >> tok) {
      if (tok == "vertex") {
        Eigen::Vector3d v;
        ss >> v.x() >> v.y() >> v.z();
        corners.push_back(v);
        if (corners.size() == 3) {
          addTriangle(corners[0], corners[1], corners[2]);
          corners.clear();
        }
      }
    }
  }
  return mesh;
}

}  // namespace

TriangleMesh TriangleMesh::load(const std::string& path) {
  if (!std::filesystem::is_regular_file(path)) throw core::FileError(path, "mesh file not found");
  const std::string ext = lowerExtension(path);
  TriangleMesh mesh;
  if (ext == ".obj") mesh = loadObj(path);
  else if (ext == ".stl") mesh = loadStl(path);
  else throw core::FileError(path, "unknown mesh format '" + ext + "' (use .obj or .stl)");
  if (mesh.triangles.empty()) throw core::FileError(path, "mesh has no triangles");
  return mesh;
}

Eigen::AlignedBox3d TriangleMesh::bounds() const {
  Eigen::AlignedBox3d box;
  for (const auto& v : vertices_m) box.extend(v);
  return box;
}

std::vector<SurfacePoint> TriangleMesh::sampleSurface(double spacing_m) const {
  std::vector<SurfacePoint> out;
  for (const auto& t : triangles) {
    const Eigen::Vector3d a = vertices_m[t[0]], b = vertices_m[t[1]], c = vertices_m[t[2]];
    Eigen::Vector3d n = (b - a).cross(c - a);
    const double area2 = n.norm();
    if (area2 < 1e-14) continue;
    n /= area2;
    // Barycentric grid: steps along the two longest edges.
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
  for (auto& v : m.vertices_m) v = X * v;
  return m;
}

}  // namespace srp::perception
