#include "srp/execution/JointTrajectory.h"

#include <gtest/gtest.h>

#include <fstream>

#include "srp/core/Error.h"

using namespace srp::execution;

TEST(JointTrajectory, HermiteInterpolationReproducesACubic) {
  // q(t) = t^3 sampled densely: the spline must match between samples.
  std::vector<double> t;
  std::vector<JointVector> q;
  for (int i = 0; i <= 100; ++i) {
    t.push_back(i * 0.01);
    q.push_back(JointVector::Constant(std::pow(i * 0.01, 3)));
  }
  const auto tr = JointTrajectory::fromPositions(t, q);
  constexpr double kInterpTol_rad = 1e-5;
  for (double ti : {0.123, 0.5, 0.777}) {
    const auto s = tr.at(ti);
    EXPECT_NEAR(s.q_rad[0], ti * ti * ti, kInterpTol_rad);
    EXPECT_NEAR(s.qd_radps[0], 3 * ti * ti, 1e-3);
  }
  EXPECT_DOUBLE_EQ(tr.duration_s(), 1.0);
  EXPECT_EQ(tr.at(5.0).qd_radps.norm(), 0.0);  // holds the end at rest
}

TEST(JointTrajectory, RejectsBadInputAndWritesCsv) {
  EXPECT_THROW(JointTrajectory::fromPositions({0.0}, {JointVector::Zero()}), srp::core::InvalidInputError);
  EXPECT_THROW(JointTrajectory::fromPositions({0.0, 0.0}, {JointVector::Zero(), JointVector::Zero()}),
               srp::core::InvalidInputError);
  auto a = JointTrajectory::hold(JointVector::Ones(), 1.0);
  a.append(JointTrajectory::hold(JointVector::Ones(), 0.5));
  EXPECT_DOUBLE_EQ(a.duration_s(), 1.5);
  EXPECT_THROW(a.append(JointTrajectory::hold(JointVector::Zero(), 1.0)), srp::core::InvalidInputError);
  const std::string path = std::string(SRP_BINARY_DIR) + "/joint_trajectory_test.csv";
  a.writeCsv(path);
  std::ifstream in(path);
  std::string header;
  std::getline(in, header);
  EXPECT_EQ(header.rfind("t_s,q1_rad", 0), 0u);
  int rows = 0;
  for (std::string line; std::getline(in, line);) ++rows;
  EXPECT_EQ(rows, 3);
}
