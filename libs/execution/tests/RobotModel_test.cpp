#include "srp/execution/RobotModel.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <filesystem>
#include <fstream>

#include "srp/core/Error.h"

using srp::execution::JointVector;
using srp::execution::RobotModel;

namespace {
constexpr double kPublishedPositionTol_m = 1e-6;  // README values are given to 1 micrometre
constexpr double kMassTol_kg = 1e-9;
}  // namespace

TEST(RobotModel, ParsesSixRevoluteJointsWithLimits) {
  const RobotModel ur5 = RobotModel::defaultUr5();
  const char* names[] = {"shoulder_pan_joint", "shoulder_lift_joint", "elbow_joint",
                         "wrist_1_joint",      "wrist_2_joint",       "wrist_3_joint"};
  for (int i = 0; i < 6; ++i) {
    EXPECT_EQ(ur5.joints()[i].name, names[i]);
    EXPECT_NEAR(ur5.joints()[i].maxVelocity_radps, M_PI, 1e-12) << names[i];
  }
  EXPECT_NEAR(ur5.joints()[2].upper_rad, M_PI, 1e-12);
  EXPECT_NEAR(ur5.joints()[0].upper_rad, 2 * M_PI, 1e-12);
  EXPECT_DOUBLE_EQ(ur5.joints()[0].maxEffort_Nm, 150.0);
  EXPECT_DOUBLE_EQ(ur5.joints()[5].maxEffort_Nm, 28.0);
}

TEST(RobotModel, MassesMatchPublishedValuesWithToolLumpedIntoWrist3) {
  const RobotModel ur5 = RobotModel::defaultUr5();
  const double published[] = {4.0, 3.7, 8.393, 2.33, 1.219, 1.219, 0.1879};
  constexpr double kToolMass_kg = 0.2;
  for (int i = 0; i < 6; ++i) EXPECT_NEAR(ur5.links()[i].mass_kg, published[i], kMassTol_kg) << i;
  EXPECT_NEAR(ur5.links()[6].mass_kg, published[6] + kToolMass_kg, kMassTol_kg);
  for (const auto& link : ur5.links()) {
    EXPECT_TRUE(std::filesystem::exists(link.collisionMesh)) << link.name << ": " << link.collisionMesh;
    // Inertia about the centre of mass must be symmetric positive definite.
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(link.I_com_kgm2);
    EXPECT_GT(eig.eigenvalues().minCoeff(), 0.0) << link.name;
  }
}

TEST(RobotModel, ForwardKinematicsMatchesPublishedTool0Positions) {
  const RobotModel ur5 = RobotModel::defaultUr5();
  const Eigen::Vector3d p0 = ur5.X_base_tool0(JointVector::Zero()).translation();
  EXPECT_LT((p0 - Eigen::Vector3d(-0.81725, -0.19145, -0.005491)).norm(), kPublishedPositionTol_m)
      << p0.transpose();
  JointVector q;
  q << 0, -M_PI / 2, 0, -M_PI / 2, 0, 0;
  const Eigen::Vector3d p1 = ur5.X_base_tool0(q).translation();
  EXPECT_LT((p1 - Eigen::Vector3d(0, -0.19145, 1.001059)).norm(), kPublishedPositionTol_m)
      << p1.transpose();
}

TEST(RobotModel, TcpIsTenCentimetresAlongTool0Z) {
  const RobotModel ur5 = RobotModel::defaultUr5();
  JointVector q;
  q << 0.3, -1.2, 1.1, -1.4, -1.57, 0.2;
  const auto X_tool0 = ur5.X_base_tool0(q);
  const auto X_tcp = ur5.X_base_tcp(q);
  const Eigen::Vector3d expected = X_tool0 * Eigen::Vector3d(0, 0, 0.10);
  EXPECT_LT((X_tcp.translation() - expected).norm(), 1e-12);
  EXPECT_LT(srp::core::rotationAngleBetween(X_tcp.linear(), X_tool0.linear()), 1e-12);
}

TEST(RobotModel, BadFilesGiveClearErrors) {
  EXPECT_THROW(RobotModel::fromUrdf("/nonexistent/robot.urdf"), srp::core::FileError);
  const std::string bad = std::string(SRP_BINARY_DIR) + "/not_a_robot.urdf";
  { std::ofstream(bad) << "<robot name='x'><link name='a'/></robot>"; }
  EXPECT_THROW(RobotModel::fromUrdf(bad), srp::core::InvalidInputError);
  { std::ofstream(bad) << "this is not xml"; }
  EXPECT_THROW(RobotModel::fromUrdf(bad), srp::core::FileError);
}
