#pragma once
/// \file KalmanSmoother.h
/// \brief Fills missing samples of a 3D position trajectory and smooths it with
/// a constant-velocity Kalman filter followed by a Rauch-Tung-Striebel
/// smoother (thesis ch. 6.4.3: missing values carried forward, then Kalman).
///
/// Model per axis: state (p [m], v [m/s]), p_k+1 = p_k + dt v_k, v_k+1 = v_k +
/// dt a with white acceleration a ~ N(0, accelerationStd^2) (discrete
/// piecewise-constant model, Q = sigma_a^2 [dt^4/4 dt^3/2; dt^3/2 dt^2]);
/// measurement p + N(0, measurementStd^2). dt from the sample times. The
/// output has the input's frame, frame numbers and times, every sample valid.

#include <optional>

#include "srp/core/PositionTrajectory.h"

namespace srp::motion {

class KalmanSmoother {
 public:
  enum class Missing {
    CarryForward,  ///< the thesis: a missing sample repeats the last valid one, then is filtered as a measurement
    Predict,       ///< a missing sample gets no measurement update (the smoother bridges the gap)
  };
  struct Options {
    /// Measurement noise [m]; nullopt: estimated from the data (robust spread of second differences).
    std::optional<double> measurementStd_m;
    double minMeasurementStd_m = 1e-4;  ///< floor of the estimate
    double accelerationStd_mps2 = 5.0;  ///< process noise: a hand accelerates by a few m/s^2
    Missing missing = Missing::Predict;
    /// Outlier gate: a detection whose innovation exceeds max(gateSigma sqrt(S),
    /// gateMin_m) is treated as missing (detector flicker), unless it is the
    /// `gateReset`-th in a row (then the track has really moved and is re-accepted).
    /// nullopt: no gate.
    std::optional<double> gateSigma;
    double gateMin_m = 0.03;
    int gateReset = 6;
  };

  KalmanSmoother() = default;
  explicit KalmanSmoother(Options options) : options_(options) {}

  /// Smoothed trajectory. Throws InvalidInputError when `in` is empty, has no
  /// valid sample, or a valid sample is non-finite. A sample at exactly
  /// (0, 0, 0) counts as missing (detectors write zeros for "not detected").
  core::PositionTrajectory smooth(const core::PositionTrajectory& in) const;

  /// Missing samples replaced by the last valid one (leading ones by the first
  /// valid one); every output sample valid. Same errors as smooth().
  static core::PositionTrajectory carryForward(const core::PositionTrajectory& in);

  /// Measurement noise [m] estimated from the valid samples (1.4826 MAD of the
  /// second differences / sqrt(6)), at least `floor_m`.
  static double estimateMeasurementStd(const core::PositionTrajectory& in, double floor_m);

  const Options& options() const { return options_; }

 private:
  Options options_;
};

}  // namespace srp::motion
