#include "srp/motion/Segmenter.h"

#include <cstdio>
#include <cstdlib>

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <opencv2/core.hpp>
#include <opencv2/ml.hpp>
#include <sstream>

#include "srp/core/Error.h"

namespace srp::motion {
namespace {

using core::InvalidInputError;

constexpr int kComponents = 3;

void validateTrajectory(const core::PositionTrajectory& t, const std::string& what) {
  if (t.size() < 2)
    throw InvalidInputError(what + " has " + std::to_string(t.size()) +
                            " samples; segmentation needs a whole demo (at least 2 samples)");
  for (const auto& s : t.samples())
    if (s.valid && !s.p_m.allFinite())
      throw InvalidInputError(what + ": sample at frame " + std::to_string(s.frame) +
                              " is NaN/infinite; mark it not detected (zeros) instead");
}

bool detected(const core::PositionSample& s) { return s.valid && !(s.p_m.array() == 0.0).all(); }

/// Per-axis median of the detected samples in [i - half, i + half]; false when
/// fewer than `minCount` are detected.
bool windowMedian(const core::PositionTrajectory& in, int i, int half, int minCount, Eigen::Vector3d& m) {
  const int n = static_cast<int>(in.size());
  thread_local std::vector<double> buf;
  for (int k = 0; k < 3; ++k) {
    buf.clear();
    for (int j = std::max(0, i - half); j <= std::min(n - 1, i + half); ++j)
      if (detected(in[static_cast<std::size_t>(j)])) buf.push_back(in[static_cast<std::size_t>(j)].p_m(k));
    if (static_cast<int>(buf.size()) < minCount) return false;
    std::sort(buf.begin(), buf.end());
    const std::size_t c = buf.size();
    m(k) = c % 2 ? buf[c / 2] : 0.5 * (buf[c / 2 - 1] + buf[c / 2]);
  }
  return true;
}

/// Detector flicker: drops a detection farther than `gate_m` from the median of
/// the detections around it (a wrong object's position for a few frames), then
/// replaces each sample by the median of the detections in `window` (missing
/// where fewer than 3 are left; the carry-forward fills those).
core::PositionTrajectory removeFlicker(const core::PositionTrajectory& in, int window, double gate_m) {
  const int n = static_cast<int>(in.size());
  core::PositionTrajectory gated = in;
  Eigen::Vector3d m;
  for (int i = 0; i < n; ++i) {
    auto& s = gated.samples()[static_cast<std::size_t>(i)];
    if (detected(s) && windowMedian(in, i, window, 5, m) && (s.p_m - m).norm() > gate_m) s.valid = false;
  }
  core::PositionTrajectory out = gated;
  for (int i = 0; i < n; ++i) {
    auto& o = out.samples()[static_cast<std::size_t>(i)];
    o.valid = windowMedian(gated, i, 1, 2, m);
    o.p_m = o.valid ? m : Eigen::Vector3d::Zero();
  }
  return out;
}

/// Objects move only in the hand, and not faster than a hand: a detection
/// away from the object's last accepted position with no hand near it, or
/// farther than maxSpeed allows, is another object or a false detection
/// (flicker), and is dropped.
core::PositionTrajectory dropMovesWithoutHand(const core::PositionTrajectory& in, const core::PositionTrajectory& hand,
                                              double gate_m, double handReach_m, double maxSpeed_mps) {
  core::PositionTrajectory out = in;
  Eigen::Vector3d last = Eigen::Vector3d::Zero();
  double lastTime_s = in.empty() ? 0.0 : in[0].t_s;
  bool haveLast = false;
  const int n = static_cast<int>(in.size());
  // Start from the median of the first detections (the object at rest before the demo).
  {
    core::PositionTrajectory head(in.frame());
    for (int i = 0; i < n && head.size() < 15; ++i)
      if (detected(in[static_cast<std::size_t>(i)])) head.append(in[static_cast<std::size_t>(i)]);
    Eigen::Vector3d m;
    if (!head.empty() && windowMedian(head, 0, static_cast<int>(head.size()), 1, m)) last = m, haveLast = true;
  }
  // A run of rejected detections that agree with each other for kReacquire
  // detections means the object is really there (it was moved unseen): accept.
  constexpr int kReacquire = 8;
  Eigen::Vector3d candidate = Eigen::Vector3d::Zero();
  int candidateCount = 0;
  for (int i = 0; i < n; ++i) {
    auto& s = out.samples()[static_cast<std::size_t>(i)];
    if (!detected(s)) continue;
    const Eigen::Vector3d& h = hand[static_cast<std::size_t>(i)].p_m;
    const double jump = haveLast ? (s.p_m - last).norm() : 0.0;
    const bool tooFast = jump > gate_m + maxSpeed_mps * (s.t_s - lastTime_s);
    const bool noHand = jump > gate_m && (h - s.p_m).norm() > handReach_m && (h - last).norm() > handReach_m;
    if (haveLast && (tooFast || noHand)) {
      if (candidateCount > 0 && (s.p_m - candidate).norm() <= gate_m) ++candidateCount;
      else candidate = s.p_m, candidateCount = 1;
      if (candidateCount < kReacquire) {
        s.valid = false;
        s.p_m.setZero();
        continue;
      }
    }
    candidateCount = 0;
    last = s.p_m;
    lastTime_s = s.t_s;
  }
  return out;
}

Eigen::Vector3d medianPosition(const core::PositionTrajectory& t, int from, int to) {
  Eigen::Vector3d m;
  std::vector<double> buf;
  for (int k = 0; k < 3; ++k) {
    buf.clear();
    for (int i = from; i < to; ++i) buf.push_back(t[i].p_m(k));
    std::nth_element(buf.begin(), buf.begin() + static_cast<long>(buf.size() / 2), buf.end());
    m(k) = buf[buf.size() / 2];
  }
  return m;
}

/// The labels of a fitted mixture (`means`: one row per component) renumbered 0..2 by the median
/// index of their samples, after merging the components whose means are closer than mergeDistance
/// (EM splits a long rest, e.g. of an object put back where it was, into two).
std::vector<int> renumberedLabels(const cv::Mat& means, cv::Mat labels, double mergeDistance_m) {
  const int n = labels.rows;
  std::vector<int> out(static_cast<std::size_t>(n), 0);
  std::vector<int> parent(kComponents);
  std::iota(parent.begin(), parent.end(), 0);
  for (int a = 0; a < kComponents; ++a)
    for (int b = a + 1; b < kComponents; ++b)
      if (cv::norm(means.row(a), means.row(b)) < mergeDistance_m * 1e3) parent[static_cast<std::size_t>(b)] = parent[static_cast<std::size_t>(a)];
  for (int i = 0; i < n; ++i) labels.at<int>(i) = parent[static_cast<std::size_t>(labels.at<int>(i))];
  // Order the components by the median index of their samples.
  std::vector<std::vector<int>> members(kComponents);
  for (int i = 0; i < n; ++i) members[static_cast<std::size_t>(labels.at<int>(i))].push_back(i);
  std::vector<std::pair<double, int>> order;
  for (int c = 0; c < kComponents; ++c) {
    const auto& m = members[static_cast<std::size_t>(c)];
    order.emplace_back(m.empty() ? 1e18 : m[m.size() / 2], c);
  }
  std::sort(order.begin(), order.end());
  std::vector<int> rank(kComponents);
  for (int r = 0; r < kComponents; ++r) rank[static_cast<std::size_t>(order[static_cast<std::size_t>(r)].second)] = r;
  for (int i = 0; i < n; ++i) out[static_cast<std::size_t>(i)] = rank[static_cast<std::size_t>(labels.at<int>(i))];
  return out;
}

/// EM labels per sample, components renumbered by the median time of their samples.
std::vector<int> mixtureLabels(const core::PositionTrajectory& t, const Eigen::Vector3d& p0,
                               const Eigen::Vector3d& p1, int maxIterations, double mergeDistance_m) {
  const int n = static_cast<int>(t.size());
  cv::Mat samples(n, 3, CV_64F);
  Eigen::Vector3d far = p0;
  double farDist = -1;
  for (int i = 0; i < n; ++i) {
    for (int k = 0; k < 3; ++k) samples.at<double>(i, k) = t[i].p_m(k) * 1e3;  // mm
    const double d = std::min((t[i].p_m - p0).norm(), (t[i].p_m - p1).norm());
    if (d > farDist) farDist = d, far = t[i].p_m;
  }
  // Start at: static before, the moving part (its farthest point), static after.
  cv::Mat means0(kComponents, 3, CV_64F);
  const Eigen::Vector3d mid = 0.5 * (0.5 * (p0 + p1) + far);
  for (int k = 0; k < 3; ++k) {
    means0.at<double>(0, k) = p0(k) * 1e3;
    means0.at<double>(1, k) = mid(k) * 1e3;
    means0.at<double>(2, k) = p1(k) * 1e3;
  }
  cv::Mat var;
  {
    cv::Mat mean;
    cv::reduce(samples, mean, 0, cv::REDUCE_AVG);
    cv::Mat centred = samples - cv::repeat(mean, n, 1);
    cv::reduce(centred.mul(centred), var, 0, cv::REDUCE_AVG);
  }
  std::vector<cv::Mat> covs0(kComponents);
  for (int c = 0; c < kComponents; ++c) {
    covs0[c] = cv::Mat::eye(3, 3, CV_64F);
    for (int k = 0; k < 3; ++k)
      covs0[c].at<double>(k, k) = c == 1 ? std::max(var.at<double>(0, k), 1.0) : 25.0;  // 5 mm static spread
  }
  cv::Mat weights0(1, kComponents, CV_64F, cv::Scalar(1.0 / kComponents));
  cv::Ptr<cv::ml::EM> em = cv::ml::EM::create();
  em->setClustersNumber(kComponents);
  em->setCovarianceMatrixType(cv::ml::EM::COV_MAT_DIAGONAL);
  em->setTermCriteria(cv::TermCriteria(cv::TermCriteria::COUNT + cv::TermCriteria::EPS, maxIterations, 1e-5));
  // EM on at most kMaxTrainSamples evenly strided samples (a 60 s demo has
  // 1800; the rests and the move are all still represented), then every
  // sample is labelled with the fitted mixture.
  constexpr int kMaxTrainSamples = 300;
  const int stride = std::max(1, (n + kMaxTrainSamples - 1) / kMaxTrainSamples);
  cv::Mat train;
  for (int i = 0; i < n; i += stride) train.push_back(samples.row(i));
  bool ok = false;
  try {
    ok = em->trainE(train, means0, covs0, weights0, cv::noArray(), cv::noArray(), cv::noArray());
  } catch (const cv::Exception&) {
    ok = false;
  }
  cv::Mat labels(n, 1, CV_32S, cv::Scalar(0));
  if (ok) {
    // Diagonal Gaussians: log pi_k - 0.5 sum_d (log var_kd + (x_d - mu_kd)^2 / var_kd).
    const cv::Mat mu = em->getMeans(), w = em->getWeights();
    std::vector<cv::Mat> covs;
    em->getCovs(covs);
    for (int i = 0; i < n; ++i) {
      double bestLog = -std::numeric_limits<double>::infinity();
      for (int c = 0; c < kComponents; ++c) {
        double logp = std::log(std::max(w.at<double>(c), 1e-300));
        for (int k = 0; k < 3; ++k) {
          const double var = std::max(covs[static_cast<std::size_t>(c)].at<double>(k, k), 1e-12);
          const double d = samples.at<double>(i, k) - mu.at<double>(c, k);
          logp -= 0.5 * (std::log(var) + d * d / var);
        }
        if (logp > bestLog) bestLog = logp, labels.at<int>(i) = c;
      }
    }
  }
  std::vector<int> out(static_cast<std::size_t>(n), 0);
  if (!ok) {
    // EM degenerate (e.g. a perfectly static object): nearest of the start means.
    for (int i = 0; i < n; ++i) {
      const double d0 = (t[i].p_m - p0).norm(), d2 = (t[i].p_m - p1).norm();
      out[static_cast<std::size_t>(i)] = d2 < d0 ? 2 : 0;
    }
    return out;
  }
  return renumberedLabels(em->getMeans(), labels, mergeDistance_m);
}

/// Boundary between the hand at rest and the hand moving off smoothly from
/// rest. For each detected candidate b in [lo, hi] (sample indices): the rest =
/// the `restCount` detections b, b - dir, ... (fitted by their mean p_rest),
/// the move = the `moveCount` detections b + dir, b + 2 dir, ... (fitted per
/// axis by p_rest + β dt² + γ dt³, dt = |t - t_b|: continuous position, zero
/// velocity at b); gaps (hand not detected) are skipped, up to 3x the count.
/// Returns the candidate with the least mean squared residual, or -1 when no
/// candidate has enough detections. dir = +1: rest before, move after (the
/// hand leaves: grasp); dir = -1: move before, rest after (the hand arrives:
/// release). `allowed(b)` filters candidates.
template <class Allowed>
int restMoveBoundary(const core::PositionTrajectory& hand, int lo, int hi, int dir, int restCount, int moveCount,
                     Allowed allowed, double minMove_m = 0.0) {
  const int n = static_cast<int>(hand.size());
  lo = std::max(lo, 0);
  hi = std::min(hi, n - 1);
  auto at = [&](int i) -> const core::PositionSample& { return hand[static_cast<std::size_t>(i)]; };
  // The first `count` detections from b (included when `fromB`) stepping by `step`.
  auto gather = [&](int b, int step, int count, bool fromB, std::vector<int>& out) {
    out.clear();
    for (int k = fromB ? 0 : 1; k <= 3 * count && static_cast<int>(out.size()) < count; ++k) {
      const int i = b + step * k;
      if (i < 0 || i >= n) break;
      if (detected(at(i))) out.push_back(i);
    }
  };
  std::vector<int> rest, move;
  int best = -1;
  double bestCost = std::numeric_limits<double>::infinity();
  for (int b = lo; b <= hi; ++b) {
    if (!detected(at(b)) || !allowed(b)) continue;
    gather(b, -dir, restCount, true, rest);
    gather(b, dir, moveCount, false, move);
    if (static_cast<int>(rest.size()) < std::max(2, restCount / 2) || move.size() < 3) continue;
    Eigen::Vector3d p_rest = Eigen::Vector3d::Zero();
    for (int i : rest) p_rest += at(i).p_m;
    p_rest /= static_cast<double>(rest.size());
    double sse = 0.0;
    for (int i : rest) sse += (at(i).p_m - p_rest).squaredNorm();
    // The move side must move by itself (inside a long rest both sides fit a
    // rest equally, and a rest next to a slow drift fits too).
    if (minMove_m > 0.0) {
      double extent = 0.0;
      for (int i : move) extent = std::max(extent, (at(i).p_m - at(move.front()).p_m).norm());
      if (extent < minMove_m) continue;
    }
    // Move: least squares of y = β u2 + γ u3 per axis (u in tenths of a second for conditioning).
    double s22 = 0, s23 = 0, s33 = 0, syy = 0;
    Eigen::Vector3d s2y = Eigen::Vector3d::Zero(), s3y = Eigen::Vector3d::Zero();
    for (int i : move) {
      const double dt = 10.0 * std::abs(at(i).t_s - at(b).t_s);
      const double u2 = dt * dt, u3 = u2 * dt;
      const Eigen::Vector3d y = at(i).p_m - p_rest;
      s22 += u2 * u2, s23 += u2 * u3, s33 += u3 * u3;
      s2y += u2 * y, s3y += u3 * y;
      syy += y.squaredNorm();
    }
    const double det = s22 * s33 - s23 * s23;
    double fitted = 0.0;  // explained sum of squares over the axes: s2y·β + s3y·γ
    if (det > 1e-12 * s22 * s33) {
      for (int a = 0; a < 3; ++a) {
        const double beta = (s33 * s2y(a) - s23 * s3y(a)) / det, gamma = (s22 * s3y(a) - s23 * s2y(a)) / det;
        fitted += beta * s2y(a) + gamma * s3y(a);
      }
    }
    const double cost = (sse + std::max(0.0, syy - fitted)) / static_cast<double>(rest.size() + move.size());
    if (cost < bestCost) bestCost = cost, best = b;
  }
  return best;
}

/// Extends a sample b inside a rest of the hand to the rest's end: p_rest =
/// the per-axis median of the `restCount` detections from b against `dir`
/// (the rest side), tolerance δ = 3x their RMS spread (2 mm to 10 mm); then
/// walks from b along `dir` while the detections stay within δ of p_rest (two
/// consecutive detections outside end the rest) and returns the last sample
/// within. dir = +1: the rest's last sample (grasp), -1: its first (release).
/// Samples outside [lo, hi] are not visited.
int restEnd(const core::PositionTrajectory& hand, int b, int dir, int restCount, int lo, int hi, double noiseTol_m = 0.0) {
  const int n = static_cast<int>(hand.size());
  auto at = [&](int i) -> const core::PositionSample& { return hand[static_cast<std::size_t>(i)]; };
  std::vector<Eigen::Vector3d> rest;
  for (int k = 0; k <= 3 * restCount && static_cast<int>(rest.size()) < restCount; ++k) {
    const int i = b - dir * k;
    if (i < 0 || i >= n) break;
    if (detected(at(i))) rest.push_back(at(i).p_m);
  }
  if (rest.size() < 2) return b;
  Eigen::Vector3d p_rest;
  std::vector<double> axis(rest.size());
  for (int a = 0; a < 3; ++a) {
    for (std::size_t k = 0; k < rest.size(); ++k) axis[k] = rest[k](a);
    std::nth_element(axis.begin(), axis.begin() + static_cast<long>(axis.size() / 2), axis.end());
    p_rest(a) = axis[axis.size() / 2];
  }
  double ss = 0.0;
  for (const auto& p : rest) ss += (p - p_rest).squaredNorm();
  // noiseTol: from the whole track's noise (robust mode), as a few samples' spread can be small by chance.
  const double tol_m = std::clamp(2.0 * std::sqrt(ss / static_cast<double>(rest.size())), std::max(0.0015, noiseTol_m),
                                  std::max(0.004, noiseTol_m));
  auto within = [&](int i) { return (at(i).p_m - p_rest).norm() <= tol_m; };
  int end = b;
  // b itself past the rest (in the move): step back into it.
  while (end - dir >= lo && end - dir <= hi && (!detected(at(end)) || !within(end)) && std::abs(end - b) < restCount) end -= dir;
  int outside = 0;
  for (int i = end + dir; i >= lo && i <= hi && outside < 2; i += dir) {
    if (!detected(at(i))) continue;
    if (within(i)) end = i, outside = 0;
    else ++outside;
  }
  return end;
}

/// Hand outliers (issue 18: single-frame jumps of up to 25 cm, carried-forward
/// values): a detection is dropped when it is farther than max(sigmas x the
/// robust spread, min_m) from the per-axis median of the linear interpolations
/// between its neighbours p(i-a) and p(i+b), a, b = 1..4 (a jump of one or two
/// frames contaminates at most half of them, smooth motion none), or when it
/// repeats the previous detection exactly (a carried value, not a measurement).
core::PositionTrajectory dropHandOutliers(const core::PositionTrajectory& in, double sigmas, double min_m,
                                          double& spread_m) {
  const int n = static_cast<int>(in.size());
  auto at = [&](int i) -> const core::PositionSample& { return in[static_cast<std::size_t>(i)]; };
  constexpr int kReach = 4;
  std::vector<double> residual(static_cast<std::size_t>(n), -1.0);
  std::vector<double> px, py, pz;
  for (int i = 0; i < n; ++i) {
    if (!detected(at(i))) continue;
    px.clear(), py.clear(), pz.clear();
    std::vector<int> before, after;
    for (int j = i - 1; j >= 0 && static_cast<int>(before.size()) < kReach && i - j <= 2 * kReach; --j)
      if (detected(at(j))) before.push_back(j);
    for (int j = i + 1; j < n && static_cast<int>(after.size()) < kReach && j - i <= 2 * kReach; ++j)
      if (detected(at(j))) after.push_back(j);
    for (int a : before)
      for (int b : after) {
        const double w = (at(i).t_s - at(a).t_s) / (at(b).t_s - at(a).t_s);
        const Eigen::Vector3d p = at(a).p_m + w * (at(b).p_m - at(a).p_m);
        px.push_back(p.x()), py.push_back(p.y()), pz.push_back(p.z());
      }
    if (px.size() < 3) continue;
    auto med = [](std::vector<double>& v) {
      std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
      return v[v.size() / 2];
    };
    residual[static_cast<std::size_t>(i)] = (at(i).p_m - Eigen::Vector3d(med(px), med(py), med(pz))).norm();
  }
  std::vector<double> valid;
  for (double r : residual)
    if (r >= 0) valid.push_back(r);
  double spread = 0.0;
  if (!valid.empty()) {
    std::nth_element(valid.begin(), valid.begin() + static_cast<long>(valid.size() / 2), valid.end());
    spread = 1.4826 * valid[valid.size() / 2];
  }
  spread_m = spread;
  const double gate_m = std::max(sigmas * spread, min_m);
  core::PositionTrajectory out = in;
  const core::PositionSample* previous = nullptr;
  for (int i = 0; i < n; ++i) {
    auto& s = out.samples()[static_cast<std::size_t>(i)];
    if (!detected(at(i))) continue;
    const bool repeat = previous && previous->p_m == at(i).p_m;
    previous = &at(i);
    if (repeat || residual[static_cast<std::size_t>(i)] > gate_m) s.valid = false, s.p_m.setZero();
  }
  return out;
}

/// Per-axis running median of the detections within +-half samples (the
/// previous value where there is none): robust to outlier runs shorter than
/// half the window.
core::PositionTrajectory runningMedian(const core::PositionTrajectory& in, int half) {
  core::PositionTrajectory out = in;
  Eigen::Vector3d m, last = Eigen::Vector3d::Zero();
  bool haveLast = false;
  const int n = static_cast<int>(in.size());
  for (int i = 0; i < n; ++i) {
    auto& o = out.samples()[static_cast<std::size_t>(i)];
    // Full-size windows at the ends too (a half window there is as weak as a short one).
    const int centre = std::clamp(i, std::min(half, n - 1), std::max(0, n - 1 - half));
    if (windowMedian(in, centre, half, 1, m)) last = m, haveLast = true;
    o.p_m = last;
    o.valid = haveLast;
  }
  // Leading samples before the first median: the first one.
  for (auto& o : out.samples())
    if (!o.valid) o.p_m = last;
  for (auto& o : out.samples()) o.valid = true;
  return out;
}

/// Per-axis median of the detections among the `count` samples from the
/// first (fromEnd: last) detection; when fewer than 5 are detected there (a
/// part seen only now and then), the window is extended to 5 detections, but
/// only by detections within `restTolerance_m` of the window's median: a part
/// seen once at its start and then only at its final place keeps its start.
Eigen::Vector3d medianDetection(const core::PositionTrajectory& t, int count, bool fromEnd, double restTolerance_m) {
  core::PositionTrajectory part(t.frame());
  const int n = static_cast<int>(t.size());
  constexpr int kMinDetections = 5;
  auto at = [&](int k) -> const core::PositionSample& { return t[static_cast<std::size_t>(fromEnd ? n - 1 - k : k)]; };
  int first = 0;
  while (first < n && !detected(at(first))) ++first;
  int k = first;
  for (; k < n && k < first + count; ++k)
    if (detected(at(k))) part.samples().push_back(at(k));  // order does not matter for the median
  Eigen::Vector3d m = Eigen::Vector3d::Zero();
  if (part.empty()) return m;
  windowMedian(part, 0, static_cast<int>(part.size()), 1, m);
  if (static_cast<int>(part.size()) >= kMinDetections) return m;
  const Eigen::Vector3d windowMedian_m = m;
  for (; k < n && static_cast<int>(part.size()) < kMinDetections; ++k)
    if (detected(at(k)) && (at(k).p_m - windowMedian_m).norm() <= restTolerance_m) part.samples().push_back(at(k));
  windowMedian(part, 0, static_cast<int>(part.size()), 1, m);
  return m;
}

void validateInputs(const core::PositionTrajectory& hand, const std::map<std::string, const ObjectTrack*>& byName,
                    const std::vector<std::string>& planOrder) {
  core::require(!planOrder.empty(), "segmentation: the plan has no target object; give the ordered object names");
  validateTrajectory(hand, "hand trajectory");
  for (const auto& name : planOrder) {
    const auto it = byName.find(name);
    if (it == byName.end())
      throw InvalidInputError("plan object '" + name + "' has no trajectory; give its track or remove it from the plan");
    const auto& track = it->second->positions;
    validateTrajectory(track, "trajectory of '" + name + "'");
    if (track.size() != hand.size())
      throw InvalidInputError("trajectory of '" + name + "' has " + std::to_string(track.size()) +
                              " samples, the hand " + std::to_string(hand.size()) + "; sample the same frames");
    for (std::size_t i = 0; i < track.size(); ++i)
      if (track[i].frame != hand[i].frame)
        throw InvalidInputError("trajectory of '" + name + "' sample " + std::to_string(i) + " is frame " +
                                std::to_string(track[i].frame) + ", the hand's is " + std::to_string(hand[i].frame));
  }
}

/// The hand as every object's pass reads it (prepared once per demo).
struct PreparedHand {
  const core::PositionTrajectory& raw;  ///< as given: frame numbers, first/last detection
  core::PositionTrajectory events;      ///< detections the events are read from (robust: jumps, repeats dropped)
  core::PositionTrajectory smoothed;    ///< Kalman/RTS smoothed `events`
  double restNoiseTol_m = 0.0;          ///< robust: a hand rest's tolerance from the whole track's noise
};

/// One plan object's segmentation, in the steps of the file comment and the
/// module README ("Segmentation"): the part's track and rests, not moved, the
/// final rest's labels, mid-move, coarse release, the grasp valley, the hand's
/// rest boundaries, confidence.
class ObjectPass {
 public:
  /// `earlier`: the plan objects before this one, segmented.
  ObjectPass(const Segmenter::Options& config, bool robust, const PreparedHand& hand, const ObjectTrack& track,
             int start, const std::vector<ObjectSegmentation>& earlier)
      : c_(config),
        robust_(robust),
        cues_(robust && config.placementCues),
        hand_(hand),
        track_(track.positions),
        earlier_(earlier),
        start_(start),
        n_(static_cast<int>(hand.raw.size())),
        w_(std::max(1, std::min(15, n_ / 10))) {
    seg_.name = track.name;
    seg_.searchStartIndex = start;
  }

  /// The object's segmentation; an unusual object adds a warning.
  ObjectSegmentation run(std::vector<std::string>& warnings) {
    smoothTrack();
    if (!moved(warnings)) return std::move(seg_);
    labelFinalRest();
    const int searchFrom = midMove();
    const int coarse = coarseRelease(searchFrom);
    int from = start_;
    if (coarse <= start_) {
      seg_.note = "object '" + seg_.name + "' comes to rest (sample " + std::to_string(coarse) +
                  ") before the previous plan object's release (sample " + std::to_string(start_) +
                  "): the plan order and the demo disagree; grasp searched from the demo start";
      warnings.push_back(seg_.note);
      from = 0;
    }
    // Before the middle of the move (an object put back where it was has the
    // hand near its initial position at the release too), and not before the
    // hand has left the part's start area.
    int to = std::max(std::min(coarse, searchFrom), from + 1);
    if (cues_) to = untilHandLeftStart(from, to, coarse);
    const std::vector<int> valley = graspValley(from, to);
    int grasp = valley[valley.size() / 2], release = coarse;
    if (c_.events == Segmenter::EventEstimator::HandDwellBoundary) {
      grasp = refineGrasp(valley, grasp, from, to);
      if (cues_) grasp = partStillAtStart(grasp, from, to);
      release = refineRelease(grasp, coarse);
      if (cues_) release = std::max(grasp + 1, std::min(release, seenAtFinalPlace(grasp + 1)));
    }
    seg_.graspIndex = grasp;
    seg_.releaseIndex = release;
    seg_.graspFrame = hand_.raw[static_cast<std::size_t>(grasp)].frame;
    seg_.releaseFrame = hand_.raw[static_cast<std::size_t>(release)].frame;
    seg_.graspHandDistance_m = handDistance_m_[static_cast<std::size_t>(grasp - from)];
    if (robust_) confidence(release, coarse);
    return std::move(seg_);
  }

 private:
  const core::PositionSample& raw(int i) const { return track_[static_cast<std::size_t>(i)]; }
  /// The detection at i if it is evidence of the part (placement cues), else not detected.
  const core::PositionSample& ev(int i) const { return evidence_[static_cast<std::size_t>(i)]; }
  const Eigen::Vector3d& smoothedHand(int i) const { return hand_.smoothed[static_cast<std::size_t>(i)].p_m; }

  /// Step 2: the part's track and its rest positions.
  void smoothTrack() {
    const std::string& name = seg_.name;
    if (robust_) {
      // Rest positions: medians of many detections (up to a fifth of them may
      // be outliers); the trajectory: a long running median (outlier runs of
      // a few frames vanish, the move is kept).
      core::require(track_.validCount() > 0, "trajectory of '" + name + "' has no detection");
      const int wr = std::max(1, std::min(c_.restMedianSamples, n_ / 5));
      evidence_ = cues_ ? partEvidence(wr) : track_;
      // The running median never outvotes a rest of wr samples: its window
      // (2 half + 1 samples, full size at the ends) holds at most 2 wr - 1, so
      // a short recording's final rest survives it.
      seg_.smoothed = runningMedian(evidence_, std::min(c_.objectMedianHalfWindow, std::max(1, wr - 1)));
      seg_.p_initial_m = medianDetection(evidence_, wr, false, c_.restTolerance_m);
      seg_.p_final_m = medianDetection(evidence_, wr, true, c_.restTolerance_m);
    } else {
      evidence_ = track_;
      const core::PositionTrajectory filtered = removeFlicker(
          dropMovesWithoutHand(track_, hand_.smoothed, c_.flickerGate_m, c_.handReach_m, c_.maxObjectSpeed_mps),
          c_.medianWindow, c_.flickerGate_m);
      core::require(filtered.validCount() > 0, "trajectory of '" + name + "' has no detection");
      seg_.smoothed = KalmanSmoother(c_.objectSmoother).smooth(filtered);
      seg_.p_initial_m = medianPosition(seg_.smoothed, 0, w_);
      seg_.p_final_m = medianPosition(seg_.smoothed, n_ - w_, n_);
    }
    for (const auto& s : seg_.smoothed.samples())
      seg_.maxExcursion_m = std::max(seg_.maxExcursion_m, (s.p_m - seg_.p_initial_m).norm());
  }

  /// Placement cues: the part's detections without those within handRadius of
  /// the detected hand (the hand labelled as the part) and those at the final
  /// place of another plan part released earlier, from its release on (that
  /// part labelled as this one: two parts cannot rest in one place), unless
  /// this part starts there. All of them when nothing is left.
  core::PositionTrajectory partEvidence(int restSamples) const {
    const Eigen::Vector3d p_start = medianDetection(track_, restSamples, false, c_.restTolerance_m);
    std::vector<const ObjectSegmentation*> ghosts;
    for (const auto& o : earlier_)
      if (o.moved && o.name != seg_.name && (o.p_final_m - p_start).norm() >= c_.restTolerance_m) ghosts.push_back(&o);
    core::PositionTrajectory out = track_;
    for (int i = 0; i < n_; ++i) {
      auto& s = out.samples()[static_cast<std::size_t>(i)];
      if (!detected(s)) continue;
      bool drop = detected(hand_.raw[static_cast<std::size_t>(i)]) && (s.p_m - smoothedHand(i)).norm() < c_.handRadius_m;
      for (const auto* g : ghosts) drop = drop || (i > g->releaseIndex && (s.p_m - g->p_final_m).norm() < c_.restTolerance_m);
      if (drop) s.valid = false, s.p_m.setZero();
    }
    return out.validCount() > 0 ? out : track_;
  }

  /// Step 3: an object that never leaves its initial position is reported, not segmented.
  bool moved(std::vector<std::string>& warnings) {
    if (seg_.maxExcursion_m >= c_.minExcursion_m) return seg_.moved = true;
    std::ostringstream msg;
    msg << "object '" << seg_.name << "' never moves (largest excursion " << seg_.maxExcursion_m * 1e3 << " mm < "
        << c_.minExcursion_m * 1e3 << " mm): no grasp or release";
    seg_.note = msg.str();
    seg_.component.assign(static_cast<std::size_t>(n_), 0);
    warnings.push_back(seg_.note);
    return false;
  }

  /// Step 4: per sample, in the final rest or not (robust: a detection within
  /// restTolerance of the final position, so a nudge after the release stays
  /// inside it; otherwise the mixture's components and the one the trajectory ends in).
  void labelFinalRest() {
    if (robust_) {
      seg_.component.assign(static_cast<std::size_t>(n_), 1);
      for (int i = 0; i < n_; ++i)
        if (detected(ev(i)) && (ev(i).p_m - seg_.p_final_m).norm() < c_.restTolerance_m)
          seg_.component[static_cast<std::size_t>(i)] = 2;
      finalComponent_ = 2;
      return;
    }
    seg_.component =
        mixtureLabels(seg_.smoothed, seg_.p_initial_m, seg_.p_final_m, c_.emMaxIterations, 0.5 * c_.minExcursion_m);
    std::vector<int> tailCount(kComponents, 0);
    for (int i = n_ - w_; i < n_; ++i) ++tailCount[static_cast<std::size_t>(seg_.component[static_cast<std::size_t>(i)])];
    finalComponent_ = static_cast<int>(std::max_element(tailCount.begin(), tailCount.end()) - tailCount.begin());
  }
  bool inFinal(int i) const { return seg_.component[static_cast<std::size_t>(i)] == finalComponent_; }

  double distanceFromRests(const Eigen::Vector3d& p) const {
    return std::min((p - seg_.p_initial_m).norm(), (p - seg_.p_final_m).norm());
  }

  /// The release comes after the moving part: the sample farthest from both
  /// rest positions (mid-move, or the top of the lift when the object is put
  /// back where it was and the components are out of temporal order).
  int midMove() const {
    // Robust: the object is away from its rests only in the hand, and for a
    // whole carry (1-4 s); outlier clusters that survive the running median
    // are shorter. So: the longest run (gaps of up to kGap samples) of
    // samples away from both rests by minExcursion with the hand near, and
    // the farthest sample in it.
    constexpr int kGap = 3;
    auto smoothedAway = [&](int i) { return distanceFromRests(seg_.smoothed[static_cast<std::size_t>(i)].p_m); };
    auto away = [&](int i) {
      return detected(ev(i)) && distanceFromRests(ev(i).p_m) > c_.minExcursion_m &&
             smoothedAway(i) > c_.minExcursion_m &&
             (smoothedHand(i) - seg_.smoothed[static_cast<std::size_t>(i)].p_m).norm() <= c_.handReach_m;
    };
    int runFrom = -1, runTo = -1, bestFrom = -1, bestTo = -1;
    int against = 0;  // placement cues: detections since runTo that are evidence and not away (no evidence: unknown)
    if (robust_) {
      for (int i = start_; i < n_; ++i) {
        if (!away(i)) {
          against += cues_ && detected(ev(i));
          continue;
        }
        if (runFrom >= 0 && (cues_ ? against <= kGap : i - runTo <= kGap + 1)) runTo = i;
        else runFrom = runTo = i;
        against = 0;
        if (runTo - runFrom > bestTo - bestFrom) bestFrom = runFrom, bestTo = runTo;
      }
    }
    // No such run (a detector that reports nothing while the part is in the
    // hand, e.g. srp perceive): the farthest sample of the gated, smoothed
    // track, which bridges the carry (the estimator before issue 18).
    constexpr int kMinRun = 30;  // a carry lasts 1-4 s (issue 18); shorter runs are occlusion artefacts
    const bool haveRun = bestFrom >= 0 && bestTo - bestFrom + 1 >= kMinRun;
    core::PositionTrajectory bridged;
    if (robust_ && !haveRun)
      bridged = KalmanSmoother(c_.objectSmoother)
                    .smooth(removeFlicker(dropMovesWithoutHand(evidence_, hand_.smoothed, c_.flickerGate_m,
                                                               c_.handReach_m, c_.maxObjectSpeed_mps),
                                          c_.medianWindow, c_.flickerGate_m));
    const int lo = haveRun ? bestFrom : start_, hi = haveRun ? bestTo + 1 : n_;
    int searchFrom = start_;
    double farthest = -1.0;
    for (int i = lo; i < hi; ++i) {
      const double d = bridged.empty() ? smoothedAway(i) : distanceFromRests(bridged[static_cast<std::size_t>(i)].p_m);
      if (d > farthest) farthest = d, searchFrom = i;
    }
    return searchFrom;
  }

  /// Step 5: the release as the change point after which the object is in the
  /// final component, placed where the fewest labels disagree: samples before
  /// it in the final component plus samples after it outside. Unlike "the
  /// first sample of the last run" this is not broken by a few flickering or
  /// occluded samples after the release. Robust: a Bernoulli change point.
  /// While carried, a detection is in the final rest with probability
  /// carriedInRest (the last few frames of the descent); in the final rest
  /// with probability restInRest (outliers and the hand lingering over the
  /// part take the rest). Costs = -log likelihoods; the mixture's labels (not
  /// robust) weigh both kinds of disagreement alike. Sets the release margin.
  int coarseRelease(int searchFrom) {
    const double qb = robust_ ? c_.carriedInRest : 0.5, qa = robust_ ? c_.restInRest : 0.5;
    const double inBefore = -std::log(qb), outBefore = -std::log(1 - qb), inAfter = -std::log(qa),
                 outAfter = -std::log(1 - qa);
    auto counts = [&](int i) { return !robust_ || detected(ev(i)); };
    double after = 0.0;
    for (int i = searchFrom; i < n_; ++i)
      if (counts(i)) after += inFinal(i) ? inAfter : outAfter;
    double before = 0.0, bestCost = std::numeric_limits<double>::infinity();
    int release = n_ - 1;
    std::vector<double> costs;
    for (int r = searchFrom; r < n_; ++r) {
      const double cost = before + after;
      costs.push_back(cost);
      if (cost < bestCost - 1e-9) bestCost = cost, release = r;
      if (counts(r)) {
        before += inFinal(r) ? inBefore : outBefore;
        after -= inFinal(r) ? inAfter : outAfter;
      }
    }
    // The change point lands on the first final-component sample of its run.
    while (release < n_ - 1 && !inFinal(release)) ++release;
    // Margin: the best change point more than kMarginSamples away, in nats.
    constexpr int kMarginSamples = 30;  // a competing release a second or more away (a nudge, a lingering hand)
    double alternative = std::numeric_limits<double>::infinity();
    for (int r = searchFrom; r < n_; ++r)
      if (std::abs(r - release) > kMarginSamples && detected(ev(r)))
        alternative = std::min(alternative, costs[static_cast<std::size_t>(r - searchFrom)]);
    if (robust_) seg_.releaseMargin = std::isfinite(alternative) ? alternative - bestCost : 0.0;
    // Placement cues: the part seen at its final place for good (a part
    // lowered through the final place's zone, or a wrong depth on the table
    // below it, then hidden under the hand until it leaves, is not yet there).
    if (cues_)
      while (release < n_ - 1 && !(inFinal(release) && sustained(release, [&](int j) { return inFinal(j); }))) ++release;
    return release;
  }

  /// Samples in the window sustainRest_s long that the part's final-place test should hold in.
  int sustainWindow() const {
    const double dt_s = n_ > 1 ? (hand_.raw[static_cast<std::size_t>(n_ - 1)].t_s - hand_.raw[0].t_s) / (n_ - 1) : 0.0;
    return std::max(8, dt_s > 0.0 ? static_cast<int>(std::lround(c_.sustainRest_s / dt_s)) : 0);
  }

  /// `at(j)` holds for good from r: in at least half of the samples of the
  /// next sustainRest_s, or in at least half of the part's evidence there
  /// when that is at least sustainMinSeenShare of the samples (a part
  /// hidden under a lingering hand for most of the window is still there).
  template <class At>
  bool sustained(int r, const At& at) const {
    const int window = sustainWindow();
    const int to = std::min(n_, r + window);
    int in = 0, seen = 0;
    for (int j = r; j < to; ++j) in += at(j), seen += detected(ev(j));
    const int minSeen = static_cast<int>(std::ceil(c_.sustainMinSeenShare * window));
    return 2 * in >= to - r || (seen >= minSeen && 2 * in >= seen);
  }

  /// Placement cues, release: the first sample from lo at which the part is
  /// seen at its final place itself (within placeTolerance: not in the hand
  /// above it) for good; n_ when never. A part already standing at its place
  /// is let go, whatever the hand still does (it may rest on the part or
  /// press it down); a hover above the place is not there yet.
  int seenAtFinalPlace(int lo) const {
    auto atPlace = [&](int j) { return detected(ev(j)) && (ev(j).p_m - seg_.p_final_m).norm() <= c_.placeTolerance_m; };
    for (int r = std::max(lo, 0); r < n_; ++r)
      if (atPlace(r) && sustained(r, atPlace)) return r;
    return n_;
  }

  /// Placement cues, grasp: the last sample in [from, to) at which the part
  /// is seen at its initial place itself (within placeTolerance); -1 when
  /// never. It is not yet carried there, so the grasp is not earlier.
  int lastSeenAtStart(int from, int to) const {
    for (int i = std::min(to, n_) - 1; i >= from; --i)
      if (detected(ev(i)) && (ev(i).p_m - seg_.p_initial_m).norm() <= c_.placeTolerance_m) return i;
    return -1;
  }

  /// Placement cues, grasp: not before the last sample in [from, to) at which
  /// the part is seen at its initial place, unless the hand has been at the
  /// part's final place in between (within handReach of it and nearer to it
  /// than to the start): the part has been carried there, so what is still
  /// seen at the start is not this part (a look-alike beside it) and the
  /// hand's grasp stands.
  int partStillAtStart(int grasp, int from, int to) const {
    const int seen = lastSeenAtStart(from, to);
    if (seen <= grasp) return grasp;
    for (int i = grasp + 1; i <= seen; ++i) {
      const double toFinal_m = (smoothedHand(i) - seg_.p_final_m).norm();
      if (toFinal_m <= c_.handReach_m && toFinal_m < (smoothedHand(i) - seg_.p_initial_m).norm()) return grasp;
    }
    return seen;
  }

  /// Step 6: where the hand is closest to the object's initial position in
  /// [from, to). The hand stops there, so the distance has a flat valley: the
  /// samples within graspValleyDepth of the minimum, extended across noise
  /// bumps of up to kBump samples, in time order (the thesis' grasp is its
  /// median sample, less noise-sensitive than the bare minimum).
  std::vector<int> graspValley(int from, int to) {
    handDistance_m_.assign(static_cast<std::size_t>(to - from), 0.0);
    int closest = from;
    double best = std::numeric_limits<double>::infinity();
    for (int i = from; i < to; ++i) {
      const double d = (smoothedHand(i) - seg_.p_initial_m).norm();
      handDistance_m_[static_cast<std::size_t>(i - from)] = d;
      if (d < best) best = d, closest = i;
    }
    constexpr int kBump = 3;
    auto inValley = [&](int i) { return handDistance_m_[static_cast<std::size_t>(i - from)] < best + c_.graspValleyDepth_m; };
    std::vector<int> valley{closest};
    for (int dir : {-1, 1}) {
      int outside = 0;
      for (int i = closest + dir; i >= from && i < to && outside <= kBump; i += dir) {
        if (inValley(i)) valley.push_back(i), outside = 0;
        else ++outside;
      }
    }
    std::sort(valley.begin(), valley.end());
    return valley;
  }

  /// The grasp search ends no earlier than where the hand, having come closest
  /// to the initial position, is startAreaLeave farther from it (the hand
  /// leaves the start area only with the part), and before the coarse release.
  int untilHandLeftStart(int from, int to, int coarse) const {
    double closest_m = std::numeric_limits<double>::infinity();
    for (int i = from; i < to; ++i) closest_m = std::min(closest_m, (smoothedHand(i) - seg_.p_initial_m).norm());
    int end = to;
    for (; end < coarse; ++end) {
      const double d = (smoothedHand(end) - seg_.p_initial_m).norm();
      if (d > closest_m + c_.startAreaLeave_m) break;
      closest_m = std::min(closest_m, d);
    }
    return end;
  }

  /// Step 7, grasp: the hand's rest at the object ends where the object starts
  /// to move with it; the valley covers the rest and the start of the lift.
  int refineGrasp(const std::vector<int>& valley, int grasp, int from, int to) {
    const int g = restMoveBoundary(hand_.events, std::max(from, valley.front()),
                                   std::min(to - 1, valley.back() + c_.moveSamples), +1, c_.restSamples, c_.moveSamples,
                                   [](int) { return true; }, robust_ ? c_.boundaryMinMove_m : 0.0);
    graspRestFound_ = g >= 0;
    return g >= 0 ? restEnd(hand_.events, g, +1, c_.restSamples, from, to - 1, hand_.restNoiseTol_m) : grasp;
  }

  /// Step 7, release: the hand's rest at the object's final position starts
  /// where the object stops moving with it (searched from the grasp on: the
  /// object's detections, hence the mid-move sample, are unreliable while it
  /// is in the hand). The hand releases where it is closest to the object's
  /// final position (measured after the hand has left): this excludes its
  /// stops above the place (lift top, end of the retract).
  int refineRelease(int grasp, int coarse) const {
    const int lo = grasp + 1, hi = std::min(n_ - 1, coarse + (robust_ ? c_.releaseRefineAfter : c_.moveSamples));
    if (cues_) return arrivalAtPlace(lo, hi);
    double closest_m = std::numeric_limits<double>::infinity();
    for (int i = lo; i <= hi; ++i) closest_m = std::min(closest_m, (smoothedHand(i) - seg_.p_final_m).norm());
    auto reachFits = [&](int i) { return (smoothedHand(i) - seg_.p_final_m).norm() <= closest_m + c_.releaseReachTolerance_m; };
    const double minMove_m = robust_ ? c_.boundaryMinMove_m : 0.0;
    int r = restMoveBoundary(hand_.events, lo, hi, -1, c_.restSamples, c_.moveSamples, reachFits, minMove_m);
    if (r < 0)
      r = restMoveBoundary(hand_.events, lo, hi, -1, c_.restSamples, c_.moveSamples, [](int) { return true; }, minMove_m);
    return r >= 0 ? restEnd(hand_.events, r, -1, c_.restSamples, lo, n_ - 1) : coarse;
  }

  /// Step 7, release with the placement cues: the hand arrives where it comes
  /// closest to the part's final place: the first sample at which the smoothed
  /// hand is within closestNoiseMin of its closest approach and the median of
  /// the hand's detections around it (+-2 samples, at least 3) within twice that (a jump
  /// the outlier filter kept, which the smoother follows, is not an arrival).
  /// A hover just above the place stays farther; a hand that lets go and
  /// leaves at once has no rest there, only this closest approach.
  int arrivalAtPlace(int lo, int hi) const {
    constexpr int kHalf = 2;
    std::vector<double> smoothed_m, median_m, around;
    for (int i = lo; i <= hi; ++i) {
      smoothed_m.push_back((smoothedHand(i) - seg_.p_final_m).norm());
      around.clear();
      for (int j = std::max(0, i - kHalf); j <= std::min(n_ - 1, i + kHalf); ++j)
        if (detected(hand_.events[static_cast<std::size_t>(j)]))
          around.push_back((hand_.events[static_cast<std::size_t>(j)].p_m - seg_.p_final_m).norm());
      std::nth_element(around.begin(), around.begin() + static_cast<long>(around.size() / 2), around.end());
      median_m.push_back(around.size() < 3 ? std::numeric_limits<double>::infinity() : around[around.size() / 2]);
    }
    auto supported = [&](std::size_t k) { return std::max(smoothed_m[k], median_m[k] - c_.closestNoiseMin_m); };
    double closest_m = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < smoothed_m.size(); ++k) closest_m = std::min(closest_m, supported(k));
    for (std::size_t k = 0; k < smoothed_m.size(); ++k)
      if (supported(k) <= closest_m + c_.closestNoiseMin_m) return lo + static_cast<int>(k);
    return hi;
  }

  /// Step 8 (robust): outlier fraction, release cue gap and the confidence flags.
  void confidence(int release, int coarse) {
    int outliers = 0, count = 0;
    for (int i = 0; i < n_; ++i) {
      if (!detected(raw(i))) continue;
      ++count;
      outliers += (raw(i).p_m - seg_.smoothed[static_cast<std::size_t>(i)].p_m).norm() > 2 * c_.restTolerance_m;
    }
    seg_.outlierFraction = count > 0 ? static_cast<double>(outliers) / count : 1.0;
    // Counted in detections of the part: a part hidden under the open hand
    // after the release (rendered demos) is not a disagreement.
    for (int i = std::min(release, coarse); i < std::max(release, coarse); ++i)
      seg_.releaseCueGap += detected(ev(i)) ? (release > coarse ? 1 : -1) : 0;
    // With the placement cues a part hidden under the hand around its release
    // leaves the change point's margin small whatever the hand did, so the
    // margin is reported but does not lower the confidence.
    const bool messy = seg_.outlierFraction > 0.3;
    seg_.releaseLowConfidence = messy || (!cues_ && seg_.releaseMargin < 10.0) || std::abs(seg_.releaseCueGap) > 10;
    seg_.graspLowConfidence = messy || !graspRestFound_ || seg_.graspHandDistance_m > c_.handReach_m;
    seg_.lowConfidence = seg_.graspLowConfidence || seg_.releaseLowConfidence;
  }

  const Segmenter::Options& c_;
  const bool robust_, cues_;
  const PreparedHand& hand_;
  const core::PositionTrajectory& track_;
  const std::vector<ObjectSegmentation>& earlier_;
  core::PositionTrajectory evidence_;
  const int start_, n_, w_;
  ObjectSegmentation seg_;
  int finalComponent_ = 2;
  bool graspRestFound_ = false;  ///< the hand's rest at the part was found (step 7)
  std::vector<double> handDistance_m_;  ///< smoothed hand to p_initial over the grasp search
};

}  // namespace

Segmentation Segmenter::segment(const core::PositionTrajectory& hand, const std::vector<ObjectTrack>& objects,
                                const std::vector<std::string>& planOrder) const {
  std::map<std::string, const ObjectTrack*> byName;
  for (const auto& o : objects) byName[o.name] = &o;
  validateInputs(hand, byName, planOrder);
  if (options_.events == EventEstimator::ThesisPublished) return segmentThesisPublished(hand, objects, planOrder);

  // Robust mode refines the default estimator; the thesis-like estimator keeps its published steps.
  const bool robust = options_.robust && options_.events == EventEstimator::HandDwellBoundary;
  // Step 1, the hand (robust: jumps and carried values dropped before anything uses it).
  PreparedHand prepared{hand, hand, {}, 0.0};
  if (robust) {
    double handSpread_m = 0.0;
    prepared.events = dropHandOutliers(hand, options_.handOutlierSigmas, options_.handOutlierMin_m, handSpread_m);
    prepared.restNoiseTol_m = std::min(options_.restNoiseFactor * handSpread_m, options_.restNoiseMax_m);
  }
  prepared.smoothed = KalmanSmoother(options_.handSmoother).smooth(prepared.events);
  Segmentation result;
  result.hand = prepared.smoothed;
  const int n = static_cast<int>(hand.size());
  result.firstHandIndex = 0;
  while (result.firstHandIndex < n - 1 && !detected(hand[static_cast<std::size_t>(result.firstHandIndex)])) ++result.firstHandIndex;
  result.lastHandIndex = n - 1;
  while (result.lastHandIndex > 0 && !detected(hand[static_cast<std::size_t>(result.lastHandIndex)])) --result.lastHandIndex;
  // Steps 2-8 per object, in plan order; each search starts at the previous release.
  int start = 0;
  for (const auto& name : planOrder) {
    ObjectSegmentation seg =
        ObjectPass(options_, robust, prepared, *byName.at(name), start, result.objects).run(result.warnings);
    if (seg.moved) start = std::max(start, seg.releaseIndex);
    result.objects.push_back(std::move(seg));
  }
  return result;
}

}  // namespace srp::motion
