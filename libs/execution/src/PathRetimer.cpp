#include "srp/execution/PathRetimer.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "srp/core/Error.h"

namespace srp::execution {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr int kBisections = 60;
// Speeds along the path below this are "not moving" (the joint bounds x, not u).
constexpr double kStillJoint_radps = 1e-9;
// The retimed spline differs from the continuous model by discretisation error: where
// a result fails verification, x = sigma^2 is capped lower on the knots around it (by
// 1 / ratio, as accelerations scale with x; at least by kMaxRefineFactor) and the
// profile planned again, at most kMaxRefinements times. Fixed before any measurement,
// not tuned.
constexpr int kMaxRefinements = 30;
constexpr std::ptrdiff_t kRefineHalfWidth = 3;  // knots on either side of the failing point
constexpr double kMaxRefineFactor = 0.9;

/// One linear acceleration constraint of a stage, |d u + c x| <= A, for one joint.
struct Row {
  double d = 0.0;
  double c = 0.0;
};

/// The stage [i, i+1]: its length, the largest x at knot i allowed by the speed limits
/// and the planned timing, and the acceleration rows of both its knots (TOPP-RA's
/// first-order interpolation: at knot i+1 the speed is x + 2 ds u, so the row reads
/// (q'_{i+1} + 2 ds q''_{i+1}) u + q''_{i+1} x), which keeps a stage from ending where
/// the next knot's limits cannot hold.
struct Stage {
  double ds = 0.0;
  double xMax = 1.0;
  std::vector<Row> rows;
};

/// Bounds of u = d^2tau/dt^2 at x = sigma^2 (lo > hi: no u fits); x + 2 ds u >= 0 too.
void uBounds(const Stage& st, double x, double A, double& lo, double& hi) {
  lo = st.ds > 0.0 ? -x / (2.0 * st.ds) : -kInf;
  hi = kInf;
  for (const Row& r : st.rows) {
    if (std::abs(r.d) <= kStillJoint_radps) {
      if (std::abs(r.c) * x > A) lo = kInf;  // a joint at rest on the path: q'' x alone
      continue;
    }
    double a = (-A - r.c * x) / r.d, b = (A - r.c * x) / r.d;
    if (r.d < 0) std::swap(a, b);
    lo = std::max(lo, a);
    hi = std::min(hi, b);
  }
}

/// Largest x in [0, xMax] with pred(x), where pred holds on an interval starting at 0
/// (both uses below are sublevel sets of convex piecewise-linear functions).
template <class Pred>
double largestFeasible(double xMax, Pred pred) {
  if (pred(xMax)) return xMax;
  double lo = 0.0, hi = xMax;
  for (int k = 0; k < kBisections; ++k) {
    const double mid = 0.5 * (lo + hi);
    (pred(mid) ? lo : hi) = mid;
  }
  return lo;
}

}  // namespace

PathRetimer::PathRetimer(const SafetyChecker& safety, Options options) : safety_(safety), options_(options) {
  auto inUnit = [](double m) { return m > 0.0 && m <= 1.0; };
  if (!inUnit(options_.velocityMargin) || !inUnit(options_.accelerationMargin))
    throw srp::core::InvalidInputError("PathRetimer: the speed and acceleration margins must be within (0, 1] (got " +
                                       std::to_string(options_.velocityMargin) + ", " +
                                       std::to_string(options_.accelerationMargin) + "); 0.95 is the default");
  if (!(options_.maxSlowDown >= 1.0))
    throw srp::core::InvalidInputError("PathRetimer: the largest slow-down must be >= 1 (got " +
                                       std::to_string(options_.maxSlowDown) + "); 4 is the default");
}

std::vector<double> PathRetimer::speedProfile(const JointTrajectory& trajectory, double velocityMargin,
                                              double accelerationMargin) const {
  return profile(trajectory, velocityMargin, accelerationMargin, std::vector<double>(trajectory.samples().size(), 1.0));
}

std::vector<double> PathRetimer::profile(const JointTrajectory& trajectory, double velocityMargin,
                                         double accelerationMargin, const std::vector<double>& xScale) const {
  const auto& s = trajectory.samples();
  const std::size_t n = s.size();
  if (n < 2) return std::vector<double>(n, 1.0);
  const JointVector V = safety_.maxVelocities_radps() * velocityMargin;
  const double A = safety_.limits().maxAcceleration_radps2 * accelerationMargin;

  // q'(tau): the spline's knot velocities. q''(tau): the spline's own second derivative,
  // which jumps at a knot (the spline is C1), so each interval has its start and end
  // value: aStart[i] at the start of [i, i+1], aEnd[i] at the end of [i-1, i].
  std::vector<JointVector> aStart(n, JointVector::Zero()), aEnd(n, JointVector::Zero());
  for (std::size_t i = 0; i + 1 < n; ++i) {
    const double h = s[i + 1].t_s - s[i].t_s;
    const JointVector dq = s[i + 1].q_rad - s[i].q_rad;
    aStart[i] = (6.0 * dq - h * (4.0 * s[i].qd_radps + 2.0 * s[i + 1].qd_radps)) / (h * h);
    aEnd[i + 1] = (-6.0 * dq + h * (2.0 * s[i].qd_radps + 4.0 * s[i + 1].qd_radps)) / (h * h);
  }
  std::vector<Stage> st(n);
  for (std::size_t i = 0; i < n; ++i) {
    Stage& g = st[i];
    // Speed: the knot velocity and both chords (the checker measures both; sigma on a
    // chord lies between its knots' values, so bounding both knots bounds it).
    double x = xScale[i];  // never faster than planned (1), lower where a result failed verification
    for (int j = 0; j < 6; ++j) {
      double speed = std::abs(s[i].qd_radps[j]);
      if (i > 0) speed = std::max(speed, std::abs(s[i].q_rad[j] - s[i - 1].q_rad[j]) / (s[i].t_s - s[i - 1].t_s));
      if (i + 1 < n) speed = std::max(speed, std::abs(s[i + 1].q_rad[j] - s[i].q_rad[j]) / (s[i + 1].t_s - s[i].t_s));
      if (speed > 0.0) x = std::min(x, (V[j] / speed) * (V[j] / speed));
      g.rows.push_back({s[i].qd_radps[j], i + 1 < n ? aStart[i][j] : aEnd[i][j]});
    }
    if (i + 1 < n) {
      g.ds = s[i + 1].t_s - s[i].t_s;
      for (int j = 0; j < 6; ++j)
        g.rows.push_back({s[i + 1].qd_radps[j] + 2.0 * g.ds * aEnd[i + 1][j], aEnd[i + 1][j]});
    }
    // The maximum velocity curve: the largest x with a feasible u at all.
    g.xMax = largestFeasible(x, [&](double xx) {
      double lo, hi;
      uBounds(g, xx, A, lo, hi);
      return lo <= hi;
    });
  }

  // Backward pass: the largest x at each knot from which the rest can still be followed.
  std::vector<double> xBack(n);
  xBack[n - 1] = st[n - 1].xMax;
  for (std::size_t i = n - 1; i-- > 0;) {
    const Stage& g = st[i];
    xBack[i] = largestFeasible(g.xMax, [&](double xx) {
      double lo, hi;
      uBounds(g, xx, A, lo, hi);
      return lo <= hi && xx + 2.0 * g.ds * lo <= xBack[i + 1];
    });
  }
  // Forward pass: as fast as the limits allow, never above the controllable bound.
  std::vector<double> sigma(n);
  double x = xBack[0];
  for (std::size_t i = 0; i < n; ++i) {
    sigma[i] = std::sqrt(std::max(x, 0.0));
    if (i + 1 == n) break;
    double lo, hi;
    uBounds(st[i], x, A, lo, hi);
    x = std::max(std::min(xBack[i + 1], x + 2.0 * st[i].ds * hi), 0.0);  // lo <= u by the backward pass
  }
  return sigma;
}

JointTrajectory PathRetimer::warp(const JointTrajectory& trajectory, const std::vector<double>& sigma) {
  const auto& s = trajectory.samples();
  const std::size_t n = s.size();
  if (sigma.size() != n || n < 2)
    throw srp::core::InvalidInputError("PathRetimer::warp: " + std::to_string(sigma.size()) + " speed factors for " +
                                       std::to_string(n) + " knots (need as many, at least 2)");
  constexpr double kMinSigma = 1e-6;  // a knot at rest in both directions still takes finite time
  // Per stage u = d^2tau/dt^2 is constant, so sigma grows linearly in t: the stage takes
  // 2 ds / (sigma_i + sigma_i+1). The knots keep their positions; their velocities are
  // the path's, times sigma (central differences over unevenly spread knots would
  // misstate them, and the spline's accelerations with them).
  std::vector<JointTrajectorySample> out(s);
  for (std::size_t i = 0; i < n; ++i) {
    const double sg = std::max(sigma[i], kMinSigma);
    if (i > 0) {
      const double sgBefore = std::max(sigma[i - 1], kMinSigma);
      out[i].t_s = out[i - 1].t_s + 2.0 * (s[i].t_s - s[i - 1].t_s) / (sgBefore + sg);
    }
    out[i].qd_radps = s[i].qd_radps * sg;
    out[i].qdd_radps2 = s[i].qdd_radps2 * (sg * sg);  // the planned term; the sigma' term is left out
  }
  return JointTrajectory::fromSamples(std::move(out));
}

RetimedTrajectory PathRetimer::retime(const JointTrajectory& trajectory) const {
  RetimedTrajectory r;
  r.trajectory = trajectory;
  if (trajectory.samples().size() < 2) return r;
  const double k = std::max(safety_.peakVelocityRatio(trajectory) / options_.velocityMargin,
                            std::sqrt(safety_.peakAccelerationRatio(trajectory) / options_.accelerationMargin));
  if (k <= 1.0) return r;
  r.slowDown = k;
  if (k > options_.maxSlowDown) {
    r.method = RetimedTrajectory::Method::Refused;
    return r;
  }
  const double duration = trajectory.duration_s();
  const auto& knots = trajectory.samples();
  const JointVector vmax = safety_.maxVelocities_radps();
  const double amax = safety_.limits().maxAcceleration_radps2;
  std::vector<double> xScale(knots.size(), 1.0);
  for (int pass = 0; pass < kMaxRefinements; ++pass) {
    const auto sigma = profile(trajectory, options_.velocityMargin, options_.accelerationMargin, xScale);
    JointTrajectory warped = warp(trajectory, sigma);
    // Verify on the replayed spline; where it breaks a limit, lower the speed cap of the
    // knots around it and plan again.
    std::vector<double> worst(knots.size(), 0.0);
    bool holds = true;
    const auto n = static_cast<std::ptrdiff_t>(knots.size());
    for (std::ptrdiff_t i = 0; i < n; ++i) {
      double ratio = 0.0;
      for (int j = 0; j < 6; ++j)
        ratio = std::max({ratio, SafetyChecker::jointSpeed_radps(warped, i, j) / vmax[j],
                          SafetyChecker::splineAcceleration_radps2(warped, i, j) / amax});
      if (ratio <= 1.0) continue;
      holds = false;
      for (std::ptrdiff_t m = std::max<std::ptrdiff_t>(0, i - kRefineHalfWidth); m <= std::min(n - 1, i + kRefineHalfWidth); ++m)
        worst[m] = std::max(worst[m], ratio);
    }
    if (holds && warped.duration_s() > k * duration) break;  // no gain over one factor: use it
    if (holds) {
      r.durationRatio = warped.duration_s() / duration;
      r.trajectory = std::move(warped);
      r.slowDown = 1.0;
      for (std::size_t i = 0; i + 1 < knots.size(); ++i)
        r.slowDown = std::max(r.slowDown, (r.trajectory.samples()[i + 1].t_s - r.trajectory.samples()[i].t_s) /
                                              (knots[i + 1].t_s - knots[i].t_s));
      r.method = RetimedTrajectory::Method::Topp;
      return r;
    }
    for (std::size_t m = 0; m < knots.size(); ++m)
      if (worst[m] > 1.0) xScale[m] *= std::min(kMaxRefineFactor, 1.0 / worst[m]);
  }
  // Not verified after kMaxRefinements passes, or slower: one factor for the whole path (speeds / k, accelerations / k^2).
  std::vector<double> t;
  std::vector<JointVector> q;
  for (const auto& s : trajectory.samples()) {
    t.push_back(s.t_s * k);
    q.push_back(s.q_rad);
  }
  r.trajectory = JointTrajectory::fromPositions(t, q);
  r.durationRatio = k;
  r.method = RetimedTrajectory::Method::Uniform;
  return r;
}

}  // namespace srp::execution
