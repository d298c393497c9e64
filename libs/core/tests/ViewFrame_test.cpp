#include "srp/core/ViewFrame.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "srp/core/Error.h"

using srp::core::Pose3;
using srp::core::ViewFrame;

namespace {
constexpr double kTol = 1e-9;

Pose3 camera(double yaw, double tilt) {
  // Looking down (180 deg about x), then turned about the world z and tilted about the camera x.
  Pose3 X = Pose3::Identity();
  X.linear() = (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitX()) *
                Eigen::AngleAxisd(tilt, Eigen::Vector3d::UnitX()))
                   .toRotationMatrix();
  X.translation() = Eigen::Vector3d(0, 0.1, 0.85);
  return X;
}
}  // namespace

TEST(ViewFrame, CameraLookingDownGivesImageAxesOnTheTable) {
  const ViewFrame v = ViewFrame::fromCamera(camera(0.0, 0.0));
  EXPECT_NEAR((v.right_world - Eigen::Vector2d(1, 0)).norm(), 0.0, kTol);
  EXPECT_NEAR((v.front_world - Eigen::Vector2d(0, -1)).norm(), 0.0, kTol);  // image down = towards the viewer
  EXPECT_NEAR((*v.direction("left of") - Eigen::Vector2d(-1, 0)).norm(), 0.0, kTol);
  EXPECT_NEAR((*v.direction("to the right of") - Eigen::Vector2d(1, 0)).norm(), 0.0, kTol);
  EXPECT_NEAR((*v.direction("in front of") - Eigen::Vector2d(0, -1)).norm(), 0.0, kTol);
  EXPECT_NEAR((*v.direction("behind") - Eigen::Vector2d(0, 1)).norm(), 0.0, kTol);
  EXPECT_FALSE(v.direction("next to"));
  EXPECT_FALSE(v.direction("in"));
}

TEST(ViewFrame, TurnedAndTiltedCameraTurnsTheFrame) {
  const ViewFrame v = ViewFrame::fromCamera(camera(M_PI / 2, 0.4));
  EXPECT_NEAR((v.right_world - Eigen::Vector2d(0, 1)).norm(), 0.0, kTol);
  EXPECT_NEAR((v.front_world - Eigen::Vector2d(1, 0)).norm(), 0.0, kTol);
  EXPECT_NEAR(v.right_world.dot(v.front_world), 0.0, kTol);
}

TEST(ViewFrame, RobotViewLooksFromTheBaseAtTheTarget) {
  Pose3 base = Pose3::Identity();
  base.translation() = Eigen::Vector3d(0, -0.3, 0);
  const ViewFrame v = ViewFrame::fromRobot(base, Eigen::Vector2d(0, 0));
  EXPECT_NEAR((v.right_world - Eigen::Vector2d(1, 0)).norm(), 0.0, kTol);
  EXPECT_NEAR((v.front_world - Eigen::Vector2d(0, -1)).norm(), 0.0, kTol);  // towards the robot
  const ViewFrame side = ViewFrame::fromRobot(base, Eigen::Vector2d(0.5, -0.3));
  EXPECT_NEAR((side.right_world - Eigen::Vector2d(0, -1)).norm(), 0.0, kTol);
}

TEST(ViewFrame, VerticalCameraXAxisIsRejected) {
  Pose3 X = Pose3::Identity();
  X.linear() = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitY()).toRotationMatrix();  // x -> -z
  EXPECT_THROW(ViewFrame::fromCamera(X), srp::core::InvalidInputError);
}
