#pragma once
/// \file KnowledgeBase.h
/// \brief Builds and loads the knowledge base's meshes (`srp kb build`).

#include <string>
#include <vector>

#include "srp/core/ObjectCatalogue.h"
#include "srp/kb/TriangleMesh.h"

namespace srp::kb {

/// One mesh written by buildMeshes().
struct BuiltMesh {
  std::string className;
  std::string path;
  std::size_t triangleCount = 0;
};

/// Generates the mesh of every class whose shape has a generator
/// (makeClassMesh) and writes it as binary STL to the class' `mesh` path
/// (creating its folder). Classes with another shape keep their user-supplied
/// mesh and are skipped. Throws FileError naming the path when writing fails.
std::vector<BuiltMesh> buildMeshes(const srp::core::ObjectCatalogue& catalogue);

/// True when makeClassMesh() can generate meshes for this shape.
bool hasShapeGenerator(const std::string& shape);

/// The mesh of a class: its STL file when present, else the generated one (so
/// a fresh checkout renders before `srp kb build`). Throws FileError naming the
/// path when the file is absent and the shape has no generator.
TriangleMesh loadClassMesh(const srp::core::ObjectClass& objectClass);

}  // namespace srp::kb
