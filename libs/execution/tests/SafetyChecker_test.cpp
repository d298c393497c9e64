#include "srp/execution/SafetyChecker.h"

#include <gtest/gtest.h>

using srp::core::Pose3;
using namespace srp::execution;

namespace {
JointVector home() {
  JointVector q;
  q << -M_PI / 2, -1.6, 1.6, -1.57, -1.57, 0.0;
  return q;
}

JointTrajectory linear(const JointVector& a, const JointVector& b, double T) {
  std::vector<double> t;
  std::vector<JointVector> q;
  for (int i = 0; i <= 50; ++i) {
    t.push_back(T * i / 50.0);
    q.push_back(a + (b - a) * (i / 50.0));
  }
  return JointTrajectory::fromPositions(t, q);
}

SafetyChecker checker(std::vector<WorldBox> obstacles = {}) {
  Pose3 X_world_base = Pose3::Identity();
  X_world_base.translation() = Eigen::Vector3d(0, -0.35, 0);
  return SafetyChecker(RobotModel::defaultUr5(), X_world_base, SafetyLimits{}, std::move(obstacles));
}
}  // namespace

TEST(SafetyChecker, AcceptsASlowMoveAboveTheTable) {
  JointVector b = home();
  b[0] += 0.5;
  EXPECT_FALSE(checker().check(linear(home(), b, 2.0), "test move").has_value());
}

TEST(SafetyChecker, RefusesJointLimitViolation) {
  JointVector b = home();
  b[5] = 6.5;  // wrist 3 limit is +-2 pi; turning it moves no link
  const auto v = checker().check(linear(home(), b, 5.0), "Reach of cuboid");
  ASSERT_TRUE(v.has_value());
  EXPECT_EQ(v->check, "joint limit");
  EXPECT_NE(v->message.find("wrist_3_joint"), std::string::npos) << v->message;
  EXPECT_NE(v->message.find("Reach of cuboid"), std::string::npos) << v->message;
}

TEST(SafetyChecker, RefusesVelocityLimitViolation) {
  JointVector b = home();
  b[0] += 1.0;  // 1 rad in 0.2 s: 5 rad/s > pi rad/s
  const auto v = checker().check(linear(home(), b, 0.2), "fast move");
  ASSERT_TRUE(v.has_value());
  EXPECT_EQ(v->check, "velocity limit");
  EXPECT_NE(v->message.find("shoulder_pan_joint"), std::string::npos) << v->message;
}

TEST(SafetyChecker, PeakVelocityRatioIsTheFastestJointOverItsLimit) {
  JointVector b = home();
  b[0] += 1.0;  // 1 rad in 0.2 s: a 5 rad/s chord against the shoulder's pi rad/s
  const double fast = checker().peakVelocityRatio(linear(home(), b, 0.2));
  EXPECT_GE(fast, 5.0 / M_PI - 1e-9);
  EXPECT_LT(fast, 1.1 * 5.0 / M_PI);
  EXPECT_LT(checker().peakVelocityRatio(linear(home(), b, 2.0)), 1.0);
}

TEST(SafetyChecker, RefusesTablePenetration) {
  const SafetyChecker c = checker();
  JointVector down = home();
  down[1] = -0.6;  // shoulder lift down: wrist goes through the table
  ASSERT_LT(c.tableClearance_m(down), 0.0);
  const auto v = c.check(linear(home(), down, 5.0), "dive");
  ASSERT_TRUE(v.has_value());
  EXPECT_TRUE(v->check == "table" || v->check == "workspace") << v->message;
}

TEST(SafetyChecker, RefusesLeavingTheWorkspace) {
  SafetyLimits limits;
  limits.workspace_world_m = Eigen::AlignedBox3d(Eigen::Vector3d(-0.3, -0.3, 0.0), Eigen::Vector3d(0.3, 0.3, 0.5));
  Pose3 X_world_base = Pose3::Identity();
  X_world_base.translation() = Eigen::Vector3d(0, -0.35, 0);
  const SafetyChecker c(RobotModel::defaultUr5(), X_world_base, limits, {});
  JointVector b = home();
  b[0] += 1.5;
  const auto v = c.check(linear(home(), b, 5.0), "swing");
  ASSERT_TRUE(v.has_value());
  EXPECT_EQ(v->check, "workspace");
}

TEST(SafetyChecker, RefusesHittingAContainerWall) {
  const SafetyChecker free = checker();
  const auto spheres = free.armSpheres(home());
  // Put a wall right where the tool is.
  WorldBox wall;
  wall.owner = "gray box";
  wall.X_world_box.translation() = spheres.back().centre_world_m;
  wall.halfExtents_m = Eigen::Vector3d(0.1, 0.003, 0.03);
  const auto v = checker({wall}).check(JointTrajectory::hold(home(), 0.5), "Move of star");
  ASSERT_TRUE(v.has_value());
  EXPECT_EQ(v->check, "collision");
  EXPECT_NE(v->message.find("gray box"), std::string::npos) << v->message;
}
