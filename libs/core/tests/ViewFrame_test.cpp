#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "srp/core/Error.h"
#include "srp/core/Scene.h"
#include "srp/core/ViewFrame.h"

using namespace srp::core;

namespace {
constexpr double kUnitTol = 1e-9;
}

TEST(ViewFrame, DefaultSceneCameraLooksDownWithRightAlongWorldX) {
  const Scene scene = Scene::load(std::string(SRP_SIM_DIR) + "/scenes/default.json");
  const ViewFrame view = ViewFrame::fromCamera(scene.X_world_camera);
  // Camera rotated by pi about world x: image x = world +x, image y (down) = world -y.
  EXPECT_NEAR((view.right_world - Eigen::Vector2d::UnitX()).norm(), 0.0, kUnitTol);
  EXPECT_NEAR((view.front_world + Eigen::Vector2d::UnitY()).norm(), 0.0, kUnitTol);
  // The robot (base at y = -0.3, x axis towards +y) sees the same left/right there.
  const ViewFrame robot = ViewFrame::fromRobot(scene.X_world_base);
  EXPECT_NEAR((robot.right_world - Eigen::Vector2d::UnitX()).norm(), 0.0, kUnitTol);
  EXPECT_NEAR((robot.front_world + Eigen::Vector2d::UnitY()).norm(), 0.0, kUnitTol);
  EXPECT_GT(view.rightOf({0.1, 0.0, 0.0}), view.rightOf({-0.1, 0.0, 0.0}));
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
  EXPECT_NEAR((view.direction("left") + view.right_world).norm(), 0.0, kUnitTol);
  EXPECT_NEAR((view.direction("behind") + view.front_world).norm(), 0.0, kUnitTol);
  EXPECT_THROW(view.direction("up"), InvalidInputError);
}

TEST(ViewFrame, CameraWithVerticalXAxisIsRefused) {
  Pose3 X = Pose3::Identity();
  X.linear() = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitY()).toRotationMatrix();  // x axis points down
  EXPECT_THROW(ViewFrame::fromCamera(X), InvalidInputError);
  EXPECT_EQ(viewpointFromString("robot"), Viewpoint::Robot);
  EXPECT_THROW(viewpointFromString("sideways"), InvalidInputError);
}
