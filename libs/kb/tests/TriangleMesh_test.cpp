#include "srp/kb/TriangleMesh.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include <assimp/Exporter.hpp>
#include <assimp/Importer.hpp>
#include <assimp/scene.h>

#include "srp/core/Error.h"
#include "srp/kb/ShapeMeshes.h"

namespace {

constexpr double kFloat32Tol_m = 1e-7;  // STL stores float32

std::string tempPath(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("srp_kb_test_" + name)).string();
}

TEST(TriangleMesh, StlRoundTripKeepsVertices) {
  const auto mesh = srp::kb::makePrismMesh(srp::kb::shapeOutline("star", {0.05, 0.05}), 0.025);
  const std::string path = tempPath("star.stl");
  mesh.saveStl(path);
  EXPECT_EQ(std::filesystem::file_size(path), 84u + 50u * mesh.size());
  const auto back = srp::kb::TriangleMesh::load(path);
  ASSERT_EQ(back.size(), mesh.size());
  for (std::size_t i = 0; i < mesh.size(); ++i)
    for (int v = 0; v < 3; ++v)
      EXPECT_LT((back.triangles()[i][v] - mesh.triangles()[i][v]).norm(), kFloat32Tol_m);
  EXPECT_TRUE(back.isClosed(1e-6));
}

TEST(TriangleMesh, LoadRejectsMissingAndTruncatedFiles) {
  EXPECT_THROW(srp::kb::TriangleMesh::load(tempPath("does_not_exist.stl")), srp::core::FileError);
  const std::string path = tempPath("truncated.stl");
  srp::kb::makeBoxMesh({0, 0, 0}, {1, 1, 1}).saveStl(path);
  std::filesystem::resize_file(path, 84 + 50 * 3);
  try {
    srp::kb::TriangleMesh::load(path);
    FAIL() << "truncated STL accepted";
  } catch (const srp::core::FileError& e) {
    EXPECT_NE(std::string(e.what()).find("truncated.stl"), std::string::npos) << e.what();
  }
}

// A user's CAD file in any of the formats the knowledge base promises: the
// same closed box, written by Assimp's exporters, loads with its size.
TEST(TriangleMesh, LoadsStlObjPlyGltfAndColladaAlike) {
  constexpr double kSizeTol_m = 1e-6;
  const Eigen::Vector3d lo(-0.02, -0.03, 0.0), hi(0.02, 0.03, 0.05);
  const std::string stl = tempPath("box.stl");
  const auto box = srp::kb::makeBoxMesh(lo, hi);
  box.saveStl(stl);
  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFile(stl, 0);
  ASSERT_NE(scene, nullptr) << importer.GetErrorString();
  Assimp::Exporter exporter;
  for (const auto& [format, ext] : std::vector<std::pair<std::string, std::string>>{
           {"obj", "obj"}, {"ply", "ply"}, {"plyb", "ply"}, {"stl", "stl"}, {"gltf2", "gltf"}, {"glb2", "glb"},
           {"collada", "dae"}}) {
    const std::string path = tempPath("box_" + format + "." + ext);
    ASSERT_EQ(exporter.Export(scene, format, path), AI_SUCCESS) << format << ": " << exporter.GetErrorString();
    const auto mesh = srp::kb::TriangleMesh::load(path);
    EXPECT_EQ(mesh.size(), box.size()) << format;
    EXPECT_LT((mesh.bounds().min() - lo).norm(), kSizeTol_m) << format;
    EXPECT_LT((mesh.bounds().max() - hi).norm(), kSizeTol_m) << format;
    EXPECT_NEAR(mesh.volume(), (hi - lo).prod(), 1e-9) << format << ": outward winding kept";
  }
}

// The real cube of datasets/real/visp-rbt-cube: an OBJ with quads and a material.
TEST(TriangleMesh, LoadsTheRealCubesObj) {
  const auto mesh = srp::kb::TriangleMesh::load(std::string(SRP_DATASETS_DIR) + "/real/visp-rbt-cube/cube.obj");
  EXPECT_NEAR(mesh.bounds().sizes().x(), 0.085, 1e-6);
  EXPECT_NEAR(mesh.bounds().center().norm(), 0.0, 1e-6) << "centred, as stored";
  EXPECT_GT(mesh.size(), 11u);
  const auto samples = mesh.sampleSurface(0.004);
  EXPECT_GT(samples.size(), 6u * 400u) << "about (85 / 4)^2 per face";
}

TEST(TriangleMesh, IsClosedDetectsAHole) {
  auto box = srp::kb::makeBoxMesh({0, 0, 0}, {1, 1, 1});
  EXPECT_TRUE(box.isClosed());
  std::vector<srp::kb::TriangleMesh::Triangle> open(box.triangles().begin() + 1, box.triangles().end());
  EXPECT_FALSE(srp::kb::TriangleMesh(open).isClosed());
}

}  // namespace
