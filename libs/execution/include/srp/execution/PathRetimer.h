#pragma once
/// \file PathRetimer.h
/// \brief Slows a joint trajectory down only where it breaks the joint speed or
/// acceleration limits: a time-optimal path parameterisation (TOPP, reachability
/// form as in TOPP-RA) along the fixed joint path, capped at the path's own timing.
///
/// The path is the trajectory's knots q_i at their planned times tau_i; the retimed
/// trajectory passes the same knots at new times t_i with tau(t) monotone, knot
/// velocities q'(tau_i) sigma_i. With
/// sigma = dtau/dt in (0, 1] (1: as planned), x = sigma^2 and u = d^2tau/dt^2, the joint
/// speed is q'(tau) sigma and the acceleration q'(tau) u + q''(tau) x, both linear in
/// (u, x). A backward pass finds at each knot the largest x from which the path can
/// still slow down in time (the controllable set's upper end), a forward pass then
/// accelerates as hard as the limits allow up to it; x <= 1 keeps the planned speed
/// wherever the limits do not bind. The speed profile is continuous, its derivative
/// (the path acceleration) may jump, as in every time-optimal profile.
///
/// Each stage's acceleration rows are imposed at both of its knots (TOPP-RA's
/// first-order interpolation). The continuous model and the cubic Hermite spline that is
/// replayed (knot velocities by central differences, JointTrajectory::fromPositions)
/// still differ by discretisation error, so every result is verified on that spline with the SafetyChecker's own
/// peak ratios; a result that fails is redone with the limits reduced by a fixed
/// ladder of margins, and, if every rung fails, the whole path is slowed by one factor
/// (the earlier method, exact by construction).
///
/// Why hand-written: Debian packages no path parameterisation library (no TOPP-RA,
/// no Ruckig; MoveIt's TOTG comes with ROS only); the algorithm is a few dozen lines.
/// Units: rad, s; knots are those of the input trajectory.

#include <string>
#include <vector>

#include "srp/execution/JointTrajectory.h"
#include "srp/execution/SafetyChecker.h"

namespace srp::execution {

/// The outcome of PathRetimer::retime.
struct RetimedTrajectory {
  JointTrajectory trajectory;  ///< the input when it was within the limits or could not be retimed
  /// Largest local slow-down: the most any knot interval is stretched in time
  /// (2 / (sigma_i + sigma_i+1); 1: as planned); for the whole-path fallback the one
  /// factor; for Refused the factor the whole path would need.
  double slowDown = 1.0;
  double durationRatio = 1.0;  ///< retimed duration / planned duration
  /// How the trajectory was timed.
  enum class Method {
    None,     ///< within the limits: as planned
    Topp,     ///< slowed where the limits bind
    Uniform,  ///< the whole path slowed by one factor
    Refused,  ///< would need more than maxSlowDown
  };
  Method method = Method::None;
};

class PathRetimer {
 public:
  struct Options {
    double velocityMargin = 0.95;      ///< the retimed path peaks at this fraction of the speed limit
    double accelerationMargin = 0.95;  ///< and at this fraction of the acceleration limit
    /// A path that slowed down as a whole by one factor would need more than this (an IK
    /// branch jump, a singularity) is not retimed, and the safety check refuses it (the
    /// same paths as before PathRetimer).
    double maxSlowDown = 4.0;
  };

  /// Limits are the checker's: URDF speeds x velocity fraction, maxAcceleration_radps2
  /// (`safety` is referenced, it must outlive the retimer). Throws InvalidInputError on
  /// margins outside (0, 1] or maxSlowDown < 1.
  PathRetimer(const SafetyChecker& safety, Options options);
  explicit PathRetimer(const SafetyChecker& safety) : PathRetimer(safety, Options{}) {}

  /// The trajectory slowed where its speed or acceleration ratio (SafetyChecker's
  /// peakVelocityRatio / peakAccelerationRatio) would exceed the margins; unchanged when
  /// it is within them. The result starts and ends at rest (fromPositions) and, unless
  /// method == Method::Refused, its peak ratios are <= 1 on the replayed spline.
  RetimedTrajectory retime(const JointTrajectory& trajectory) const;

  /// The speed profile sigma_i = dtau/dt at every knot of `trajectory` for speed and
  /// acceleration limits scaled by the given margins (the TOPP passes; no verification).
  std::vector<double> speedProfile(const JointTrajectory& trajectory, double velocityMargin,
                                   double accelerationMargin) const;

  /// `trajectory` followed with the speed profile sigma (one per knot; between knots
  /// d^2tau/dt^2 is constant): the same knots at new times, knot velocities scaled by
  /// sigma (the spline through them is kept, fromSamples), at rest at both ends as the
  /// input is. Throws InvalidInputError on a length mismatch.
  static JointTrajectory warp(const JointTrajectory& trajectory, const std::vector<double>& sigma);

 private:
  /// speedProfile with x = sigma^2 capped at xScale[i] (<= 1) on knot i.
  std::vector<double> profile(const JointTrajectory& trajectory, double velocityMargin, double accelerationMargin,
                              const std::vector<double>& xScale) const;

  const SafetyChecker& safety_;
  Options options_;
};

}  // namespace srp::execution
