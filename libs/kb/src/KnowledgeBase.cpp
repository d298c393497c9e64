#include "srp/kb/KnowledgeBase.h"

#include <filesystem>

#include "srp/core/Error.h"
#include "srp/kb/ShapeMeshes.h"

namespace srp::kb {

bool hasShapeGenerator(const std::string& shape) {
  return shape == "open_box" || shape == "cuboid" || shape == "star" || shape == "parallelogram" ||
         shape == "octagon";
}

std::vector<BuiltMesh> buildMeshes(const srp::core::ObjectCatalogue& catalogue) {
  std::vector<BuiltMesh> built;
  for (const auto& c : catalogue.classes()) {
    if (!hasShapeGenerator(c.shape)) continue;
    srp::core::require(!c.meshPath.empty(), "catalogue class '" + c.name + "': missing field 'mesh'");
    const TriangleMesh mesh = makeClassMesh(c);
    mesh.saveStl(c.meshPath, "srp kb: " + c.name + " (" + c.shape + "), metres, object frame = bottom centre");
    built.push_back({c.name, c.meshPath, mesh.size()});
  }
  return built;
}

TriangleMesh loadClassMesh(const srp::core::ObjectClass& c) {
  if (!c.meshPath.empty() && std::filesystem::exists(c.meshPath)) return TriangleMesh::loadStl(c.meshPath);
  if (hasShapeGenerator(c.shape)) return makeClassMesh(c);
  throw srp::core::FileError(c.meshPath, "mesh of class '" + c.name + "' (shape '" + c.shape +
                                             "') is missing and cannot be generated; add the STL file");
}

}  // namespace srp::kb
