#pragma once
/// \file KnowledgeBase.h
/// \brief Builds and loads the knowledge base's meshes (`srp kb build`),
/// loads catalogues whose classes may be given by a CAD file alone, and adds
/// such classes (`srp kb add`).

#include <Eigen/Core>
#include <filesystem>
#include <optional>
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
/// (makeClassMesh) and writes it as binary STL: to the class' `mesh` path
/// (creating its folder) when `outDir` is empty, else to
/// `outDir/meshes/<file name of the class' mesh path>` (where copyCatalogue()
/// points them). Classes with another shape keep their user-supplied mesh and
/// are skipped. Throws FileError naming the path when writing fails.
std::vector<BuiltMesh> buildMeshes(const srp::core::ObjectCatalogue& catalogue,
                                   const std::filesystem::path& outDir = {});

/// Writes a copy of the catalogue file `cataloguePath` as `outDir/<its file
/// name>` (atomically): a class with a shape generator names
/// `meshes/<file name>` (what buildMeshes(catalogue, outDir) writes), a class
/// given by its own CAD file names that file by its absolute path; everything
/// else is copied as it is. Returns the path written. Throws InvalidInputError
/// when the copy would replace the catalogue itself, FileError when `outDir` is
/// not a folder.
std::filesystem::path copyCatalogue(const std::string& cataloguePath, const std::filesystem::path& outDir);

/// True when makeClassMesh() can generate meshes for this shape.
bool hasShapeGenerator(const std::string& shape);

/// The mesh of a class: its file when present (times the class' meshScale),
/// else the generated one (so a fresh checkout renders before `srp kb build`). Throws FileError naming the
/// path when the file is absent and the shape has no generator.
TriangleMesh loadClassMesh(const srp::core::ObjectClass& objectClass);

/// Density [kg/m^3] that gives a mesh-only class without "mass_kg" its mass
/// from the mesh's volume (a solid plastic part).
constexpr double kDefaultPartDensity_kg_m3 = 1000.0;

/// The one catalogue loader (every command and library reads a catalogue file
/// through it): reads the file (ObjectCatalogue.h gives the format), checks
/// every name (core::isSafeName) and number (finite; sizes within
/// MeshValidator's 1 mm - 2 m; masses positive), then every class given by its
/// mesh alone has its mesh checked (MeshValidator, at its "mesh_scale", "flat")
/// and gets its bounding-box size (`dimensions_m`, in the mesh's frame) and,
/// without "mass_kg", the mass of its volume at kDefaultPartDensity_kg_m3.
/// Throws FileError or InvalidInputError naming the file, the class and the
/// field, or a mesh that cannot be read or breaks a rule.
srp::core::ObjectCatalogue loadCatalogue(const std::string& path);

/// A class given by its CAD file alone (`srp kb add`).
struct MeshClassEntry {
  std::string name;
  int classId = -1;                 ///< -1: the next free id
  std::string noun;                 ///< empty: the name
  std::string kind = "part";        ///< "part" or "container"
  std::string meshPath;             ///< the CAD file (any path; stored relative to the catalogue)
  std::optional<Eigen::Vector3d> rgb;  ///< linear RGB [0, 1] when the colour identifies it
  std::optional<double> mass_kg;
  double scale = 1.0;               ///< metres per file unit (0.001: the file is in millimetres)
  bool flat = false;                ///< a flat part (a sheet): no enclosed volume needed
};

/// A part or container without a mesh, given by its box size (`srp kb add NAME
/// --shape box --size X Y Z`): catalogue shape "cuboid" (a container: "open_box"
/// with walls kBoxContainerWall_m thick), no "mesh".
struct BoxClassEntry {
  std::string name;
  int classId = -1;                 ///< -1: the next free id
  std::string noun;                 ///< empty: the name
  std::string kind = "part";        ///< "part" or "container"
  Eigen::Vector3d size_m = Eigen::Vector3d::Zero();  ///< x, y, z [m], each in [kMinBoxSide_m, kMaxBoxSide_m]
  std::optional<Eigen::Vector3d> rgb;  ///< linear RGB [0, 1] when the colour identifies it
  std::optional<double> mass_kg;       ///< default: the box's volume at kDefaultPartDensity_kg_m3
};

/// The sides a box class may have [m]: from a screw to a large box.
constexpr double kMinBoxSide_m = 0.001, kMaxBoxSide_m = 2.0;
/// Wall and floor thickness of a box container [m] (at most a third of its smallest side).
constexpr double kBoxContainerWall_m = 0.005;

/// Appends a box class to the catalogue file (created when missing), after
/// checking its size (every side finite, in [kMinBoxSide_m, kMaxBoxSide_m]),
/// rgb (in [0, 1]), mass (positive) and that its name and id are free. Returns
/// the class as loadCatalogue() reads it back. Throws InvalidInputError naming
/// the bad value, FileError for an unreadable catalogue.
srp::core::ObjectClass addBoxClass(const std::string& cataloguePath, const BoxClassEntry& entry);

/// Appends `entry` to the catalogue file (created when missing; replaced
/// atomically), after checking its name (core::isSafeName), that its mesh loads
/// and passes MeshValidator (at `entry.scale`, `entry.flat`), and that its name
/// and id are free; the file keeps its other content. Returns the class as
/// loadCatalogue() reads it back; `warnings` (if given) receives the
/// validator's warnings (a part that looks drawn in millimetres). Throws
/// InvalidInputError naming a taken name or id, a bad kind or name, a mesh that
/// breaks a rule, or a mesh that is the catalogue itself; FileError naming an
/// unreadable mesh or catalogue.
srp::core::ObjectClass addMeshClass(const std::string& cataloguePath, const MeshClassEntry& entry,
                                    std::vector<std::string>* warnings = nullptr);

}  // namespace srp::kb
