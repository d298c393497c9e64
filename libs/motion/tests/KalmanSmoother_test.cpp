#include "srp/motion/KalmanSmoother.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "srp/core/Error.h"

namespace srp::motion {
namespace {

Eigen::Vector3d truthAt(double t) { return {0.3 * std::sin(1.5 * t), 0.1 * t, 0.8 + 0.05 * std::cos(2.0 * t)}; }

core::PositionTrajectory noisyCurve(double noise_m, double dropout, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> g(0.0, noise_m);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  core::PositionTrajectory t("camera");
  for (int k = 0; k < 300; ++k) {
    core::PositionSample s;
    s.frame = k;
    s.t_s = k / 30.0;
    if (k > 0 && u(rng) < dropout) s.valid = false, s.p_m.setZero();
    else s.p_m = truthAt(s.t_s) + Eigen::Vector3d(g(rng), g(rng), g(rng));
    t.append(s);
  }
  return t;
}

double rmsError(const core::PositionTrajectory& t) {
  double sum = 0.0;
  for (const auto& s : t.samples()) sum += (s.p_m - truthAt(s.t_s)).squaredNorm();
  return std::sqrt(sum / t.size());
}

TEST(KalmanSmoother, ReducesNoiseWellBelowTheMeasurementNoise) {
  constexpr double kNoise_m = 0.005;
  const auto raw = noisyCurve(kNoise_m, 0.0, 3);
  KalmanSmoother::Options c;
  c.accelerationStd_mps2 = 1.0;  // the curve accelerates by < 1 m/s^2
  const auto smoothed = KalmanSmoother(c).smooth(raw);
  const double rms = rmsError(smoothed);
  EXPECT_LT(rms, 0.5 * kNoise_m * std::sqrt(3.0)) << "rms " << rms;
  const double estimated = KalmanSmoother::estimateMeasurementStd(raw, 1e-4);
  EXPECT_NEAR(estimated, kNoise_m, 0.25 * kNoise_m);
}

TEST(KalmanSmoother, BridgesDropoutsInBothMissingPolicies) {
  constexpr double kNoise_m = 0.004;
  const auto raw = noisyCurve(kNoise_m, 0.3, 5);
  for (auto policy : {KalmanSmoother::Missing::CarryForward, KalmanSmoother::Missing::Predict}) {
    KalmanSmoother::Options c;
    c.missing = policy;
    const auto smoothed = KalmanSmoother(c).smooth(raw);
    ASSERT_EQ(smoothed.size(), raw.size());
    EXPECT_EQ(smoothed.validCount(), raw.size());
    // Carrying forward lags behind a moving point; predicting does not.
    const double bound_m = policy == KalmanSmoother::Missing::Predict ? 0.006 : 0.015;
    EXPECT_LT(rmsError(smoothed), bound_m) << static_cast<int>(policy);
  }
}

TEST(KalmanSmoother, CarryForwardRepeatsTheLastDetection) {
  core::PositionTrajectory t("camera");
  const std::vector<Eigen::Vector3d> p = {{0, 0, 0}, {1, 2, 3}, {0, 0, 0}, {4, 5, 6}, {0, 0, 0}};
  for (int k = 0; k < 5; ++k) t.append({k, k * 0.1, p[k], k != 2});
  const auto f = KalmanSmoother::carryForward(t);
  EXPECT_EQ(f[0].p_m, p[1]);  // leading gap: first detection
  EXPECT_EQ(f[2].p_m, p[1]);
  EXPECT_EQ(f[4].p_m, p[3]);  // exact zeros count as missing
  EXPECT_EQ(f.validCount(), 5u);
}

TEST(KalmanSmoother, RejectsEmptyUndetectedAndNonFinite) {
  EXPECT_THROW(KalmanSmoother().smooth(core::PositionTrajectory("camera")), core::InvalidInputError);
  core::PositionTrajectory none("camera");
  for (int k = 0; k < 3; ++k) none.append({k, k * 0.1, Eigen::Vector3d::Zero(), false});
  EXPECT_THROW(KalmanSmoother().smooth(none), core::InvalidInputError);
  core::PositionTrajectory bad = noisyCurve(0.001, 0.0, 1);
  bad.samples()[10].p_m(1) = std::nan("");
  EXPECT_THROW(KalmanSmoother().smooth(bad), core::InvalidInputError);
}

}  // namespace
}  // namespace srp::motion
