#include <gtest/gtest.h>

#include "srp/core/Error.h"
#include "srp/core/Json.h"
#include "srp/core/Pose.h"

using namespace srp::core;

namespace {
constexpr double kExact = 1e-12;  // conversions only copy or multiply doubles

Pose3 samplePose() {
  return makePoseYPR({0.12, -0.34, 0.56}, 0.7, -0.3, 1.1);
}
}  // namespace

TEST(Pose, ComposesWithFrameNamesAndInverts) {
  const Pose3 X_base_camera = makePoseYPR({0.5, 0.0, 1.2}, M_PI / 2, 0.0, M_PI);
  const Pose3 X_camera_object = makePose({0.1, 0.2, 0.8}, Eigen::Quaterniond::Identity());
  const Pose3 X_base_object = X_base_camera * X_camera_object;
  // Camera at 1.2 m looking down (roll pi), rotated 90 deg about z.
  EXPECT_NEAR(X_base_object.translation().z(), 1.2 - 0.8, kExact);
  const Pose3 back = X_base_camera.inverse() * X_base_object;
  EXPECT_NEAR(translationDistance(back, X_camera_object), 0.0, kExact);
  EXPECT_NEAR(rotationAngleBetween(back.linear(), X_camera_object.linear()), 0.0, 1e-7);
}

TEST(Pose, YawOfYprRoundTrips) {
  for (double yaw : {-3.0, -1.0, 0.0, 0.4, 3.1}) {
    const Pose3 X = makePoseYPR(Eigen::Vector3d::Zero(), yaw, 0.2, -0.1);
    EXPECT_NEAR(yawOf(X.linear()), yaw, kExact) << "yaw " << yaw;
  }
  EXPECT_NEAR(angleDifference(3.1, -3.1), 6.2 - 2 * M_PI, kExact);
  EXPECT_NEAR(angleDifference(-3.1, 3.1), 2 * M_PI - 6.2, kExact);
}

TEST(Json, PoseRoundTripAndMatrixForm) {
  const Pose3 X = samplePose();
  const Pose3 back = poseFromJson(poseToJson(X), "test pose");
  EXPECT_LT((back.matrix() - X.matrix()).cwiseAbs().maxCoeff(), 1e-12);
  nlohmann::json m = {{"matrix", {1, 0, 0, 0.5, 0, 1, 0, 0.25, 0, 0, 1, -1, 0, 0, 0, 1}}};
  EXPECT_NEAR(poseFromJson(m, "m").translation().z(), -1.0, kExact);
  EXPECT_THROW(poseFromJson(nlohmann::json{{"translation", {1, 2, 3}}}, "no rotation"),
               srp::core::InvalidInputError);
}
