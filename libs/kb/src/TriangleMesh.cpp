#include "srp/kb/TriangleMesh.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>
#include <tuple>

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include "srp/core/Error.h"
#include "srp/core/OutputFile.h"

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
  std::string bytes;
  bytes.reserve(84 + 50 * triangles_.size());
  char head[80] = {};
  std::strncpy(head, header.c_str(), sizeof(head) - 1);
  bytes.append(head, sizeof(head));
  const auto count = static_cast<std::uint32_t>(triangles_.size());
  bytes.append(reinterpret_cast<const char*>(&count), sizeof(count));
  for (std::size_t i = 0; i < triangles_.size(); ++i) {
    float record[12];
    const Eigen::Vector3d n = normal(i);
    for (int k = 0; k < 3; ++k) record[k] = static_cast<float>(n[k]);
    for (int v = 0; v < 3; ++v)
      for (int k = 0; k < 3; ++k) record[3 + 3 * v + k] = static_cast<float>(triangles_[i][v][k]);
    bytes.append(reinterpret_cast<const char*>(record), sizeof(record));
    const std::uint16_t attribute = 0;
    bytes.append(reinterpret_cast<const char*>(&attribute), sizeof(attribute));
  }
  srp::core::writeFileAtomically(path, bytes);
}

namespace {

std::string lowerExtension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

std::size_t plyTypeSize(const std::string& type) {
  if (type == "char" || type == "uchar" || type == "int8" || type == "uint8") return 1;
  if (type == "short" || type == "ushort" || type == "int16" || type == "uint16") return 2;
  if (type == "int" || type == "uint" || type == "int32" || type == "uint32" || type == "float" || type == "float32")
    return 4;
  if (type == "double" || type == "float64") return 8;
  return 0;
}

/// A PLY header's element counts against the bytes after the header: each row
/// of an element needs at least its fixed-size properties (binary) or two
/// characters per property (ASCII: a digit and a separator).
void checkPlyHeader(const std::string& path, std::uintmax_t fileSize, const TriangleMesh::LoadOptions& o) {
  std::ifstream in(path, std::ios::binary);
  constexpr std::size_t kMaxHeaderBytes = 1 << 16;
  std::string line;
  std::size_t headerBytes = 0;
  bool binary = false, ended = false;
  struct Element { std::string name; std::uintmax_t count = 0; std::uintmax_t minRowBytes = 0; };
  std::vector<Element> elements;
  while (std::getline(in, line) && headerBytes <= kMaxHeaderBytes) {
    headerBytes += line.size() + 1;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::istringstream words(line);
    std::string key;
    words >> key;
    if (key == "format") {
      std::string format;
      words >> format;
      binary = format != "ascii";
    } else if (key == "element") {
      Element e;
      std::string count;
      words >> e.name >> count;
      if (count.empty() || count.size() > 19 || count.find_first_not_of("0123456789") != std::string::npos)
        throw srp::core::FileError(path, "PLY element '" + e.name + "' has no valid count ('" + count + "')");
      e.count = std::stoull(count);
      elements.push_back(e);
    } else if (key == "property" && !elements.empty()) {
      std::string type;
      words >> type;
      std::size_t bytes = type == "list" ? 0 : plyTypeSize(type);
      if (type == "list") {
        std::string countType;
        words >> countType;
        bytes = plyTypeSize(countType);
      }
      elements.back().minRowBytes += binary ? std::max<std::size_t>(bytes, 1) : 2;
    } else if (key == "end_header") {
      ended = true;
      break;
    }
  }
  if (!ended) throw srp::core::FileError(path, "the PLY header has no end_header within its first 64 kB");
  const std::uintmax_t body = fileSize > headerBytes ? fileSize - headerBytes : 0;
  std::uintmax_t needed = 0;
  for (const auto& e : elements) {
    const std::uintmax_t row = std::max<std::uintmax_t>(e.minRowBytes, 1);
    if (e.count > body / row || needed > body - e.count * row)
      throw srp::core::FileError(path, "the PLY header declares " + std::to_string(e.count) + " '" + e.name +
                                           "' elements, more than the file's " + std::to_string(body) +
                                           " bytes can hold (a damaged or hostile file)");
    needed += e.count * row;
    if ((e.name == "face" && e.count > o.maxTriangles) || (e.name == "vertex" && e.count > 3 * o.maxTriangles))
      throw srp::core::FileError(path, "the PLY file declares " + std::to_string(e.count) + " " + e.name +
                                           " elements, above the limit of " + std::to_string(o.maxTriangles) +
                                           " triangles; simplify the mesh");
  }
}

/// A binary STL's triangle count against its size (84-byte header + 50 bytes per triangle).
void checkBinaryStl(const std::string& path, std::uintmax_t fileSize, const TriangleMesh::LoadOptions& o) {
  std::ifstream in(path, std::ios::binary);
  char head[84] = {};
  in.read(head, sizeof(head));
  if (std::string(head, head + std::min<std::size_t>(5, static_cast<std::size_t>(in.gcount()))) == "solid")
    return;  // ASCII STL (or a binary one whose size Assimp checks): no declared count to trust
  if (in.gcount() < 84) throw srp::core::FileError(path, "the binary STL is shorter than its 84-byte header");
  std::uint32_t count = 0;
  std::memcpy(&count, head + 80, sizeof(count));
  if (84 + 50ull * count > fileSize)
    throw srp::core::FileError(path, "the binary STL declares " + std::to_string(count) +
                                         " triangles, more than its " + std::to_string(fileSize) +
                                         " bytes hold (truncated or damaged)");
  if (count > o.maxTriangles)
    throw srp::core::FileError(path, "the STL holds " + std::to_string(count) + " triangles, above the limit of " +
                                         std::to_string(o.maxTriangles) + "; simplify the mesh");
}

/// XML formats (COLLADA) declare array sizes in `count="N"` attributes that the
/// reader allocates up front: none may exceed what the file's text can hold.
void checkDeclaredXmlCounts(const std::string& path, std::uintmax_t fileSize) {
  std::ifstream in(path, std::ios::binary);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  static const std::string kKey = "count=\"";
  for (std::size_t at = text.find(kKey); at != std::string::npos; at = text.find(kKey, at + 1)) {
    std::size_t end = at + kKey.size();
    while (end < text.size() && std::isdigit(static_cast<unsigned char>(text[end]))) ++end;
    const std::string digits = text.substr(at + kKey.size(), end - at - kKey.size());
    if (digits.empty()) continue;
    if (digits.size() > 18 || std::stoull(digits) > fileSize)
      throw srp::core::FileError(path, "the file declares an array of " + digits + " values, more than its " +
                                           std::to_string(fileSize) + " bytes can hold (a damaged or hostile file)");
  }
}

}  // namespace

TriangleMesh TriangleMesh::load(const std::string& path, const LoadOptions& options) {
  if (!std::filesystem::is_regular_file(path))
    throw srp::core::FileError(path, "mesh file not found (a catalogue's \"mesh\" is relative to the catalogue file; "
                                     "run `srp kb build` to generate the bundled ones)");
  std::error_code ec;
  const std::uintmax_t fileSize = std::filesystem::file_size(path, ec);
  if (ec) throw srp::core::FileError(path, "cannot read the mesh's size (" + ec.message() + ")");
  if (fileSize > options.maxFileBytes)
    throw srp::core::FileError(path, "the mesh file is " + std::to_string(fileSize >> 20) + " MB, above the limit of " +
                                         std::to_string(options.maxFileBytes >> 20) + " MB; simplify the mesh");
  {
    std::ifstream in(path, std::ios::binary);
    char magic[4] = {};
    in.read(magic, sizeof(magic));
    const std::string ext = lowerExtension(path);
    if (std::string(magic, 3) == "ply" && (magic[3] == '\n' || magic[3] == '\r')) checkPlyHeader(path, fileSize, options);
    else if (ext == ".stl") checkBinaryStl(path, fileSize, options);
    else if (ext == ".dae" || ext == ".xml") checkDeclaredXmlCounts(path, fileSize);
  }
  Assimp::Importer importer;
  // The object frame is the file's own: no up-axis conversion.
  importer.SetPropertyBool(AI_CONFIG_IMPORT_COLLADA_IGNORE_UP_DIRECTION, true);
  // Whole faces only: points and lines are no surface.
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE, aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  const aiScene* scene = nullptr;
  try {
    scene = importer.ReadFile(path, aiProcess_Triangulate | aiProcess_PreTransformVertices | aiProcess_SortByPType |
                                        aiProcess_FindDegenerates);
  } catch (const std::bad_alloc&) {
    throw srp::core::FileError(path, "reading the mesh ran out of memory (a damaged or hostile file?)");
  }
  if (!scene || (scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE))
    throw srp::core::FileError(path, std::string("cannot read the mesh (") + importer.GetErrorString() +
                                         "); give an STL, OBJ, PLY, glTF or COLLADA file");
  std::size_t faces = 0;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) faces += scene->mMeshes[m]->mNumFaces;
  if (faces > options.maxTriangles)
    throw srp::core::FileError(path, "the mesh holds " + std::to_string(faces) + " faces, above the limit of " +
                                         std::to_string(options.maxTriangles) + " triangles; simplify the mesh");
  TriangleMesh mesh;
  mesh.triangles_.reserve(faces);
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh* am = scene->mMeshes[m];
    for (unsigned f = 0; f < am->mNumFaces; ++f) {
      const aiFace& face = am->mFaces[f];
      if (face.mNumIndices != 3) continue;
      Triangle t;
      for (int k = 0; k < 3; ++k) {
        if (face.mIndices[k] >= am->mNumVertices)
          throw srp::core::FileError(path, "a face refers to vertex " + std::to_string(face.mIndices[k]) +
                                               " of a mesh with " + std::to_string(am->mNumVertices));
        const aiVector3D& v = am->mVertices[face.mIndices[k]];
        t[k] = Eigen::Vector3d(v.x, v.y, v.z);
        if (!t[k].allFinite())
          throw srp::core::FileError(path, "triangle " + std::to_string(mesh.triangles_.size()) +
                                               " has a non-finite vertex (NaN or Inf); repair the mesh");
      }
      mesh.triangles_.push_back(t);
    }
  }
  if (mesh.triangles_.empty()) throw srp::core::FileError(path, "the mesh file holds no triangles");
  return mesh;
}

TriangleMesh TriangleMesh::scaled(double factor) const {
  TriangleMesh m = *this;
  for (Triangle& t : m.triangles_)
    for (Eigen::Vector3d& v : t) v *= factor;
  return m;
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
