// Plane geometry against known configurations.
#include <gtest/gtest.h>

#include <cmath>

#include "srp/perception/PlaneFit.h"

namespace srp::perception {
namespace {

constexpr double kDepthTol_m = 1e-9;

// A table 0.8 m in front of a camera looking straight at it: every ray
// through a pixel (x, y, 1) meets it at depth 0.8 m, and the plane raised by
// h at depth 0.8 - h.
TEST(Plane, RayScaleAtHeightFacingTheCamera) {
  Plane table;
  table.n = Eigen::Vector3d(0, 0, -1);  // towards the camera
  table.d = 0.8;
  for (const Eigen::Vector3d ray : {Eigen::Vector3d(0, 0, 1), Eigen::Vector3d(0.2, -0.1, 1)}) {
    ASSERT_TRUE(table.rayScaleAtHeight(ray).has_value());
    EXPECT_NEAR(*table.rayScaleAtHeight(ray), 0.8, kDepthTol_m);
    EXPECT_NEAR(*table.rayScaleAtHeight(ray, 0.1), 0.7, kDepthTol_m);
  }
  // A ray of twice the length meets it at half the scale.
  EXPECT_NEAR(*table.rayScaleAtHeight(Eigen::Vector3d(0, 0, 2)), 0.4, kDepthTol_m);
}

// A table 1 m below a camera that looks 30 deg down (camera y points down in
// the image, z forwards): the optical axis meets it at 1 / sin 30 = 2 m; a
// ray parallel to the table never does; a ray upwards meets it behind the camera.
TEST(Plane, RayScaleAtHeightOfATiltedTable) {
  const double tilt = 30.0 * M_PI / 180.0, h = 1.0;
  // World up in the camera frame: mostly image up (-y), and against the
  // optical axis, which points down by the tilt.
  Plane table;
  table.n = Eigen::Vector3d(0, -std::cos(tilt), -std::sin(tilt));
  table.d = h;
  ASSERT_NEAR(table.height(Eigen::Vector3d::Zero()), h, kDepthTol_m);
  const auto axis = table.rayScaleAtHeight(Eigen::Vector3d(0, 0, 1));
  ASSERT_TRUE(axis.has_value());
  EXPECT_NEAR(*axis, h / std::sin(tilt), kDepthTol_m);
  // Any ray: the point found lies at the asked height.
  for (const double height_m : {0.0, 0.25}) {
    const Eigen::Vector3d ray(-0.3, 0.2, 1.0);
    const auto s = table.rayScaleAtHeight(ray, height_m);
    ASSERT_TRUE(s.has_value());
    EXPECT_NEAR(table.height(*s * ray), height_m, kDepthTol_m);
  }
  const Eigen::Vector3d parallel(0, std::sin(tilt), -std::cos(tilt));  // along the table, perpendicular to n
  ASSERT_NEAR(table.n.dot(parallel), 0.0, 1e-12);
  EXPECT_FALSE(table.rayScaleAtHeight(parallel).has_value());
  EXPECT_FALSE(table.rayScaleAtHeight(Eigen::Vector3d(0, -1, 0.1)).has_value()) << "upwards: behind the camera";
  EXPECT_FALSE(table.rayScaleAtHeight(Eigen::Vector3d(0, 0, 1), 1.5).has_value()) << "above the camera";
}

}  // namespace
}  // namespace srp::perception
