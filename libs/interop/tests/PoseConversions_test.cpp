#include "srp/interop/PoseConversions.h"

#include <gtest/gtest.h>

#include <mrpt/poses/CPose3D.h>
#include <visp3/core/vpHomogeneousMatrix.h>

using srp::core::Pose3;
using namespace srp::interop;

namespace {
constexpr double kExact = 1e-12;  // conversions only copy or multiply doubles

Pose3 samplePose() { return srp::core::makePoseYPR({0.12, -0.34, 0.56}, 0.7, -0.3, 1.1); }
}  // namespace

TEST(PoseConversions, ViSPRoundTripAndMeaning) {
  const Pose3 X = samplePose();
  const vpHomogeneousMatrix M = toVisp(X);
  const vpColVector p_b({0.3, 0.2, 0.1, 1.0});
  const vpColVector p_a = M * p_b;
  const Eigen::Vector3d expected = X * Eigen::Vector3d(0.3, 0.2, 0.1);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(p_a[i], expected[i], kExact);
  const Pose3 back = fromVisp(M);
  EXPECT_LT((back.matrix() - X.matrix()).cwiseAbs().maxCoeff(), kExact);
}

TEST(PoseConversions, MrptRoundTripAndYprConvention) {
  const Pose3 X = samplePose();
  const mrpt::poses::CPose3D P = toMrpt(X);
  EXPECT_NEAR(P.yaw(), 0.7, 1e-12);
  EXPECT_NEAR(P.pitch(), -0.3, 1e-12);
  EXPECT_NEAR(P.roll(), 1.1, 1e-12);
  EXPECT_NEAR(P.x(), 0.12, kExact);
  const Pose3 back = fromMrpt(P);
  EXPECT_LT((back.matrix() - X.matrix()).cwiseAbs().maxCoeff(), kExact);
}
