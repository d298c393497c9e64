#include "srp/motion/QuaternionDmp.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include "srp/core/Error.h"

namespace srp::motion {
namespace {

constexpr double kReproductionTol_rad = 1.0 * M_PI / 180.0;  // demo followed to 1 degree
constexpr double kGoalTol_rad = 0.2 * M_PI / 180.0;          // ends at the goal to 0.2 degree

double angleBetween(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b) { return a.angularDistance(b); }

struct Demo {
  Eigen::VectorXd t;
  std::vector<Eigen::Quaterniond> q;
};

// A tool turning about z by 1.2 rad and tilting about x by 0.4 rad, minimum-jerk timing.
Demo makeDemo() {
  Demo d;
  const int n = 60;
  d.t.resize(n);
  for (int i = 0; i < n; ++i) {
    d.t(i) = i / 30.0;
    const double s = static_cast<double>(i) / (n - 1), m = s * s * s * (10 - 15 * s + 6 * s * s);
    d.q.push_back(Eigen::Quaterniond(Eigen::AngleAxisd(0.3 + 1.2 * m, Eigen::Vector3d::UnitZ()) *
                                     Eigen::AngleAxisd(0.4 * std::sin(M_PI * s), Eigen::Vector3d::UnitX())));
  }
  return d;
}

TEST(QuaternionDmp, ReproducesTheDemoAndConvergesToNewGoals) {
  const Demo d = makeDemo();
  QuaternionDmp dmp = QuaternionDmp::imitate(d.t, d.q, Dmp::Options{});
  QuaternionDmpRollout r = dmp.rollout(1.0 / 30.0);
  ASSERT_EQ(r.q.size(), d.q.size());
  double worst = 0.0;
  for (std::size_t i = 0; i < d.q.size(); ++i) worst = std::max(worst, angleBetween(r.q[i], d.q[i]));
  EXPECT_LE(worst, kReproductionTol_rad);
  std::cout << "quaternion DMP reproduction: worst " << worst * 180 / M_PI << " deg, lambda " << dmp.lambda() << "\n";

  const Eigen::Quaterniond start(Eigen::AngleAxisd(-0.5, Eigen::Vector3d::UnitY()));
  const Eigen::Quaterniond goal(Eigen::AngleAxisd(2.0, Eigen::Vector3d(1, 1, 1).normalized()));
  dmp.configure(start, goal, 3.0);
  r = dmp.rollout(0.01);
  EXPECT_NEAR(r.t_s(r.t_s.size() - 1), 3.0, 1e-12);
  EXPECT_LE(angleBetween(r.q.front(), start), 1e-12);
  EXPECT_LE(angleBetween(r.q.back(), goal), kGoalTol_rad) << angleBetween(r.q.back(), goal) * 180 / M_PI << " deg";
  for (const auto& q : r.q) EXPECT_NEAR(q.norm(), 1.0, 1e-12);
}

TEST(QuaternionDmp, JsonRoundTripRollsOutIdentically) {
  const Demo d = makeDemo();
  QuaternionDmp dmp = QuaternionDmp::imitate(d.t, d.q, Dmp::Options{});
  dmp.configure(Eigen::Quaterniond(Eigen::AngleAxisd(0.1, Eigen::Vector3d::UnitX())), d.q.back(), 1.5);
  const QuaternionDmp back = QuaternionDmp::fromJson(nlohmann::json::parse(dmp.toJson().dump()));
  const auto a = dmp.rollout(0.02), b = back.rollout(0.02);
  ASSERT_EQ(a.q.size(), b.q.size());
  for (std::size_t i = 0; i < a.q.size(); ++i) EXPECT_TRUE(a.q[i].coeffs() == b.q[i].coeffs()) << i;
  nlohmann::json wrong = dmp.toJson();
  wrong["class"] = "srp::motion::Dmp";
  EXPECT_THROW(QuaternionDmp::fromJson(wrong), core::InvalidInputError);
}

TEST(QuaternionDmp, RejectsBadDemos) {
  const Demo d = makeDemo();
  EXPECT_THROW(QuaternionDmp::imitate(d.t.head(2), {d.q[0], d.q[1]}, Dmp::Options{}), core::InvalidInputError);
  auto q = d.q;
  q[5].coeffs()(0) = std::nan("");
  EXPECT_THROW(QuaternionDmp::imitate(d.t, q, Dmp::Options{}), core::InvalidInputError);
  EXPECT_THROW(QuaternionDmp::imitate(d.t, d.q, Dmp::Options::reference(0.1)), core::InvalidInputError);
}

}  // namespace
}  // namespace srp::motion
