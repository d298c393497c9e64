#include "srp/execution/PathRetimer.h"

#include <gtest/gtest.h>

#include <cmath>

#include "srp/core/Error.h"

using srp::core::Pose3;
using namespace srp::execution;

namespace {
constexpr double kSample_s = 0.01;             // the executor's path sampling
constexpr double kServoPeriod_s = 0.008;       // the URScript servoj tick
constexpr double kTickAccelerationTol_radps2 = 0.01;
constexpr double kTickSpeedTol_radps = 1e-6;
constexpr double kPositionTol_rad = 1e-12;       // first and last knots are the input's
constexpr double kPlannedTimingTol_rad = 1e-6;   // resampling a 10 ms grid at 9.9-10 ms
constexpr double kRestTol_radps = 1e-12;

JointVector home() {
  JointVector q;
  q << -M_PI / 2, -1.6, 1.6, -1.57, -1.57, 0.0;
  return q;
}

SafetyChecker checker(SafetyLimits limits = {}) {
  Pose3 X_world_base = Pose3::Identity();
  X_world_base.translation() = Eigen::Vector3d(0, -0.35, 0);
  return SafetyChecker(RobotModel::defaultUr5(), X_world_base, limits, {});
}

/// A slow 4 s minimum-jerk turn of the base (peak 0.37 rad/s, 0.29 rad/s^2) with a short,
/// fast wrist-1 bump in its middle: 0.1 rad Gaussian of width 50 ms, peak acceleration
/// 0.1 / 0.05^2 = 40 rad/s^2, eight times the 5 rad/s^2 limit, over ~0.2 s of the 4 s.
JointTrajectory slowTurnWithAShortBump() {
  constexpr double T = 4.0, kBump_rad = 0.1, kWidth_s = 0.05, kCentre_s = 2.0;
  std::vector<double> t;
  std::vector<JointVector> q;
  for (int i = 0; i <= static_cast<int>(std::lround(T / kSample_s)); ++i) {
    const double ti = i * kSample_s, tau = ti / T, s = tau * tau * tau * (10 - 15 * tau + 6 * tau * tau);
    JointVector qi = home();
    qi[0] += 0.8 * s;
    qi[3] += kBump_rad * std::exp(-(ti - kCentre_s) * (ti - kCentre_s) / (2 * kWidth_s * kWidth_s));
    t.push_back(ti);
    q.push_back(qi);
  }
  return JointTrajectory::fromPositions(t, q);
}

/// Whole-path scaling by one factor, the executor's method before PathRetimer.
double uniformSlowDown(const SafetyChecker& safety, const JointTrajectory& tr) {
  return std::max(safety.peakVelocityRatio(tr) / 0.95, std::sqrt(safety.peakAccelerationRatio(tr) / 0.95));
}

/// The trajectory as servoj replays it: 8 ms ticks on the spline; every tick's speed and
/// second difference within the limits.
void expectLimitsAtEveryTick(const SafetyChecker& safety, const JointTrajectory& tr) {
  const JointVector vmax = safety.maxVelocities_radps();
  const double amax = safety.limits().maxAcceleration_radps2;
  const int ticks = static_cast<int>(std::ceil(tr.duration_s() / kServoPeriod_s)) + 1;
  std::vector<JointVector> q(ticks);
  for (int k = 0; k < ticks; ++k) q[k] = tr.at(k * kServoPeriod_s).q_rad;
  for (int k = 1; k < ticks; ++k)
    for (int j = 0; j < 6; ++j) {
      ASSERT_LE(std::abs(q[k][j] - q[k - 1][j]) / kServoPeriod_s, vmax[j] + kTickSpeedTol_radps) << "tick " << k;
      if (k + 1 < ticks)
        ASSERT_LE(std::abs(q[k + 1][j] - 2 * q[k][j] + q[k - 1][j]) / (kServoPeriod_s * kServoPeriod_s),
                  amax + kTickAccelerationTol_radps2)
            << "tick " << k << " joint " << j;
    }
}
}  // namespace

TEST(PathRetimer, SlowsOnlyAroundAShortAccelerationPeak) {
  const SafetyChecker safety = checker();
  const JointTrajectory path = slowTurnWithAShortBump();
  ASSERT_GT(safety.peakAccelerationRatio(path), 6.0) << "the test path must break the limit";
  const double k = uniformSlowDown(safety, path);
  ASSERT_GT(k, 2.5);
  ASSERT_LT(k, 4.0);

  const RetimedTrajectory r = PathRetimer(safety).retime(path);
  EXPECT_EQ(r.method, RetimedTrajectory::Method::Topp);
  // Whole-path scaling would take k x 4 s (~11.6 s); only the bump's ~0.3 s is slowed here.
  constexpr double kMaxFractionOfUniform = 0.5;
  EXPECT_LE(r.trajectory.duration_s(), kMaxFractionOfUniform * k * path.duration_s())
      << "retimed " << r.trajectory.duration_s() << " s, uniform " << k * path.duration_s() << " s";
  EXPECT_NEAR(r.durationRatio, r.trajectory.duration_s() / path.duration_s(), 1e-12);
  EXPECT_GT(r.slowDown, 1.5);  // locally about as slow as the uniform factor
  EXPECT_LE(r.slowDown, 4.0);

  // Limits on the spline and at every servoj tick; at rest at both ends; same knots.
  EXPECT_LE(safety.peakAccelerationRatio(r.trajectory), 1.0);
  EXPECT_LE(safety.peakVelocityRatio(r.trajectory), 1.0);
  EXPECT_FALSE(safety.check(r.trajectory, "bump").has_value());
  expectLimitsAtEveryTick(safety, r.trajectory);
  // The same path: it starts and ends where the input does, at rest, and away from the
  // bump the planned timing is kept (the first second replays the input's spline).
  const auto& out = r.trajectory.samples();
  EXPECT_LT((out.front().q_rad - path.samples().front().q_rad).norm(), kPositionTol_rad);
  EXPECT_LT((out.back().q_rad - path.samples().back().q_rad).norm(), kPositionTol_rad);
  EXPECT_LT(out.front().qd_radps.norm(), kRestTol_radps);
  EXPECT_LT(out.back().qd_radps.norm(), kRestTol_radps);
  for (double t = 0.0; t <= 1.0; t += kServoPeriod_s)
    ASSERT_LT((r.trajectory.at(t).q_rad - path.at(t).q_rad).norm(), kPlannedTimingTol_rad) << "t = " << t;
}

TEST(PathRetimer, SpeedProfileIsCappedAtThePlannedTimingAndDipsAtThePeak) {
  const SafetyChecker safety = checker();
  const JointTrajectory path = slowTurnWithAShortBump();
  const auto sigma = PathRetimer(safety).speedProfile(path, 0.95, 0.95);
  ASSERT_EQ(sigma.size(), path.samples().size());
  double lowest = 1.0;
  std::size_t at = 0;
  for (std::size_t i = 0; i < sigma.size(); ++i) {
    ASSERT_GT(sigma[i], 0.0);
    ASSERT_LE(sigma[i], 1.0);
    if (sigma[i] < lowest) lowest = sigma[i], at = i;
  }
  EXPECT_LT(lowest, 0.6);
  constexpr double kBumpWindow_s = 0.3;  // the bump's +-6 widths
  EXPECT_NEAR(path.samples()[at].t_s, 2.0, kBumpWindow_s);
}

TEST(PathRetimer, LeavesAPathWithinTheLimitsAlone) {
  const SafetyChecker safety = checker();
  std::vector<double> t;
  std::vector<JointVector> q;
  for (int i = 0; i <= 200; ++i) {
    const double tau = i / 200.0, s = tau * tau * tau * (10 - 15 * tau + 6 * tau * tau);
    JointVector qi = home();
    qi[0] += 0.5 * s;
    t.push_back(2.0 * tau);
    q.push_back(qi);
  }
  const JointTrajectory path = JointTrajectory::fromPositions(t, q);
  const RetimedTrajectory r = PathRetimer(safety).retime(path);
  EXPECT_EQ(r.method, RetimedTrajectory::Method::None);
  EXPECT_DOUBLE_EQ(r.slowDown, 1.0);
  EXPECT_DOUBLE_EQ(r.trajectory.duration_s(), path.duration_s());
}

TEST(PathRetimer, APathNeedingMoreThanTheLargestSlowDownIsNotRetimedAndStaysRefused) {
  // Acceleration limit 0.2 rad/s^2: the bump needs sqrt(40 / 0.19) ~ 14x > 4x.
  SafetyLimits limits;
  limits.maxAcceleration_radps2 = 0.2;
  const SafetyChecker safety = checker(limits);
  const JointTrajectory path = slowTurnWithAShortBump();
  const RetimedTrajectory r = PathRetimer(safety).retime(path);
  EXPECT_EQ(r.method, RetimedTrajectory::Method::Refused);
  EXPECT_GT(r.slowDown, 4.0);
  EXPECT_DOUBLE_EQ(r.trajectory.duration_s(), path.duration_s());
  const auto v = safety.check(r.trajectory, "bump");
  ASSERT_TRUE(v.has_value());
  EXPECT_EQ(v->check, "acceleration limit");
}

TEST(PathRetimer, BadOptionsAreRejectedWithTheFix) {
  const SafetyChecker safety = checker();
  try {
    PathRetimer(safety, PathRetimer::Options{1.5, 0.95, 4.0});
    FAIL() << "margin 1.5 accepted";
  } catch (const srp::core::InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("(0, 1]"), std::string::npos) << e.what();
  }
  EXPECT_THROW(PathRetimer(safety, PathRetimer::Options{0.95, 0.95, 0.5}), srp::core::InvalidInputError);
}
