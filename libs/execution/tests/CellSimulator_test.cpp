#include "srp/execution/CellSimulator.h"

#include <gtest/gtest.h>

#include "srp/execution/UrInverseKinematics.h"

using srp::core::Pose3;
using namespace srp::execution;

namespace {
constexpr double kHoldTol_rad = 2e-3;         // gravity compensated: no sag while holding
constexpr double kTrackingTol_rad = 2e-3;     // end of a tracked trajectory
constexpr double kRestHeightTol_m = 1e-3;     // penalty contact sinks g / omega^2 = 27 um
constexpr double kRestDriftTol_m = 2e-3;      // a dropped part lands where it was dropped
constexpr double kCarryTol_m = 5e-3;          // carried part ends near the commanded place

/// Down-pointing tcp orientation (tool z = world -z).
Pose3 downPose(const Eigen::Vector3d& p_world) {
  Pose3 X = Pose3::Identity();
  X.linear() = Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitX()).toRotationMatrix();
  X.translation() = p_world;
  return X;
}

/// Minimum-jerk joint-space move from qa to qb over T seconds.
JointTrajectory jointMove(const JointVector& qa, const JointVector& qb, double T) {
  std::vector<double> t;
  std::vector<JointVector> q;
  const int n = static_cast<int>(T / 0.01);
  for (int i = 0; i <= n; ++i) {
    const double s = static_cast<double>(i) / n;
    const double mj = 10 * s * s * s - 15 * s * s * s * s + 6 * s * s * s * s * s;
    t.push_back(i * T / n);
    q.push_back(qa + (qb - qa) * mj);
  }
  return JointTrajectory::fromPositions(t, q);
}

struct Fixture {
  RobotModel model = RobotModel::defaultUr5();
  UrInverseKinematics ik{model};
  CellDescription cell;
  JointVector qHome;
  Fixture() {
    cell.X_world_base = Pose3::Identity();
    cell.X_world_base.translation() = Eigen::Vector3d(0.0, -0.35, 0.0);
    qHome << -M_PI / 2, -1.6, 1.6, -1.57, -1.57, 0.0;
  }
  JointVector ikWorld(const Pose3& X_world_tcp, const JointVector& near) const {
    const auto q = ik.solveNearestTcp(cell.X_world_base.inverse() * X_world_tcp, near);
    EXPECT_TRUE(q.has_value());
    return *q;
  }
};

CellObject part(const std::string& name, const Eigen::Vector3d& p) {
  CellObject o;
  o.name = name;
  o.kind = CellObjectKind::Part;
  o.size_m = Eigen::Vector3d(0.05, 0.03, 0.03);
  o.mass_kg = 0.06;
  o.X_world_object.translation() = p;
  return o;
}
}  // namespace

TEST(CellSimulator, HoldsPoseAgainstGravity) {
  Fixture f;
  CellSimulator sim(f.model, f.cell, f.qHome);
  sim.settle(1.0);
  const double err = (sim.jointPositions() - f.qHome).cwiseAbs().maxCoeff();
  EXPECT_LT(err, kHoldTol_rad);
  EXPECT_NEAR(sim.time_s(), 1.0, 1e-9);
}

TEST(CellSimulator, TracksAJointTrajectory) {
  Fixture f;
  CellSimulator sim(f.model, f.cell, f.qHome);
  const JointVector qGoal = f.ikWorld(downPose({0.2, 0.1, 0.25}), f.qHome);
  const TrackingResult r = sim.track(jointMove(f.qHome, qGoal, 1.5));
  EXPECT_LT(r.finalJointError_rad, kTrackingTol_rad);
  EXPECT_LT(r.maxJointError_rad, 0.02);
  EXPECT_GT(r.minTableClearance_m, 0.03);  // the shoulder stands 0.089 m above the table
  EXPECT_EQ(r.torqueSaturations, 0);
  const Pose3 X = sim.X_world_tcp();
  EXPECT_LT((X.translation() - Eigen::Vector3d(0.2, 0.1, 0.25)).norm(), 2e-3);
  std::cout << "sim " << sim.time_s() << " s in " << sim.wallSeconds() << " s wall\n";
}

TEST(CellSimulator, DroppedPartFallsAndRestsOnTheTable) {
  Fixture f;
  f.cell.objects.push_back(part("cuboid", {0.3, 0.2, 0.02}));
  CellSimulator sim(f.model, f.cell, f.qHome);
  sim.settle(0.6);
  const Pose3 X = sim.X_world_part("cuboid");
  EXPECT_NEAR(X.translation().z(), 0.0, kRestHeightTol_m);
  EXPECT_LT((X.translation().head<2>() - Eigen::Vector2d(0.3, 0.2)).norm(), kRestDriftTol_m);
  EXPECT_LT(srp::core::rotationAngleBetween(X.linear(), Eigen::Matrix3d::Identity()), 0.01);
  std::cout << "sim " << sim.time_s() << " s in " << sim.wallSeconds() << " s wall\n";
}

TEST(CellSimulator, PartRestsOnContainerFloor) {
  Fixture f;
  CellObject box;
  box.name = "gray box";
  box.kind = CellObjectKind::Container;
  box.size_m = Eigen::Vector3d(0.25, 0.2, 0.06);
  box.wallThickness_m = 0.006;
  box.X_world_object.translation() = Eigen::Vector3d(0.3, 0.1, 0.0);
  f.cell.objects.push_back(box);
  f.cell.objects.push_back(part("cuboid", {0.3, 0.1, 0.03}));
  CellSimulator sim(f.model, f.cell, f.qHome);
  sim.settle(0.6);
  EXPECT_NEAR(sim.X_world_part("cuboid").translation().z(), box.wallThickness_m, kRestHeightTol_m);
}

TEST(CellSimulator, GraspCarriesAPartAndReleaseDropsIt) {
  Fixture f;
  const Eigen::Vector3d start(0.25, 0.15, 0.0), goal(0.05, 0.25, 0.0);
  f.cell.objects.push_back(part("cuboid", start));
  const double h = f.cell.objects.back().size_m.z();
  CellSimulator sim(f.model, f.cell, f.qHome);
  // Too far away: refused with a reason.
  EXPECT_TRUE(sim.grasp("cuboid").has_value());
  const JointVector qAbove = f.ikWorld(downPose(start + Eigen::Vector3d(0, 0, h + 0.05)), f.qHome);
  const JointVector qOn = f.ikWorld(downPose(start + Eigen::Vector3d(0, 0, h)), qAbove);
  sim.track(jointMove(f.qHome, qAbove, 1.0));
  sim.track(jointMove(qAbove, qOn, 0.5));
  const auto failure = sim.grasp("cuboid");
  ASSERT_FALSE(failure.has_value()) << *failure;
  const JointVector qLift = f.ikWorld(downPose(start + Eigen::Vector3d(0, 0, h + 0.08)), qOn);
  const JointVector qDrop = f.ikWorld(downPose(goal + Eigen::Vector3d(0, 0, h + 0.004)), qLift);
  sim.track(jointMove(qOn, qLift, 0.6));
  EXPECT_GT(sim.X_world_part("cuboid").translation().z(), 0.07);  // lifted with the tool
  sim.track(jointMove(qLift, qDrop, 1.2));
  sim.release();
  const JointVector qRetreat = f.ikWorld(downPose(goal + Eigen::Vector3d(0, 0, h + 0.06)), qDrop);
  sim.track(jointMove(qDrop, qRetreat, 0.5), 0.3);
  const Pose3 X = sim.X_world_part("cuboid");
  EXPECT_NEAR(X.translation().z(), 0.0, kRestHeightTol_m);
  EXPECT_LT((X.translation().head<2>() - goal.head<2>()).norm(), kCarryTol_m);
  EXPECT_FALSE(sim.graspedPart().has_value());
  std::cout << "sim " << sim.time_s() << " s in " << sim.wallSeconds() << " s wall\n";
}
