#include "srp/synth/HeadSway.h"

#include <Eigen/Geometry>
#include <cmath>
#include <random>

#include "srp/core/Angles.h"
#include "srp/core/Error.h"

namespace srp::synth {

HeadSway::HeadSway(const Options& options, std::uint32_t seed) : options_(options) {
  srp::core::require(options.rotationAmplitude_deg >= 0.0 && options.translationAmplitude_m >= 0.0 &&
                         options.rollFraction >= 0.0,
                     "HeadSway: rotationAmplitude_deg, rollFraction and translationAmplitude_m must be >= 0");
  srp::core::require(options.minFrequency_Hz > 0.0 && options.maxFrequency_Hz >= options.minFrequency_Hz,
                     "HeadSway: the frequencies must satisfy 0 < minFrequency_Hz <= maxFrequency_Hz");
  std::mt19937 rng(seed ^ 0x5ea5u);  // its own stream: the demonstration's draws stay as they are
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (auto& w : waves_) {
    double sum = 0.0;
    for (int i = 0; i < kComponents; ++i) {
      w.frequency_Hz[i] = options.minFrequency_Hz + (options.maxFrequency_Hz - options.minFrequency_Hz) * unit(rng);
      w.phase_rad[i] = 2.0 * srp::core::kPi * unit(rng);
      w.weight[i] = 0.5 + unit(rng);
      sum += w.weight[i];
    }
    for (auto& x : w.weight) x /= sum;
  }
}

double HeadSway::wave(int axis, double t_s) const {
  const Wave& w = waves_[static_cast<std::size_t>(axis)];
  double v = 0.0;
  for (int i = 0; i < kComponents; ++i)
    v += w.weight[i] * std::sin(2.0 * srp::core::kPi * w.frequency_Hz[i] * t_s + w.phase_rad[i]);
  return v;
}

srp::core::Pose3 HeadSway::X_nominal_camera(double t_s) const {
  srp::core::Pose3 X = srp::core::Pose3::Identity();
  if (!options_.enabled) return X;
  const double a_rad = options_.rotationAmplitude_deg * srp::core::kPi / 180.0;
  const Eigen::Vector3d rotation(a_rad * wave(0, t_s), a_rad * wave(1, t_s), options_.rollFraction * a_rad * wave(2, t_s));
  if (rotation.norm() > 0.0) X.linear() = Eigen::AngleAxisd(rotation.norm(), rotation.normalized()).toRotationMatrix();
  X.translation() = options_.translationAmplitude_m * Eigen::Vector3d(wave(3, t_s), wave(4, t_s), wave(5, t_s));
  return X;
}

}  // namespace srp::synth
