#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "srp/core/CameraIntrinsics.h"
#include "srp/core/Error.h"

using srp::core::CameraIntrinsics;

namespace {
constexpr double kPixelTol_px = 1e-9;
constexpr double kPositionTol_m = 1e-12;
const CameraIntrinsics kL515{607.178, 607.234, 321.391, 241.918, 640, 480};
}  // namespace

TEST(CameraIntrinsics, BackProjectionIsPinholeInverse) {
  // SPEC.md: X = (u - cx) Z / fx. A point 0.1 m right of the axis at 0.5 m depth
  // lands fx * 0.2 px right of cx.
  const Eigen::Vector3d p = kL515.backProject(321.391 + 607.178 * 0.2, 241.918, 0.5);
  EXPECT_NEAR(p.x(), 0.1, kPositionTol_m);
  EXPECT_NEAR(p.y(), 0.0, kPositionTol_m);
  EXPECT_NEAR(p.z(), 0.5, kPositionTol_m);
  for (double u : {0.0, 100.5, 639.0})
    for (double v : {0.0, 240.0, 479.0}) {
      const auto uv = kL515.project(kL515.backProject(u, v, 0.73));
      ASSERT_TRUE(uv);
      EXPECT_NEAR(uv->x(), u, kPixelTol_px);
      EXPECT_NEAR(uv->y(), v, kPixelTol_px);
    }
  EXPECT_FALSE(kL515.project({0.0, 0.0, -1.0}));
}

TEST(CameraIntrinsics, JsonRoundTripAndValidation) {
  const nlohmann::json j = kL515;
  EXPECT_EQ(j.get<CameraIntrinsics>(), kL515);
  nlohmann::json bad = j;
  bad.erase("fy");
  EXPECT_THROW(bad.get<CameraIntrinsics>(), srp::core::InvalidInputError);
  CameraIntrinsics zero = kL515;
  zero.fx_px = 0;
  EXPECT_THROW(zero.validate("camera.json"), srp::core::InvalidInputError);
}
