#include "srp/kb/KnowledgeBase.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "srp/core/Error.h"

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

}  // namespace
