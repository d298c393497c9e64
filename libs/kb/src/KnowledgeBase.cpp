#include "srp/kb/KnowledgeBase.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "srp/core/Error.h"
#include "srp/core/Json.h"
#include "srp/core/OutputFile.h"
#include "srp/kb/ShapeMeshes.h"

namespace srp::kb {

bool hasShapeGenerator(const std::string& shape) {
  return shape == "open_box" || shape == "cuboid" || shape == "star" || shape == "parallelogram" ||
         shape == "octagon" || shape == "hull";
}

std::vector<BuiltMesh> buildMeshes(const srp::core::ObjectCatalogue& catalogue) {
  std::vector<BuiltMesh> built;
  for (const auto& c : catalogue.classes()) {
    if (!hasShapeGenerator(c.shape) || c.meshPath.empty()) continue;  // no file wanted: generated when used
    const TriangleMesh mesh = makeClassMesh(c);
    mesh.saveStl(c.meshPath, "srp kb: " + c.name + " (" + c.shape + "), metres, object frame = bottom centre");
    built.push_back({c.name, c.meshPath, mesh.size()});
  }
  return built;
}

TriangleMesh loadClassMesh(const srp::core::ObjectClass& c) {
  if (!c.meshPath.empty() && std::filesystem::exists(c.meshPath)) return TriangleMesh::load(c.meshPath);
  if (hasShapeGenerator(c.shape)) return makeClassMesh(c);
  throw srp::core::FileError(c.meshPath, "mesh of class '" + c.name + "' (shape '" + c.shape +
                                             "') is missing and cannot be generated; add the mesh file (STL, OBJ, PLY, glTF, COLLADA)");
}

srp::core::ObjectCatalogue loadCatalogue(const std::string& path) {
  const srp::core::ObjectCatalogue raw = srp::core::ObjectCatalogue::load(path);
  std::vector<srp::core::ObjectClass> classes = raw.classes();
  for (auto& c : classes) {
    if (!c.shape.empty() || c.meshPath.empty()) continue;  // generated shapes carry their size
    const TriangleMesh mesh = TriangleMesh::load(c.meshPath);
    if ((c.dimensions_m.array() <= 0.0).any()) c.dimensions_m = mesh.bounds().sizes();
    if (!(c.mass_kg > 0.0)) c.mass_kg = std::abs(mesh.volume()) * kDefaultPartDensity_kg_m3;
  }
  return srp::core::ObjectCatalogue(std::move(classes));
}

namespace {
// Appends the catalogue entry `e` (its "name" and "class_id" checked free; a
// class_id of -1 becomes the next free one) and writes the file atomically.
void appendClass(const std::string& cataloguePath, nlohmann::json e) {
  namespace fs = std::filesystem;
  const std::string name = e.at("name").get<std::string>();
  const int classId = e.at("class_id").get<int>();
  nlohmann::json j = fs::exists(cataloguePath) ? srp::core::readJsonFile(cataloguePath)
                                               : nlohmann::json{{"schema_version", 1}, {"classes", nlohmann::json::array()}};
  if (fs::exists(cataloguePath)) srp::core::ObjectCatalogue::load(cataloguePath);  // a valid catalogue to add to
  int nextId = 0;
  for (const auto& c : j.at("classes")) {
    if (c.value("name", "") == name)
      throw srp::core::InvalidInputError("srp kb add: class '" + name + "' is already in " + cataloguePath +
                                         "; choose another --name");
    if (c.value("class_id", -1) == classId)
      throw srp::core::InvalidInputError("srp kb add: class_id " + std::to_string(classId) + " is taken by '" +
                                         c.value("name", "") + "' in " + cataloguePath + "; choose another --id");
    nextId = std::max(nextId, c.value("class_id", -1) + 1);
  }
  if (classId < 0) e["class_id"] = nextId;
  j["classes"].push_back(e);
  const fs::path folder = fs::absolute(cataloguePath).parent_path();
  if (!folder.empty()) fs::create_directories(folder);
  srp::core::writeFileAtomically(cataloguePath, j.dump(2) + "\n");
}
}  // namespace

srp::core::ObjectClass addMeshClass(const std::string& cataloguePath, const MeshClassEntry& entry) {
  namespace fs = std::filesystem;
  srp::core::require(!entry.name.empty(), "srp kb add: the class needs a name (--name)");
  srp::core::require(entry.kind == "part" || entry.kind == "container",
                     "srp kb add: kind must be \"part\" or \"container\", not \"" + entry.kind + "\"");
  TriangleMesh::load(entry.meshPath);  // readable, has triangles
  const fs::path folder = fs::absolute(cataloguePath).parent_path();
  nlohmann::json e{{"name", entry.name},
                   {"class_id", entry.classId},
                   {"noun", entry.noun.empty() ? entry.name : entry.noun},
                   {"kind", entry.kind},
                   {"mesh", fs::absolute(entry.meshPath).lexically_relative(folder).generic_string()}};
  if (entry.rgb) e["rgb"] = {entry.rgb->x(), entry.rgb->y(), entry.rgb->z()};
  if (entry.mass_kg) e["mass_kg"] = *entry.mass_kg;
  appendClass(cataloguePath, e);
  return loadCatalogue(cataloguePath).at(entry.name);
}

srp::core::ObjectClass addBoxClass(const std::string& cataloguePath, const BoxClassEntry& entry) {
  srp::core::require(!entry.name.empty(), "srp kb add: the class needs a name");
  srp::core::require(entry.kind == "part" || entry.kind == "container",
                     "srp kb add: kind must be \"part\" or \"container\", not \"" + entry.kind + "\"");
  const Eigen::Vector3d& d = entry.size_m;
  if (!d.allFinite() || (d.array() < kMinBoxSide_m).any() || (d.array() > kMaxBoxSide_m).any()) {
    char got[96];
    std::snprintf(got, sizeof got, "%g %g %g", d.x(), d.y(), d.z());
    throw srp::core::InvalidInputError(std::string("srp kb add: --size must be three sides in metres, each from 0.001 "
                                                   "to 2 (got ") + got + "; a part drawn in millimetres? divide by 1000)");
  }
  if (entry.rgb && (!entry.rgb->allFinite() || (entry.rgb->array() < 0.0).any() || (entry.rgb->array() > 1.0).any()))
    throw srp::core::InvalidInputError("srp kb add: --rgb must be three numbers in [0, 1] (linear RGB)");
  const double mass = entry.mass_kg.value_or(d.prod() * kDefaultPartDensity_kg_m3);
  if (!std::isfinite(mass) || !(mass > 0.0))
    throw srp::core::InvalidInputError("srp kb add: --mass must be a positive number of kilograms");
  nlohmann::json e{{"name", entry.name},
                   {"class_id", entry.classId},
                   {"noun", entry.noun.empty() ? entry.name : entry.noun},
                   {"kind", entry.kind},
                   {"shape", entry.kind == "container" ? "open_box" : "cuboid"},
                   {"dimensions_m", {d.x(), d.y(), d.z()}},
                   {"mass_kg", mass}};
  if (entry.kind == "container") {
    // An open box: floor and walls kBoxContainerWall_m thick (at most a third of the smallest side).
    e["wall_thickness_m"] = std::min(kBoxContainerWall_m, d.minCoeff() / 3);
    e["mass_kg"] = entry.mass_kg.value_or(0.2 * mass);  // hollow: a fifth of the solid box
  }
  if (entry.rgb) e["rgb"] = {entry.rgb->x(), entry.rgb->y(), entry.rgb->z()};
  appendClass(cataloguePath, e);
  return loadCatalogue(cataloguePath).at(entry.name);
}

}  // namespace srp::kb
