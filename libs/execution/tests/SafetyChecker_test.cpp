#include "srp/execution/SafetyChecker.h"

#include <gtest/gtest.h>

#include "srp/core/Error.h"

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

/// a -> b in T seconds with the minimum-jerk time law (at rest at both ends): peak
/// speed 1.875 |b - a| / T, peak acceleration 5.774 |b - a| / T^2.
JointTrajectory smooth(const JointVector& a, const JointVector& b, double T) {
  std::vector<double> t;
  std::vector<JointVector> q;
  for (int i = 0; i <= 200; ++i) {
    const double tau = i / 200.0, s = tau * tau * tau * (10 - 15 * tau + 6 * tau * tau);
    t.push_back(T * tau);
    q.push_back(a + (b - a) * s);
  }
  return JointTrajectory::fromPositions(t, q);
}

SafetyChecker checker(std::vector<WorldBox> obstacles = {}, SafetyLimits limits = {}) {
  Pose3 X_world_base = Pose3::Identity();
  X_world_base.translation() = Eigen::Vector3d(0, -0.35, 0);
  return SafetyChecker(RobotModel::defaultUr5(), X_world_base, limits, std::move(obstacles));
}

// Peak acceleration of the minimum-jerk law, 10 sqrt(3) / 3 |b - a| / T^2.
constexpr double kMinJerkPeakAcceleration = 5.773502691896258;
constexpr double kAccelerationTol = 0.02;  // relative: the 200-sample spline vs the analytic law
}  // namespace

TEST(SafetyChecker, AcceptsASlowMoveAboveTheTable) {
  JointVector b = home();
  b[0] += 0.5;
  EXPECT_FALSE(checker().check(smooth(home(), b, 2.0), "test move").has_value());
}

TEST(SafetyChecker, RefusesJointLimitViolation) {
  JointVector b = home();
  b[5] = 6.5;  // wrist 3 limit is +-2 pi; turning it moves no link
  const auto v = checker().check(smooth(home(), b, 5.0), "Reach of cuboid");
  ASSERT_TRUE(v.has_value());
  EXPECT_EQ(v->check, "joint limit");
  EXPECT_NE(v->message.find("wrist_3_joint"), std::string::npos) << v->message;
  EXPECT_NE(v->message.find("Reach of cuboid"), std::string::npos) << v->message;
}

TEST(SafetyChecker, RefusesVelocityLimitViolation) {
  JointVector b = home();
  b[0] += 1.0;  // 1 rad in 0.2 s: 5 rad/s > pi rad/s
  SafetyLimits noAccelerationLimit;  // the speed alone (the jump from rest breaks any acceleration limit)
  noAccelerationLimit.maxAcceleration_radps2 = 1e6;
  const auto v = checker({}, noAccelerationLimit).check(linear(home(), b, 0.2), "fast move");
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

TEST(SafetyChecker, RefusesAccelerationLimitViolation) {
  JointVector b = home();
  b[1] -= 1.0;  // shoulder lift 1 rad up in 1 s, minimum jerk: 1.9 rad/s (< pi), 5.8 rad/s^2 (> 5)
  const SafetyChecker c = checker();
  ASSERT_DOUBLE_EQ(c.limits().maxAcceleration_radps2, 5.0);  // UR's MoveIt limit, the default
  const JointTrajectory fast = smooth(home(), b, 1.0);
  EXPECT_LT(c.peakVelocityRatio(fast), 1.0);
  EXPECT_NEAR(SafetyChecker::peakSplineAcceleration_radps2(fast), kMinJerkPeakAcceleration,
              kAccelerationTol * kMinJerkPeakAcceleration);
  const auto v = c.check(fast, "Move of the star");
  ASSERT_TRUE(v.has_value());
  EXPECT_EQ(v->check, "acceleration limit");
  EXPECT_NE(v->message.find("shoulder_lift_joint"), std::string::npos) << v->message;
  EXPECT_NE(v->message.find("Move of the star"), std::string::npos) << v->message;
  EXPECT_NE(v->message.find("above its limit 5.00 rad/s^2"), std::string::npos) << v->message;
  // The same path 10 % slower: 5.8 / 1.1^2 = 4.8 rad/s^2, accepted.
  const auto slower = c.check(smooth(home(), b, 1.1), "Move of the star");
  EXPECT_FALSE(slower.has_value()) << slower->message;
  // A configured limit (srp execute --max-acceleration) is the one checked.
  SafetyLimits lax;
  lax.maxAcceleration_radps2 = 6.0;
  EXPECT_FALSE(checker({}, lax).check(fast, "Move of the star").has_value());
  SafetyLimits bad;
  bad.maxAcceleration_radps2 = 0.0;
  EXPECT_THROW(checker({}, bad), srp::core::InvalidInputError);
}

TEST(SafetyChecker, SlowingDownByKDividesTheAccelerationRatioByKSquared) {
  JointVector b = home();
  b[3] -= 0.8;
  const SafetyChecker c = checker();
  const double r1 = c.peakAccelerationRatio(smooth(home(), b, 0.5));
  const double r2 = c.peakAccelerationRatio(smooth(home(), b, 1.0));
  EXPECT_GT(r1, 1.0);
  EXPECT_NEAR(r2, r1 / 4.0, 1e-9 * r1);
}

TEST(SafetyChecker, RefusesTablePenetration) {
  const SafetyChecker c = checker();
  JointVector down = home();
  down[1] = -0.6;  // shoulder lift down: wrist goes through the table
  ASSERT_LT(c.tableClearance_m(down), 0.0);
  const auto v = c.check(smooth(home(), down, 5.0), "dive");
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
  const auto v = c.check(smooth(home(), b, 5.0), "swing");
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
