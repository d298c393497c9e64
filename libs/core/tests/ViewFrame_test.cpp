#include "srp/core/ViewFrame.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "srp/core/Error.h"
#include "srp/core/Scene.h"

using namespace srp::core;

namespace {
constexpr double kUnitTol = 1e-9;

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
  EXPECT_NEAR((v.right_world - Eigen::Vector2d(1, 0)).norm(), 0.0, kUnitTol);
  EXPECT_NEAR((v.front_world - Eigen::Vector2d(0, -1)).norm(), 0.0, kUnitTol);  // image down = towards the viewer
  EXPECT_NEAR((*v.direction("left of") - Eigen::Vector2d(-1, 0)).norm(), 0.0, kUnitTol);
  EXPECT_NEAR((*v.direction("to the right of") - Eigen::Vector2d(1, 0)).norm(), 0.0, kUnitTol);
  EXPECT_NEAR((*v.direction("in front of") - Eigen::Vector2d(0, -1)).norm(), 0.0, kUnitTol);
  EXPECT_NEAR((*v.direction("behind") - Eigen::Vector2d(0, 1)).norm(), 0.0, kUnitTol);
  EXPECT_NEAR((*v.direction("at the back of") - Eigen::Vector2d(0, 1)).norm(), 0.0, kUnitTol);
  EXPECT_FALSE(v.direction("next to"));
  EXPECT_FALSE(v.direction("in"));
  EXPECT_FALSE(v.direction("in the front left corner of"));
  EXPECT_FALSE(v.direction("back to"));  // a return to where the part was, not "behind"
}

TEST(ViewFrame, DefaultSceneCameraAndRobotAgreeRightIsWorldX) {
  const Scene scene = Scene::load(std::string(SRP_SIM_DIR) + "/scenes/default.json");
  const ViewFrame view = ViewFrame::fromCamera(scene.X_world_camera);
  // Camera rotated by pi about world x: image x = world +x, image y (down) = world -y.
  EXPECT_NEAR((view.right_world - Eigen::Vector2d::UnitX()).norm(), 0.0, kUnitTol);
  EXPECT_NEAR((view.front_world + Eigen::Vector2d::UnitY()).norm(), 0.0, kUnitTol);
  // The robot (base at y = -0.38, looking at the table centre = world origin) sees the same left/right there.
  const ViewFrame robot = ViewFrame::fromRobot(scene.X_world_base, Eigen::Vector2d::Zero());
  EXPECT_NEAR((robot.right_world - Eigen::Vector2d::UnitX()).norm(), 0.0, kUnitTol);
  EXPECT_NEAR((robot.front_world + Eigen::Vector2d::UnitY()).norm(), 0.0, kUnitTol);
  EXPECT_GT(view.rightOf({0.1, 0.0, 0.0}), view.rightOf({-0.1, 0.0, 0.0}));
  EXPECT_GT(view.frontOf({0.0, -0.1, 0.0}), view.frontOf({0.0, 0.1, 0.0}));
}

TEST(ViewFrame, TurnedAndTiltedCameraTurnsTheFrame) {
  const ViewFrame v = ViewFrame::fromCamera(camera(M_PI / 2, 0.4));
  EXPECT_NEAR((v.right_world - Eigen::Vector2d(0, 1)).norm(), 0.0, kUnitTol);
  EXPECT_NEAR((v.front_world - Eigen::Vector2d(1, 0)).norm(), 0.0, kUnitTol);
  EXPECT_NEAR(v.right_world.dot(v.front_world), 0.0, kUnitTol);
}

TEST(ViewFrame, TiltedAndTurnedCameraGivesItsImageAxesOnTheTable) {
  // A camera turned by 90 degrees about the vertical and tilted 30 degrees: the
  // image's right is world +y, its "down" leans towards world +x.
  Pose3 X = Pose3::Identity();
  X.linear() = (Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(M_PI - 0.5, Eigen::Vector3d::UnitX()))
                   .toRotationMatrix();
  const ViewFrame view = ViewFrame::fromCamera(X);
  EXPECT_NEAR((view.right_world - Eigen::Vector2d::UnitY()).norm(), 0.0, kUnitTol);
  EXPECT_NEAR((view.front_world - Eigen::Vector2d::UnitX()).norm(), 0.0, kUnitTol);
  EXPECT_NEAR(view.right_world.dot(view.front_world), 0.0, kUnitTol);
  EXPECT_NEAR((*view.direction("left") + view.right_world).norm(), 0.0, kUnitTol);
  EXPECT_NEAR((*view.direction("behind") + view.front_world).norm(), 0.0, kUnitTol);
  EXPECT_NEAR((*view.direction("back") + view.front_world).norm(), 0.0, kUnitTol);
  EXPECT_FALSE(view.direction("up"));
  EXPECT_EQ(ViewFrame::directionWord("front"), "front");
  EXPECT_EQ(ViewFrame::directionWord("up"), "");
}

TEST(ViewFrame, RobotViewLooksFromTheBaseAtTheTarget) {
  Pose3 base = Pose3::Identity();
  base.translation() = Eigen::Vector3d(0, -0.3, 0);
  const ViewFrame v = ViewFrame::fromRobot(base, Eigen::Vector2d(0, 0));
  EXPECT_NEAR((v.right_world - Eigen::Vector2d(1, 0)).norm(), 0.0, kUnitTol);
  EXPECT_NEAR((v.front_world - Eigen::Vector2d(0, -1)).norm(), 0.0, kUnitTol);  // towards the robot
  const ViewFrame side = ViewFrame::fromRobot(base, Eigen::Vector2d(0.5, -0.3));
  EXPECT_NEAR((side.right_world - Eigen::Vector2d(0, -1)).norm(), 0.0, kUnitTol);
}

TEST(ViewFrame, CameraWithVerticalXAxisIsRefused) {
  Pose3 X = Pose3::Identity();
  X.linear() = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitY()).toRotationMatrix();  // x axis points down
  EXPECT_THROW(ViewFrame::fromCamera(X), InvalidInputError);
  EXPECT_EQ(viewpointFromString("robot"), Viewpoint::Robot);
  EXPECT_EQ(viewpointFromString("camera"), Viewpoint::Demonstrator);
  EXPECT_EQ(toString(Viewpoint::Robot), "robot");
  EXPECT_THROW(viewpointFromString("sideways"), InvalidInputError);
}
