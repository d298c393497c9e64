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

namespace {

Eigen::Vector3d vec3(const nlohmann::json& j, const std::string& context) {
  if (!j.is_array() || j.size() != 3)
    throw srp::core::InvalidInputError(context + ": expected an array of 3 numbers");
  return {j[0].get<double>(), j[1].get<double>(), j[2].get<double>()};
}

/// The catalogue file's classes as written (a mesh-only class keeps zero size
/// and mass); errors name the file and the field.
std::vector<srp::core::ObjectClass> readCatalogueFile(const std::string& path) {
  using srp::core::InvalidInputError;
  using srp::core::requireField;
  const nlohmann::json j = srp::core::readJsonFile(path);
  const int version = requireField(j, "schema_version", path).get<int>();
  if (version != 1)
    throw srp::core::FileError(path, "catalogue schema_version " + std::to_string(version) +
                                         " is not supported by this build (expected 1)");
  const std::filesystem::path folder = std::filesystem::path(path).parent_path();
  std::vector<srp::core::ObjectClass> classes;
  try {
    for (const auto& e : requireField(j, "classes", path)) {
      srp::core::ObjectClass c;
      const std::string ctx0 = path + ": class";
      c.name = requireField(e, "name", ctx0).get<std::string>();
      const std::string ctx = path + ": class '" + c.name + "'";
      c.classId = requireField(e, "class_id", ctx).get<int>();
      c.noun = e.value("noun", c.name);
      c.colourName = e.value("color_name", "");
      const std::string kind = requireField(e, "kind", ctx).get<std::string>();
      if (kind == "part") c.kind = srp::core::ObjectKind::Part;
      else if (kind == "container") c.kind = srp::core::ObjectKind::Container;
      else throw InvalidInputError(ctx + ": field 'kind' must be \"part\" or \"container\", not \"" + kind + "\"");
      if (e.contains("mesh")) c.meshPath = (folder / e.at("mesh").get<std::string>()).lexically_normal().string();
      // A class given by its CAD file alone: shape, size, colour and mass may
      // be left out (size and mass then come from the mesh).
      const bool meshOnly = !c.meshPath.empty() && !e.contains("shape");
      c.shape = meshOnly ? std::string() : requireField(e, "shape", ctx).get<std::string>();
      c.hasColour = e.contains("rgb");  // without: a neutral grey, and colour is no evidence for it
      if (c.hasColour) c.rgb = vec3(requireField(e, "rgb", ctx), ctx + " field 'rgb'");
      if (!meshOnly || e.contains("dimensions_m")) {
        c.dimensions_m = vec3(requireField(e, "dimensions_m", ctx), ctx + " field 'dimensions_m'");
        if ((c.dimensions_m.array() <= 0.0).any())
          throw InvalidInputError(ctx + ": field 'dimensions_m' must be positive");
      }
      c.wallThickness_m = e.value("wall_thickness_m", 0.0);
      c.mass_kg = meshOnly ? e.value("mass_kg", 0.0) : requireField(e, "mass_kg", ctx).get<double>();
      if (c.shape == "hull") {
        const auto& fp = requireField(e, "footprint_m", ctx);
        if (!fp.is_array() || fp.size() < 3)
          throw InvalidInputError(ctx + ": field 'footprint_m' must list at least 3 [x, y] points (metres)");
        for (const auto& q : fp) {
          if (!q.is_array() || q.size() != 2 || !q[0].is_number() || !q[1].is_number())
            throw InvalidInputError(ctx + ": field 'footprint_m' must hold [x, y] pairs of numbers (metres)");
          const Eigen::Vector2d v(q[0].get<double>(), q[1].get<double>());
          if (!v.allFinite()) throw InvalidInputError(ctx + ": field 'footprint_m' holds a non-finite number");
          c.footprint_object.push_back(v);
        }
      }
      c.observed = e.value("observed", false);
      if (e.contains("grasp_axis")) c.graspAxis_object = vec3(e.at("grasp_axis"), ctx + " field 'grasp_axis'").normalized();
      classes.push_back(std::move(c));
    }
  } catch (const nlohmann::json::exception& e) {
    throw srp::core::FileError(path, std::string("bad catalogue entry: ") + e.what());
  }
  return classes;
}

}  // namespace

bool hasShapeGenerator(const std::string& shape) {
  return shape == "open_box" || shape == "cuboid" || shape == "star" || shape == "parallelogram" ||
         shape == "octagon" || shape == "hull";
}

namespace {

/// Where buildMeshes(catalogue, outDir) writes a generated class's mesh, relative to outDir.
std::filesystem::path generatedMeshPath(const std::string& meshPath) {
  return std::filesystem::path("meshes") / std::filesystem::path(meshPath).filename();
}

}  // namespace

std::vector<BuiltMesh> buildMeshes(const srp::core::ObjectCatalogue& catalogue, const std::filesystem::path& outDir) {
  std::vector<BuiltMesh> built;
  for (const auto& c : catalogue.classes()) {
    if (!hasShapeGenerator(c.shape) || c.meshPath.empty()) continue;  // no file wanted: generated when used
    const TriangleMesh mesh = makeClassMesh(c);
    const std::string path = outDir.empty() ? c.meshPath : (outDir / generatedMeshPath(c.meshPath)).string();
    mesh.saveStl(path, "srp kb: " + c.name + " (" + c.shape + "), metres, object frame = bottom centre");
    built.push_back({c.name, path, mesh.size()});
  }
  return built;
}

std::filesystem::path copyCatalogue(const std::string& cataloguePath, const std::filesystem::path& outDir) {
  namespace fs = std::filesystem;
  if (!fs::is_directory(outDir)) throw srp::core::FileError(outDir.string(), "not a folder (create it first)");
  const fs::path target = outDir / fs::path(cataloguePath).filename();
  srp::core::checkOutputPaths({{"catalogue copy", target}}, {{"--catalogue", cataloguePath}}, /*overwrite=*/true);
  const srp::core::ObjectCatalogue catalogue(readCatalogueFile(cataloguePath));
  nlohmann::json j = srp::core::readJsonFile(cataloguePath);
  for (auto& entry : j.at("classes")) {
    const srp::core::ObjectClass& c = catalogue.at(entry.at("name").get<std::string>());
    if (c.meshPath.empty()) continue;
    entry["mesh"] = hasShapeGenerator(c.shape) ? generatedMeshPath(c.meshPath).string()
                                               : fs::absolute(c.meshPath).lexically_normal().string();
  }
  srp::core::writeFileAtomically(target, j.dump(2) + "\n");
  return target;
}

TriangleMesh loadClassMesh(const srp::core::ObjectClass& c) {
  if (!c.meshPath.empty() && std::filesystem::exists(c.meshPath)) return TriangleMesh::load(c.meshPath);
  if (hasShapeGenerator(c.shape)) return makeClassMesh(c);
  throw srp::core::FileError(c.meshPath, "mesh of class '" + c.name + "' (shape '" + c.shape +
                                             "') is missing and cannot be generated; add the mesh file (STL, OBJ, PLY, glTF, COLLADA)");
}

srp::core::ObjectCatalogue loadCatalogue(const std::string& path) {
  std::vector<srp::core::ObjectClass> classes = readCatalogueFile(path);
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
  if (fs::exists(cataloguePath)) loadCatalogue(cataloguePath);  // a valid catalogue to add to
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
