#pragma once
/// \file HeadSway.h
/// \brief A head-mounted camera's sway: a smooth, seeded motion of the camera
/// about its nominal pose, as a camera on a working person's head moves.

#include <array>
#include <cstdint>

#include "srp/core/Pose.h"

namespace srp::synth {

/// The camera's motion about its nominal pose, `X_nominal_camera(t)` (both
/// optical frames: x right, y down, z forward; metres), for a camera worn on
/// the head of a person working at a table (an egocentric recording).
///
/// What the numbers model: a standing person handling parts keeps the head
/// roughly still but not fixed. The head turns and nods by a few degrees as
/// the eyes follow the hand (rotationAmplitude_deg, about each of the
/// camera's axes; roll is smaller, rollFraction), and the body sways by a
/// few centimetres (translationAmplitude_m, along each axis), at the rates of
/// postural sway and of gaze following a hand (frequencies drawn in
/// [minFrequency_Hz, maxFrequency_Hz], 0.1-0.8 Hz: periods of 1.3-10 s, no
/// tremor or walking). Each of the six components is a sum of
/// `kComponents` sinusoids with seeded frequencies, phases and weights
/// (weights summing to one: each component stays within its amplitude),
/// so the motion is smooth (continuous velocity) and the same for a seed.
/// At t = 0 the camera is generally off its nominal pose, as a recording
/// starts anywhere in the head's motion.
///
/// \code
///   HeadSway sway(HeadSway::Options{}, 7);
///   const core::Pose3 X_world_camera_t = X_world_camera * sway.X_nominal_camera(t_s);
/// \endcode
class HeadSway {
 public:
  struct Options {
    /// Off: the camera stays at its nominal pose (X_nominal_camera is the identity).
    bool enabled = false;
    /// Peak turn about the camera's x (nod) and y (turn) axes [deg].
    double rotationAmplitude_deg = 3.0;
    /// Roll (about the optical axis) is this share of that [ratio].
    double rollFraction = 0.5;
    /// Peak displacement along each of the camera's axes [m].
    double translationAmplitude_m = 0.02;
    /// Range of the sinusoids' frequencies [Hz].
    double minFrequency_Hz = 0.1;
    double maxFrequency_Hz = 0.8;
  };
  static constexpr int kComponents = 3;

  /// Throws InvalidInputError naming the bad option (negative amplitude, an empty or negative frequency range).
  HeadSway(const Options& options, std::uint32_t seed);

  /// The camera at time `t_s` in its nominal pose's frame (identity when off).
  srp::core::Pose3 X_nominal_camera(double t_s) const;
  const Options& options() const { return options_; }

 private:
  struct Wave {
    std::array<double, kComponents> frequency_Hz{}, phase_rad{}, weight{};
  };
  /// Value in [-1, 1] of axis `axis`'s sum of sinusoids at t_s.
  double wave(int axis, double t_s) const;

  Options options_;
  std::array<Wave, 6> waves_{};  ///< rotation x, y, z; translation x, y, z
};

}  // namespace srp::synth
