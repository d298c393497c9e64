#include "srp/kb/ShapeMeshes.h"

#include <gtest/gtest.h>

#include <cmath>

#include "srp/core/Error.h"
#include "srp/kb/KnowledgeBase.h"

namespace {

constexpr double kDimensionTol_m = 1e-9;
constexpr double kVolumeRelTol = 1e-9;

// Every bundled class: a closed, outward-oriented mesh filling exactly its
// bounding box, with the object frame at the centre of the bottom face.
TEST(ShapeMeshes, CatalogueClassesFillTheirBoundingBoxInTheObjectFrame) {
  const auto catalogue = srp::kb::loadCatalogue(srp::core::ObjectCatalogue::defaultPath());
  ASSERT_GE(catalogue.classes().size(), 6u);
  for (const auto& c : catalogue.classes()) {
    SCOPED_TRACE(c.name);
    const auto mesh = srp::kb::makeClassMesh(c);
    const auto box = mesh.bounds();
    const Eigen::Vector3d expectedMin(-0.5 * c.dimensions_m.x(), -0.5 * c.dimensions_m.y(), 0.0);
    const Eigen::Vector3d expectedMax(0.5 * c.dimensions_m.x(), 0.5 * c.dimensions_m.y(), c.dimensions_m.z());
    EXPECT_LT((box.min() - expectedMin).norm(), kDimensionTol_m) << box.min().transpose();
    EXPECT_LT((box.max() - expectedMax).norm(), kDimensionTol_m) << box.max().transpose();
    EXPECT_TRUE(mesh.isClosed(1e-12));
    EXPECT_GT(mesh.volume(), 0.0) << "inward-facing mesh";
    EXPECT_LE(mesh.volume(), c.dimensions_m.prod() * (1.0 + kVolumeRelTol));
  }
}

TEST(ShapeMeshes, VolumesMatchClosedForms) {
  const Eigen::Vector3d d(0.22, 0.17, 0.06);
  const double t = 0.006;
  const double openBox = d.prod() - (d.x() - 2 * t) * (d.y() - 2 * t) * (d.z() - t);
  EXPECT_NEAR(srp::kb::makeOpenBoxMesh(d, t).volume(), openBox, kVolumeRelTol * openBox);
  // Regular octagon of apothem a: area 8 a^2 tan(pi/8).
  const double a = 0.02, h = 0.025;
  const double octagon = 8.0 * a * a * std::tan(M_PI / 8.0) * h;
  const auto oct = srp::kb::makePrismMesh(srp::kb::shapeOutline("octagon", {2 * a, 2 * a}), h);
  EXPECT_NEAR(oct.volume(), octagon, kVolumeRelTol * octagon);
  // Parallelogram: base 3/4 of the length times the width.
  const double para = 0.75 * 0.06 * 0.03 * h;
  EXPECT_NEAR(srp::kb::makePrismMesh(srp::kb::shapeOutline("parallelogram", {0.06, 0.03}), h).volume(), para,
              kVolumeRelTol * para);
}

// A part observed in a demonstration: a prism over its measured convex footprint.
TEST(ShapeMeshes, HullIsThePrismOverItsFootprint) {
  srp::core::ObjectClass c;
  c.name = "toy";
  c.shape = "hull";
  c.footprint_object = {{-0.05, -0.03}, {0.06, -0.03}, {0.06, 0.04}, {-0.05, 0.04}};  // 0.11 x 0.07 m
  c.dimensions_m = {0.11, 0.07, 0.2};
  const auto mesh = srp::kb::makeClassMesh(c);
  EXPECT_TRUE(mesh.isClosed(1e-12));
  const double volume = 0.11 * 0.07 * 0.2;
  EXPECT_NEAR(mesh.volume(), volume, kVolumeRelTol * volume);
  EXPECT_LT((mesh.bounds().max() - Eigen::Vector3d(0.06, 0.04, 0.2)).norm(), kDimensionTol_m);
  EXPECT_TRUE(srp::kb::hasShapeGenerator("hull"));
  c.footprint_object.resize(2);
  EXPECT_THROW(srp::kb::makeClassMesh(c), srp::core::InvalidInputError);
}

TEST(ShapeMeshes, UnknownShapeNamesTheClass) {
  srp::core::ObjectClass c;
  c.name = "teapot";
  c.shape = "teapot";
  c.dimensions_m = {0.1, 0.1, 0.1};
  try {
    srp::kb::makeClassMesh(c);
    FAIL();
  } catch (const srp::core::InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("teapot"), std::string::npos);
  }
  EXPECT_FALSE(srp::kb::hasShapeGenerator("teapot"));
}

// The committed meshes are what `srp kb build` generates.
TEST(ShapeMeshes, CommittedMeshesMatchTheGenerator) {
  constexpr double kFloat32Tol_m = 1e-7;
  const auto catalogue = srp::kb::loadCatalogue(srp::core::ObjectCatalogue::defaultPath());
  for (const auto& c : catalogue.classes()) {
    SCOPED_TRACE(c.meshPath);
    const auto committed = srp::kb::TriangleMesh::load(c.meshPath);
    const auto generated = srp::kb::makeClassMesh(c);
    ASSERT_EQ(committed.size(), generated.size());
    for (std::size_t i = 0; i < committed.size(); ++i)
      for (int v = 0; v < 3; ++v)
        ASSERT_LT((committed.triangles()[i][v] - generated.triangles()[i][v]).norm(), kFloat32Tol_m);
  }
}

}  // namespace
