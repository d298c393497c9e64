#include "srp/kb/TriangleMesh.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

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
  const auto back = srp::kb::TriangleMesh::loadStl(path);
  ASSERT_EQ(back.size(), mesh.size());
  for (std::size_t i = 0; i < mesh.size(); ++i)
    for (int v = 0; v < 3; ++v)
      EXPECT_LT((back.triangles()[i][v] - mesh.triangles()[i][v]).norm(), kFloat32Tol_m);
  EXPECT_TRUE(back.isClosed(1e-6));
}

TEST(TriangleMesh, LoadRejectsMissingAndTruncatedFiles) {
  EXPECT_THROW(srp::kb::TriangleMesh::loadStl(tempPath("does_not_exist.stl")), srp::core::FileError);
  const std::string path = tempPath("truncated.stl");
  srp::kb::makeBoxMesh({0, 0, 0}, {1, 1, 1}).saveStl(path);
  std::filesystem::resize_file(path, 84 + 50 * 3);
  try {
    srp::kb::TriangleMesh::loadStl(path);
    FAIL() << "truncated STL accepted";
  } catch (const srp::core::FileError& e) {
    EXPECT_NE(std::string(e.what()).find("truncated.stl"), std::string::npos) << e.what();
  }
}

TEST(TriangleMesh, IsClosedDetectsAHole) {
  auto box = srp::kb::makeBoxMesh({0, 0, 0}, {1, 1, 1});
  EXPECT_TRUE(box.isClosed());
  std::vector<srp::kb::TriangleMesh::Triangle> open(box.triangles().begin() + 1, box.triangles().end());
  EXPECT_FALSE(srp::kb::TriangleMesh(open).isClosed());
}

}  // namespace
