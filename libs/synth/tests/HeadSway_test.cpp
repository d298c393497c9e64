#include "srp/synth/HeadSway.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "srp/core/Angles.h"
#include "srp/core/Error.h"

namespace {

using srp::synth::HeadSway;

constexpr double kFps = 30.0;
constexpr double kDuration_s = 60.0;
constexpr double kIdentityTol = 1e-12;

double angle_rad(const srp::core::Pose3& X) { return Eigen::AngleAxisd(X.linear()).angle(); }

TEST(HeadSway, OffIsTheNominalPose) {
  const HeadSway sway(HeadSway::Options{}, 3);
  for (double t = 0.0; t < 5.0; t += 0.7) EXPECT_TRUE(sway.X_nominal_camera(t).matrix().isIdentity(kIdentityTol));
}

// Within its amplitudes, reaching a good share of them, smooth from frame to frame.
TEST(HeadSway, StaysWithinItsAmplitudesAndMovesSmoothly) {
  HeadSway::Options o;
  o.enabled = true;
  const HeadSway sway(o, 7);
  const double a_rad = o.rotationAmplitude_deg * srp::core::kPi / 180.0;
  // Three axes at most a_rad each, roll at rollFraction of it.
  const double maxTurn_rad = a_rad * std::sqrt(2.0 + o.rollFraction * o.rollFraction);
  // Per frame: at most 2 pi f_max times the amplitude (the weights sum to one), per axis.
  const double maxStepTurn_rad = 2.0 * srp::core::kPi * o.maxFrequency_Hz / kFps * maxTurn_rad;
  const double maxStepShift_m =
      2.0 * srp::core::kPi * o.maxFrequency_Hz / kFps * o.translationAmplitude_m * std::sqrt(3.0);
  double largestTurn = 0.0, largestShift = 0.0;
  srp::core::Pose3 previous = sway.X_nominal_camera(0.0);
  for (int k = 1; k < static_cast<int>(kDuration_s * kFps); ++k) {
    const auto X = sway.X_nominal_camera(k / kFps);
    EXPECT_LE(angle_rad(X), maxTurn_rad + 1e-9);
    for (int i = 0; i < 3; ++i) EXPECT_LE(std::abs(X.translation()[i]), o.translationAmplitude_m + 1e-12);
    EXPECT_LE(angle_rad(previous.inverse() * X), maxStepTurn_rad + 1e-9) << "frame " << k;
    EXPECT_LE((X.translation() - previous.translation()).norm(), maxStepShift_m + 1e-12) << "frame " << k;
    largestTurn = std::max(largestTurn, angle_rad(X));
    largestShift = std::max(largestShift, X.translation().norm());
    previous = X;
  }
  // A minute of sway uses a good part of the range (not a still camera).
  EXPECT_GT(largestTurn, 0.5 * a_rad);
  EXPECT_GT(largestShift, 0.5 * o.translationAmplitude_m);
}

TEST(HeadSway, SameSeedSameMotionOtherSeedAnother) {
  HeadSway::Options o;
  o.enabled = true;
  const HeadSway a(o, 11), b(o, 11), c(o, 12);
  EXPECT_TRUE(a.X_nominal_camera(2.5).matrix().isApprox(b.X_nominal_camera(2.5).matrix(), 0.0));
  EXPECT_GT((a.X_nominal_camera(2.5).translation() - c.X_nominal_camera(2.5).translation()).norm(), 1e-4);
}

TEST(HeadSway, BadOptionsNameTheOption) {
  HeadSway::Options o;
  o.enabled = true;
  o.minFrequency_Hz = 0.0;
  try {
    HeadSway sway(o, 1);
    FAIL() << "no error";
  } catch (const srp::core::InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("minFrequency_Hz"), std::string::npos);
  }
  o = HeadSway::Options{};
  o.rotationAmplitude_deg = -1.0;
  EXPECT_THROW(HeadSway(o, 1), srp::core::InvalidInputError);
}

}  // namespace
