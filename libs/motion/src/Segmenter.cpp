#include "srp/motion/Segmenter.h"

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
  // Components whose means are closer than mergeDistance are one place (EM
  // splits a long rest, e.g. of an object put back where it was, into two).
  const cv::Mat means = em->getMeans();
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

/// Per-axis median of the detections among the first (fromEnd: last) `count`
/// samples; when fewer than 5 are detected there (a part hidden at the start or
/// end), of the first (last) `count` detections.
Eigen::Vector3d medianDetection(const core::PositionTrajectory& t, int count, bool fromEnd) {
  core::PositionTrajectory part(t.frame());
  const int n = static_cast<int>(t.size());
  constexpr int kMinDetections = 5;
  for (int k = 0; k < n; ++k) {
    if (k >= count && static_cast<int>(part.size()) >= kMinDetections) break;
    if (static_cast<int>(part.size()) >= count) break;
    const auto& s = t[static_cast<std::size_t>(fromEnd ? n - 1 - k : k)];
    if (detected(s)) part.samples().push_back(s);  // order does not matter for the median
  }
  Eigen::Vector3d m = Eigen::Vector3d::Zero();
  if (!part.empty()) windowMedian(part, 0, static_cast<int>(part.size()), 1, m);
  return m;
}

}  // namespace

Segmentation Segmenter::segment(const core::PositionTrajectory& hand, const std::vector<ObjectTrack>& objects,
                                const std::vector<std::string>& planOrder) const {
  core::require(!planOrder.empty(), "segmentation: the plan has no target object; give the ordered object names");
  // Robust mode refines the default estimator; the thesis-like estimator keeps its published steps.
  const bool robust = config_.robust && config_.events == EventEstimator::HandDwellBoundary;
  validateTrajectory(hand, "hand trajectory");
  std::map<std::string, const ObjectTrack*> byName;
  for (const auto& o : objects) byName[o.name] = &o;
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

  if (config_.events == EventEstimator::ThesisPublished) return segmentThesisPublished(hand, objects, planOrder);
  Segmentation result;
  // Robust mode: hand jumps and carried values dropped before anything uses the hand.
  double handSpread_m = 0.0;
  const core::PositionTrajectory handEvents =
      robust ? dropHandOutliers(hand, config_.handOutlierSigmas, config_.handOutlierMin_m, handSpread_m) : hand;
  const double restNoiseTol_m = robust ? std::min(config_.restNoiseFactor * handSpread_m, config_.restNoiseMax_m) : 0.0;
  result.hand = KalmanSmoother(config_.handSmoother).smooth(handEvents);
  const int n = static_cast<int>(hand.size());
  result.firstHandIndex = 0;
  while (result.firstHandIndex < n - 1 && !detected(hand[static_cast<std::size_t>(result.firstHandIndex)])) ++result.firstHandIndex;
  result.lastHandIndex = n - 1;
  while (result.lastHandIndex > 0 && !detected(hand[static_cast<std::size_t>(result.lastHandIndex)])) --result.lastHandIndex;
  const int w = std::max(1, std::min(15, n / 10));
  int start = 0;
  for (const auto& name : planOrder) {
    const ObjectTrack& track = *byName.at(name);
    ObjectSegmentation seg;
    seg.name = name;
    seg.searchStartIndex = start;
    if (robust) {
      // Rest positions: medians of many detections (up to a fifth of them may
      // be outliers); the trajectory: a long running median (outlier runs of
      // a few frames vanish, the move is kept).
      core::require(track.positions.validCount() > 0, "trajectory of '" + name + "' has no detection");
      seg.smoothed = runningMedian(track.positions, config_.objectMedianHalfWindow);
      const int wr = std::max(1, std::min(config_.restMedianSamples, n / 5));
      seg.p_initial_m = medianDetection(track.positions, wr, false);
      seg.p_final_m = medianDetection(track.positions, wr, true);
    } else {
      const core::PositionTrajectory filtered =
          removeFlicker(dropMovesWithoutHand(track.positions, result.hand, config_.flickerGate_m, config_.handReach_m,
                                             config_.maxObjectSpeed_mps),
                        config_.medianWindow, config_.flickerGate_m);
      core::require(filtered.validCount() > 0, "trajectory of '" + name + "' has no detection");
      seg.smoothed = KalmanSmoother(config_.objectSmoother).smooth(filtered);
      seg.p_initial_m = medianPosition(seg.smoothed, 0, w);
      seg.p_final_m = medianPosition(seg.smoothed, n - w, n);
    }
    for (const auto& s : seg.smoothed.samples())
      seg.maxExcursion_m = std::max(seg.maxExcursion_m, (s.p_m - seg.p_initial_m).norm());
    if (seg.maxExcursion_m < config_.minExcursion_m) {
      std::ostringstream msg;
      msg << "object '" << name << "' never moves (largest excursion " << seg.maxExcursion_m * 1e3
          << " mm < " << config_.minExcursion_m * 1e3 << " mm): no grasp or release";
      seg.note = msg.str();
      seg.component.assign(static_cast<std::size_t>(n), 0);
      result.warnings.push_back(seg.note);
      result.objects.push_back(std::move(seg));
      continue;
    }
    seg.moved = true;
    if (robust) {
      // In the final rest: a detection within restTolerance of the final
      // position (a nudge after the release stays inside it).
      seg.component.assign(static_cast<std::size_t>(n), 1);
      for (int i = 0; i < n; ++i)
        if (detected(track.positions[static_cast<std::size_t>(i)]) &&
            (track.positions[static_cast<std::size_t>(i)].p_m - seg.p_final_m).norm() < config_.restTolerance_m)
          seg.component[static_cast<std::size_t>(i)] = 2;
    } else {
      seg.component = mixtureLabels(seg.smoothed, seg.p_initial_m, seg.p_final_m, config_.emMaxIterations,
                                    0.5 * config_.minExcursion_m);
    }

    // Release: the change point after which the object is in the final
    // component (the one the trajectory ends in), placed where the fewest
    // labels disagree: samples before it in the final component plus samples
    // after it outside. Unlike "the first sample of the last run" this is not
    // broken by a few flickering or occluded samples after the release.
    std::vector<int> tailCount(kComponents, 0);
    for (int i = n - w; i < n; ++i) ++tailCount[static_cast<std::size_t>(seg.component[static_cast<std::size_t>(i)])];
    const int finalComponent = robust ? 2 : static_cast<int>(std::max_element(tailCount.begin(), tailCount.end()) - tailCount.begin());
    auto inFinal = [&](int i) { return seg.component[static_cast<std::size_t>(i)] == finalComponent; };
    // The release comes after the moving part: search from the sample farthest
    // from both rest positions (mid-move, or the top of the lift when the
    // object is put back where it was and the components are out of temporal order).
    int searchFrom = start;
    {
      // Robust: the object is away from its rests only in the hand, and for a
      // whole carry (1-4 s); outlier clusters that survive the running median
      // are shorter. So: the longest run (gaps of up to kGap samples) of
      // samples away from both rests by minExcursion with the hand near, and
      // the farthest sample in it.
      constexpr int kGap = 3;
      auto distanceFromRests = [&](int i) {
        const Eigen::Vector3d& p = seg.smoothed[static_cast<std::size_t>(i)].p_m;
        return std::min((p - seg.p_initial_m).norm(), (p - seg.p_final_m).norm());
      };
      auto away = [&](int i) {
        const auto& raw = track.positions[static_cast<std::size_t>(i)];
        return detected(raw) && std::min((raw.p_m - seg.p_initial_m).norm(), (raw.p_m - seg.p_final_m).norm()) > config_.minExcursion_m &&
               distanceFromRests(i) > config_.minExcursion_m &&
               (result.hand[static_cast<std::size_t>(i)].p_m - seg.smoothed[static_cast<std::size_t>(i)].p_m).norm() <=
                   config_.handReach_m;
      };
      int runFrom = -1, runTo = -1, bestFrom = -1, bestTo = -1;
      if (robust) {
        for (int i = start; i < n; ++i) {
          if (!away(i)) continue;
          if (runFrom >= 0 && i - runTo <= kGap + 1) runTo = i;
          else runFrom = runTo = i;
          if (runTo - runFrom > bestTo - bestFrom) bestFrom = runFrom, bestTo = runTo;
        }
      }
      // No such run (a detector that reports nothing while the part is in the
      // hand, e.g. srp perceive): the farthest sample of the gated, smoothed
      // track, which bridges the carry (the estimator before issue 18).
      constexpr int kMinRun = 30;  // a carry lasts 1-4 s (issue 18); shorter runs are occlusion artefacts
      const bool haveRun = bestFrom >= 0 && bestTo - bestFrom + 1 >= kMinRun;
      core::PositionTrajectory bridged;
      if (robust && !haveRun)
        bridged = KalmanSmoother(config_.objectSmoother)
                      .smooth(removeFlicker(dropMovesWithoutHand(track.positions, result.hand, config_.flickerGate_m,
                                                                 config_.handReach_m, config_.maxObjectSpeed_mps),
                                            config_.medianWindow, config_.flickerGate_m));
      const int lo = haveRun ? bestFrom : start, hi = haveRun ? bestTo + 1 : n;
      double farthest = -1.0;
      for (int i = lo; i < hi; ++i) {
        double d = distanceFromRests(i);
        if (!bridged.empty()) {
          const Eigen::Vector3d& p = bridged[static_cast<std::size_t>(i)].p_m;
          d = std::min((p - seg.p_initial_m).norm(), (p - seg.p_final_m).norm());
        }
        if (d > farthest) farthest = d, searchFrom = i;
      }
    }
    int release = n - 1;
    {
      // Robust: a Bernoulli change point. While carried, a detection is in
      // the final rest with probability carriedInRest (the last few frames of the
      // descent); in the final rest with probability restInRest (outliers and
      // the hand lingering over the part take the rest). Costs = -log likelihoods;
      // the mixture's labels (not robust) weigh both kinds of disagreement alike.
      const double qb = robust ? config_.carriedInRest : 0.5, qa = robust ? config_.restInRest : 0.5;
      const double inBefore = -std::log(qb), outBefore = -std::log(1 - qb), inAfter = -std::log(qa),
                   outAfter = -std::log(1 - qa);
      double after = 0.0;
      for (int i = searchFrom; i < n; ++i)
        if (!robust || detected(track.positions[static_cast<std::size_t>(i)])) after += inFinal(i) ? inAfter : outAfter;
      double before = 0.0, bestCost = std::numeric_limits<double>::infinity();
      std::vector<double> costs;
      for (int r = searchFrom; r < n; ++r) {
        const double cost = before + after;
        costs.push_back(cost);
        if (cost < bestCost - 1e-9) bestCost = cost, release = r;
        if (!robust || detected(track.positions[static_cast<std::size_t>(r)])) {
          before += inFinal(r) ? inBefore : outBefore;
          after -= inFinal(r) ? inAfter : outAfter;
        }
      }
      // The change point lands on the first final-component sample of its run.
      while (release < n - 1 && !inFinal(release)) ++release;
      // Margin: the best change point more than kMarginSamples away, in nats.
      constexpr int kMarginSamples = 30;  // a competing release a second or more away (a nudge, a lingering hand)
      double alternative = std::numeric_limits<double>::infinity();
      for (int r = searchFrom; r < n; ++r)
        if (std::abs(r - release) > kMarginSamples && detected(track.positions[static_cast<std::size_t>(r)])) alternative = std::min(alternative, costs[static_cast<std::size_t>(r - searchFrom)]);
      if (robust) seg.releaseMargin = std::isfinite(alternative) ? alternative - bestCost : 0.0;
    }
    const int coarseRelease = release;
    int from = start;
    if (release <= start) {
      seg.note = "object '" + name + "' comes to rest (sample " + std::to_string(release) +
                 ") before the previous plan object's release (sample " + std::to_string(start) +
                 "): the plan order and the demo disagree; grasp searched from the demo start";
      result.warnings.push_back(seg.note);
      from = 0;
    }
    // Grasp: where the hand is closest to the object's initial position. The
    // hand stops there, so the distance has a flat valley; its centre is less
    // noise-sensitive than the bare minimum.
    // Before the middle of the move (an object put back where it was has the
    // hand near its initial position at the release too).
    const int to = std::max(std::min(release, searchFrom), from + 1);
    std::vector<double> dist(static_cast<std::size_t>(to - from));
    int grasp = from;
    double best = std::numeric_limits<double>::infinity();
    for (int i = from; i < to; ++i) {
      dist[static_cast<std::size_t>(i - from)] = (result.hand[static_cast<std::size_t>(i)].p_m - seg.p_initial_m).norm();
      if (dist[static_cast<std::size_t>(i - from)] < best) best = dist[static_cast<std::size_t>(i - from)], grasp = i;
    }
    // The valley: samples within graspValleyDepth of the minimum, extended
    // across noise bumps of up to kBump samples; the grasp is its median sample.
    constexpr int kBump = 3;
    auto inValley = [&](int i) { return dist[static_cast<std::size_t>(i - from)] < best + config_.graspValleyDepth_m; };
    std::vector<int> valley{grasp};
    for (int dir : {-1, 1}) {
      int outside = 0;
      for (int i = grasp + dir; i >= from && i < to && outside <= kBump; i += dir) {
        if (inValley(i)) valley.push_back(i), outside = 0;
        else ++outside;
      }
    }
    std::sort(valley.begin(), valley.end());
    grasp = valley[valley.size() / 2];
    if (config_.events == EventEstimator::HandDwellBoundary) {
      // Grasp: the hand's rest at the object ends where the object starts to
      // move with it; the valley covers the rest and the start of the lift.
      const int g = restMoveBoundary(handEvents, std::max(from, valley.front()), std::min(to - 1, valley.back() + config_.moveSamples),
                                     +1, config_.restSamples, config_.moveSamples, [](int) { return true; },
                                     robust ? config_.boundaryMinMove_m : 0.0);
      if (g >= 0) grasp = restEnd(handEvents, g, +1, config_.restSamples, from, to - 1, restNoiseTol_m);
      // Release: the hand's rest at the object's final position starts where
      // the object stops moving with it (searched from the grasp on: the
      // object's detections, hence the mid-move sample, are unreliable while
      // it is in the hand). The hand releases where it is closest to the
      // object's final position (measured after the hand has left): this
      // excludes its stops above the place (lift top, end of the retract).
      const int lo = grasp + 1, hi = std::min(n - 1, release + (robust ? config_.releaseRefineAfter : config_.moveSamples));
      double closest_m = std::numeric_limits<double>::infinity();
      for (int i = lo; i <= hi; ++i)
        closest_m = std::min(closest_m, (result.hand[static_cast<std::size_t>(i)].p_m - seg.p_final_m).norm());
      auto reachFits = [&](int i) {
        return (result.hand[static_cast<std::size_t>(i)].p_m - seg.p_final_m).norm() <=
               closest_m + config_.releaseReachTolerance_m;
      };
      const double minMove_m = robust ? config_.boundaryMinMove_m : 0.0;
      int r = restMoveBoundary(handEvents, lo, hi, -1, config_.restSamples, config_.moveSamples, reachFits, minMove_m);
      if (r < 0)
        r = restMoveBoundary(handEvents, lo, hi, -1, config_.restSamples, config_.moveSamples, [](int) { return true; }, minMove_m);
      if (r >= 0) release = restEnd(handEvents, r, -1, config_.restSamples, lo, n - 1);
    }
    if (robust) {
      int outliers = 0, count = 0;
      for (int i = 0; i < n; ++i) {
        const auto& s = track.positions[static_cast<std::size_t>(i)];
        if (!detected(s)) continue;
        ++count;
        outliers += (s.p_m - seg.smoothed[static_cast<std::size_t>(i)].p_m).norm() > 2 * config_.restTolerance_m;
      }
      seg.outlierFraction = count > 0 ? static_cast<double>(outliers) / count : 1.0;
      // Counted in detections of the part: a part hidden under the open hand
      // after the release (rendered demos) is not a disagreement.
      for (int i = std::min(release, coarseRelease); i < std::max(release, coarseRelease); ++i)
        seg.releaseCueGap += detected(track.positions[static_cast<std::size_t>(i)]) ? (release > coarseRelease ? 1 : -1) : 0;
      seg.lowConfidence = seg.outlierFraction > 0.3 || seg.releaseMargin < 10.0 || std::abs(seg.releaseCueGap) > 10;
    }
    seg.graspIndex = grasp;
    seg.releaseIndex = release;
    seg.graspFrame = hand[static_cast<std::size_t>(grasp)].frame;
    seg.releaseFrame = hand[static_cast<std::size_t>(release)].frame;
    seg.graspHandDistance_m = dist[static_cast<std::size_t>(grasp - from)];
    start = std::max(start, release);
    result.objects.push_back(std::move(seg));
  }
  return result;
}

}  // namespace srp::motion
