#include "srp/kb/KnowledgeBase.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "srp/core/Error.h"
#include "srp/kb/ShapeMeshes.h"

namespace {

const std::string kCubeFolder = std::string(SRP_DATASETS_DIR) + "/real/visp-rbt-cube";
constexpr double kMeshTol_m = 1e-6;

// A class given by its CAD file alone: size from the mesh's bounding box,
// mass from its volume, no colour, no generator shape.
TEST(KnowledgeBase, MeshOnlyClassTakesSizeAndMassFromItsMesh) {
  const auto catalogue = srp::kb::loadCatalogue(kCubeFolder + "/catalogue.json");
  const auto& cube = catalogue.at("cube");
  EXPECT_TRUE(cube.shape.empty());
  EXPECT_FALSE(cube.hasColour);
  EXPECT_NEAR(cube.dimensions_m.x(), 0.085, kMeshTol_m);
  EXPECT_NEAR(cube.dimensions_m.z(), 0.085, kMeshTol_m);
  EXPECT_NEAR(cube.mass_kg, 0.085 * 0.085 * 0.085 * srp::kb::kDefaultPartDensity_kg_m3, 1e-6);
  EXPECT_EQ(srp::kb::loadClassMesh(cube).size(), srp::kb::TriangleMesh::load(cube.meshPath).size());
}

TEST(KnowledgeBase, AddMeshClassWritesAnEntryAndRefusesATakenName) {
  const auto dir = std::filesystem::temp_directory_path() / "srp_kb_add_test";
  std::filesystem::remove_all(dir);
  const std::string path = (dir / "parts.json").string();
  srp::kb::MeshClassEntry e;
  e.name = "cube";
  e.meshPath = kCubeFolder + "/cube.obj";
  const auto c = srp::kb::addMeshClass(path, e);
  EXPECT_EQ(c.classId, 0);
  EXPECT_EQ(c.noun, "cube");
  EXPECT_NEAR(c.dimensions_m.y(), 0.085, kMeshTol_m);
  e.name = "cube 2";
  e.rgb = Eigen::Vector3d(0.8, 0.1, 0.1);
  const auto c2 = srp::kb::addMeshClass(path, e);
  EXPECT_EQ(c2.classId, 1) << "the next free id";
  EXPECT_TRUE(c2.hasColour);
  try {
    srp::kb::addMeshClass(path, e);
    FAIL() << "a taken name was accepted";
  } catch (const srp::core::InvalidInputError& err) {
    EXPECT_NE(std::string(err.what()).find("'cube 2' is already"), std::string::npos) << err.what();
  }
  e.name = "ghost";
  e.meshPath = (dir / "missing.stl").string();
  EXPECT_THROW(srp::kb::addMeshClass(path, e), srp::core::FileError);
}

// `srp kb build -o DIR`: a copy of the catalogue whose generated classes name the
// meshes written beside it, and whose CAD classes name their file absolutely; the
// copy loads, and its meshes are the shipped catalogue's shapes. Never over the input.
TEST(KnowledgeBase, CopiedCatalogueNamesTheMeshesBuiltBesideIt) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / "srp_kb_copy_test";
  fs::remove_all(dir);
  fs::create_directories(dir / "mixed");
  const std::string shipped = std::string(SRP_DATASETS_DIR) + "/kb/catalogue.json";
  const auto original = srp::kb::loadCatalogue(shipped);
  const auto built = srp::kb::buildMeshes(original, dir);
  EXPECT_EQ(built.size(), original.classes().size());
  const fs::path copy = srp::kb::copyCatalogue(shipped, dir);
  EXPECT_EQ(copy, dir / "catalogue.json");
  const auto catalogue = srp::kb::loadCatalogue(copy.string());
  for (const auto& c : catalogue.classes()) {
    EXPECT_EQ(fs::path(c.meshPath), dir / "meshes" / fs::path(original.at(c.name).meshPath).filename()) << c.name;
    EXPECT_EQ(srp::kb::TriangleMesh::load(c.meshPath).size(), srp::kb::makeClassMesh(original.at(c.name)).size());
  }
  // A class given by its own CAD file keeps naming that file from the copy's folder.
  const fs::path cubeCopy = srp::kb::copyCatalogue(kCubeFolder + "/catalogue.json", dir / "mixed");
  EXPECT_TRUE(fs::equivalent(srp::kb::loadCatalogue(cubeCopy.string()).at("cube").meshPath, kCubeFolder + "/cube.obj"));
  try {
    srp::kb::copyCatalogue(copy.string(), dir);
    FAIL() << "the copy replaced its own input";
  } catch (const srp::core::InvalidInputError& err) {
    EXPECT_NE(std::string(err.what()).find("catalogue.json"), std::string::npos) << err.what();
  }
  fs::remove_all(dir);
}

}  // namespace

// A part without a CAD file, given by its box (srp kb add NAME --shape box --size X Y Z).
TEST(KnowledgeBase, AddBoxClassWritesACuboidWithoutAMesh) {
  const auto dir = std::filesystem::temp_directory_path() / "srp_kb_add_box_test";
  std::filesystem::remove_all(dir);
  const std::string path = (dir / "parts.json").string();
  srp::kb::BoxClassEntry toy;
  toy.name = "toy";
  toy.size_m = {0.12, 0.08, 0.06};
  const auto c = srp::kb::addBoxClass(path, toy);
  EXPECT_EQ(c.shape, "cuboid");
  EXPECT_TRUE(c.meshPath.empty());
  EXPECT_FALSE(c.hasColour) << "no --rgb: colour is no evidence for it";
  EXPECT_NEAR((c.dimensions_m - toy.size_m).norm(), 0.0, kMeshTol_m);
  EXPECT_NEAR(c.mass_kg, 0.12 * 0.08 * 0.06 * srp::kb::kDefaultPartDensity_kg_m3, 1e-9);
  EXPECT_EQ(srp::kb::loadClassMesh(c).bounds().sizes().isApprox(toy.size_m, 1e-9), true);
  EXPECT_TRUE(srp::kb::buildMeshes(srp::kb::loadCatalogue(path)).empty()) << "no mesh file wanted";
  // Sizes outside 1 mm .. 2 m (a part drawn in millimetres), NaN, a taken name: refused, the file unchanged.
  for (const Eigen::Vector3d bad : {Eigen::Vector3d(120, 80, 60), Eigen::Vector3d(0.0005, 0.08, 0.06),
                                    Eigen::Vector3d(0.1, std::nan(""), 0.06)}) {
    srp::kb::BoxClassEntry e;
    e.name = "other";
    e.size_m = bad;
    try {
      srp::kb::addBoxClass(path, e);
      ADD_FAILURE() << "accepted size " << bad.transpose();
    } catch (const srp::core::InvalidInputError& err) {
      EXPECT_NE(std::string(err.what()).find("--size"), std::string::npos) << err.what();
    }
  }
  EXPECT_THROW(srp::kb::addBoxClass(path, toy), srp::core::InvalidInputError);
  EXPECT_EQ(srp::kb::loadCatalogue(path).classes().size(), 1u);
}
