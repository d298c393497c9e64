#include "srp/kb/KnowledgeBase.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "srp/core/Error.h"
#include "srp/core/Json.h"
#include "srp/core/OutputFile.h"
#include "srp/core/SafeText.h"
#include "srp/kb/MeshValidator.h"
#include "srp/kb/ShapeMeshes.h"

namespace srp::kb {

namespace {

Eigen::Vector3d vec3(const nlohmann::json& j, const std::string& context) {
  if (!j.is_array() || j.size() != 3)
    throw srp::core::InvalidInputError(context + ": expected an array of 3 numbers");
  return {j[0].get<double>(), j[1].get<double>(), j[2].get<double>()};
}

/// The numbers of a class as written: finite, sizes within what a robot cell
/// handles (MeshValidator::Options), masses positive.
void checkNumbers(const srp::core::ObjectClass& c, const std::string& ctx, bool meshOnly) {
  using srp::core::InvalidInputError;
  const MeshValidator::Options rules;
  if (!(c.meshScale > 0.0) || !std::isfinite(c.meshScale))
    throw InvalidInputError(ctx + ": field 'mesh_scale' must be a positive number (0.001 for a file in millimetres)");
  const bool sized = (c.dimensions_m.array() > 0.0).all();
  if (sized && !(c.dimensions_m.maxCoeff() <= rules.maxSize_m && c.dimensions_m.maxCoeff() >= rules.minSize_m))
    throw InvalidInputError(ctx + ": field 'dimensions_m' must be within " + std::to_string(rules.minSize_m) + "-" +
                            std::to_string(rules.maxSize_m) + " m (metres, not millimetres)");
  if (!(c.mass_kg >= 0.0) || !std::isfinite(c.mass_kg) || (!meshOnly && !(c.mass_kg > 0.0)))
    throw InvalidInputError(ctx + ": field 'mass_kg' must be a positive number of kilograms");
  if (!(c.wallThickness_m >= 0.0) || (sized && !(c.wallThickness_m < c.dimensions_m.minCoeff())))
    throw InvalidInputError(ctx + ": field 'wall_thickness_m' must be >= 0 and thinner than the box");
  if (!c.rgb.allFinite() || (c.rgb.array() < 0.0).any() || (c.rgb.array() > 1.0).any())
    throw InvalidInputError(ctx + ": field 'rgb' must be three numbers in [0, 1]");
  if (!c.graspAxis_object.allFinite())
    throw InvalidInputError(ctx + ": field 'grasp_axis' must be a non-zero direction");
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
      srp::core::requireSafeName(c.name, ctx0 + " field 'name'");
      const std::string ctx = path + ": class '" + c.name + "'";
      c.classId = requireField(e, "class_id", ctx).get<int>();
      c.noun = e.value("noun", c.name);
      srp::core::requireSafeName(c.noun, ctx + " field 'noun'");
      c.colourName = e.value("color_name", "");
      if (!c.colourName.empty()) srp::core::requireSafeName(c.colourName, ctx + " field 'color_name'");
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
      c.meshScale = e.value("mesh_scale", 1.0);
      c.flat = e.value("flat", false);
      checkNumbers(c, ctx, meshOnly);
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
  if (!c.meshPath.empty() && std::filesystem::exists(c.meshPath)) {
    TriangleMesh mesh = TriangleMesh::load(c.meshPath);
    return c.meshScale == 1.0 ? mesh : mesh.scaled(c.meshScale);
  }
  if (hasShapeGenerator(c.shape)) return makeClassMesh(c);
  throw srp::core::FileError(c.meshPath, "mesh of class '" + c.name + "' (shape '" + c.shape +
                                             "') is missing and cannot be generated; add the mesh file (STL, OBJ, PLY, glTF, COLLADA)");
}

namespace {

/// Checks the mesh of a class given by its CAD file alone (MeshValidator) and
/// measures it: bounding-box size and, without a mass, the mass of its volume
/// (a flat part: of its box, each side at least the validator's minimum size).
std::vector<std::string> measureMeshClass(srp::core::ObjectClass& c, const std::string& what) {
  const TriangleMesh mesh = loadClassMesh(c);
  MeshValidator::Options rules;
  rules.flat = c.flat;
  std::vector<std::string> warnings = MeshValidator(rules).check(mesh, what);
  const Eigen::Vector3d size = mesh.bounds().sizes().cwiseMax(c.flat ? rules.minSize_m : 0.0);
  if ((c.dimensions_m.array() <= 0.0).any()) c.dimensions_m = size;
  if (!(c.mass_kg > 0.0))
    c.mass_kg = (c.flat ? size.prod() : std::abs(mesh.volume())) * kDefaultPartDensity_kg_m3;
  return warnings;
}

}  // namespace

srp::core::ObjectCatalogue loadCatalogue(const std::string& path) {
  std::vector<srp::core::ObjectClass> classes = readCatalogueFile(path);
  for (auto& c : classes)
    if (c.shape.empty() && !c.meshPath.empty())  // generated shapes carry their size
      measureMeshClass(c, path + ": class '" + c.name + "' (mesh " + c.meshPath + ")");
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

srp::core::ObjectClass addMeshClass(const std::string& cataloguePath, const MeshClassEntry& entry,
                                    std::vector<std::string>* warnings) {
  namespace fs = std::filesystem;
  srp::core::requireSafeName(entry.name, "srp kb add --name");
  if (!entry.noun.empty()) srp::core::requireSafeName(entry.noun, "srp kb add --noun");
  srp::core::require(entry.kind == "part" || entry.kind == "container",
                     "srp kb add: kind must be \"part\" or \"container\", not \"" + entry.kind + "\"");
  srp::core::checkOutputPaths({{"--catalogue", cataloguePath}}, {{"--mesh", entry.meshPath}}, true);
  if (!(entry.scale > 0.0) || !std::isfinite(entry.scale))
    throw srp::core::InvalidInputError("srp kb add: --scale " + std::to_string(entry.scale) +
                                       " must be a positive number (0.001 for a file in millimetres)");
  if (entry.mass_kg && (!(*entry.mass_kg > 0.0) || !std::isfinite(*entry.mass_kg)))
    throw srp::core::InvalidInputError("srp kb add: --mass must be a positive number of kilograms");
  if (entry.rgb && (!entry.rgb->allFinite() || (entry.rgb->array() < 0.0).any() || (entry.rgb->array() > 1.0).any()))
    throw srp::core::InvalidInputError("srp kb add: --rgb must be three numbers in [0, 1]");
  {  // the mesh as the catalogue will read it: valid, and its warnings for the user
    srp::core::ObjectClass probe;
    probe.name = entry.name;
    probe.meshPath = entry.meshPath;
    probe.meshScale = entry.scale;
    probe.flat = entry.flat;
    if (warnings) *warnings = measureMeshClass(probe, "srp kb add --mesh " + entry.meshPath);
    else measureMeshClass(probe, "srp kb add --mesh " + entry.meshPath);
  }
  const fs::path folder = fs::absolute(cataloguePath).parent_path();
  nlohmann::json e{{"name", entry.name},
                   {"class_id", entry.classId},
                   {"noun", entry.noun.empty() ? entry.name : entry.noun},
                   {"kind", entry.kind},
                   {"mesh", fs::absolute(entry.meshPath).lexically_relative(folder).generic_string()}};
  if (entry.rgb) e["rgb"] = {entry.rgb->x(), entry.rgb->y(), entry.rgb->z()};
  if (entry.mass_kg) e["mass_kg"] = *entry.mass_kg;
  if (entry.scale != 1.0) e["mesh_scale"] = entry.scale;
  if (entry.flat) e["flat"] = true;
  appendClass(cataloguePath, e);
  return loadCatalogue(cataloguePath).at(entry.name);
}

srp::core::ObjectClass addBoxClass(const std::string& cataloguePath, const BoxClassEntry& entry) {
  srp::core::requireSafeName(entry.name, "srp kb add --name");
  if (!entry.noun.empty()) srp::core::requireSafeName(entry.noun, "srp kb add --noun");
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
