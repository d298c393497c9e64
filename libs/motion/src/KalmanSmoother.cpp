#include "srp/motion/KalmanSmoother.h"

#include <Eigen/Core>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <vector>

#include "srp/core/Error.h"

namespace srp::motion {
namespace {

bool isDetected(const core::PositionSample& s) { return s.valid && !(s.p_m.array() == 0.0).all(); }

void validate(const core::PositionTrajectory& in) {
  core::require(!in.empty(), "trajectory is empty; give at least one detected sample");
  bool any = false;
  for (const auto& s : in.samples()) {
    if (s.valid && !s.p_m.allFinite())
      throw core::InvalidInputError("trajectory sample at frame " + std::to_string(s.frame) +
                                    " is NaN/infinite; mark it not detected instead");
    any = any || isDetected(s);
  }
  core::require(any, "trajectory has no detected sample (all missing or zero)");
  for (std::size_t i = 1; i < in.size(); ++i)
    core::require(in[i].t_s > in[i - 1].t_s, "trajectory times must increase (frame " +
                                                 std::to_string(in[i].frame) + ")");
}

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  const auto mid = v.begin() + static_cast<long>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

}  // namespace

core::PositionTrajectory KalmanSmoother::carryForward(const core::PositionTrajectory& in) {
  validate(in);
  core::PositionTrajectory out(in.frame());
  out.samples() = in.samples();
  auto& s = out.samples();
  std::size_t first = 0;
  while (!isDetected(s[first])) ++first;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (i < first) s[i].p_m = s[first].p_m;
    else if (!isDetected(s[i])) s[i].p_m = s[i - 1].p_m;
    s[i].valid = true;
  }
  return out;
}

double KalmanSmoother::estimateMeasurementStd(const core::PositionTrajectory& in, double floor_m) {
  std::vector<double> d2;
  const auto& s = in.samples();
  for (std::size_t i = 1; i + 1 < s.size(); ++i) {
    if (!isDetected(s[i - 1]) || !isDetected(s[i]) || !isDetected(s[i + 1])) continue;
    const Eigen::Vector3d d = s[i + 1].p_m - 2.0 * s[i].p_m + s[i - 1].p_m;
    for (int k = 0; k < 3; ++k) d2.push_back(d(k));
  }
  if (d2.size() < 3) return floor_m;
  const double m = median(d2);
  for (double& x : d2) x = std::abs(x - m);
  return std::max(floor_m, 1.4826 * median(d2) / std::sqrt(6.0));
}

core::PositionTrajectory KalmanSmoother::smooth(const core::PositionTrajectory& in) const {
  validate(in);
  const bool carry = options_.missing == Missing::CarryForward;
  const core::PositionTrajectory filled = carry ? carryForward(in) : in;
  const double sigmaM =
      options_.measurementStd_m ? *options_.measurementStd_m : estimateMeasurementStd(in, options_.minMeasurementStd_m);
  const double R = sigmaM * sigmaM, qa = options_.accelerationStd_mps2 * options_.accelerationStd_mps2;
  const auto& s = filled.samples();
  const std::size_t n = s.size();

  // The covariances do not depend on the data (same model per axis), so the
  // filter runs on 2x2 covariances with the three axes as columns of the state.
  using Mat2 = Eigen::Matrix2d;
  using State = Eigen::Matrix<double, 2, 3>;  // rows: position, velocity; columns: x, y, z
  std::vector<State> xf(n), xp(n);
  std::vector<Mat2> Pf(n), Pp(n), Fs(n);
  std::size_t first = 0;
  while (!isDetected(in[first]) && !carry) ++first;
  State x = State::Zero();
  x.row(0) = s[first].p_m.transpose();
  Mat2 P;
  P << R, 0, 0, 1.0;  // unknown initial velocity: ~1 m/s
  int rejectedInARow = 0;
  for (std::size_t k = 0; k < n; ++k) {
    Mat2 F = Mat2::Identity();
    if (k > 0) {
      const double dt = s[k].t_s - s[k - 1].t_s;
      F(0, 1) = dt;
      Mat2 Q;
      Q << dt * dt * dt * dt / 4, dt * dt * dt / 2, dt * dt * dt / 2, dt * dt;
      x = F * x;
      P = F * P * F.transpose() + qa * Q;
    }
    Fs[k] = F;
    xp[k] = x;
    Pp[k] = P;
    bool measured = carry || isDetected(s[k]);
    const double S = P(0, 0) + R;
    const Eigen::RowVector3d innovation = s[k].p_m.transpose() - x.row(0);
    if (measured && options_.gateSigma && k > first) {
      const double gate = std::max(*options_.gateSigma * std::sqrt(S), options_.gateMin_m);
      if (innovation.norm() > gate && ++rejectedInARow < options_.gateReset) measured = false;
      else rejectedInARow = 0;
    }
    if (measured) {
      const Eigen::Vector2d K = P.col(0) / S;
      x += K * innovation;
      P = P - K * P.row(0);
    }
    xf[k] = x;
    Pf[k] = P;
  }
  // Rauch-Tung-Striebel backward pass.
  State xs = xf[n - 1];
  core::PositionTrajectory out(in.frame());
  out.samples() = in.samples();
  out.samples()[n - 1].p_m = xs.row(0).transpose();
  out.samples()[n - 1].valid = true;
  for (std::size_t k = n - 1; k-- > 0;) {
    const Mat2 C = Pf[k] * Fs[k + 1].transpose() * Pp[k + 1].inverse();
    xs = xf[k] + C * (xs - xp[k + 1]);
    out.samples()[k].p_m = xs.row(0).transpose();
    out.samples()[k].valid = true;
  }
  return out;
}

}  // namespace srp::motion
