// Segmenter::EventEstimator::ThesisPublished: the thesis' published
// segmentation (shuanglu2023/SemanticRobotProgramming at 861470e0, MIT:
// env_module/utils.py smooth_traj, env_module/segmentation.py segmentation,
// env_module/env_module.py EnvModule.seg; the reference copy is described in
// libs/motion/README.md). Re-implemented in C++ from its rules, not translated.
#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <map>
#include <opencv2/core.hpp>

#include "srp/core/Error.h"
#include "srp/motion/Segmenter.h"

namespace srp::motion {
namespace {

bool isDetected(const core::PositionSample& s) { return s.valid && !(s.p_m.array() == 0.0).all(); }

/// pykalman.KalmanFilter(transition_matrices=I, observation_matrices=I).smooth(z)[0]
/// with its defaults (Q = R = I, initial mean 0, initial covariance I): all
/// matrices are multiples of I, so each axis is the same scalar filter.
std::vector<Eigen::Vector3d> pykalmanIdentitySmooth(const std::vector<Eigen::Vector3d>& z) {
  const std::size_t n = z.size();
  std::vector<Eigen::Vector3d> xf(n), xp(n), xs(n);
  std::vector<double> pf(n), pp(n);
  for (std::size_t t = 0; t < n; ++t) {
    xp[t] = t == 0 ? Eigen::Vector3d::Zero() : xf[t - 1];
    pp[t] = t == 0 ? 1.0 : pf[t - 1] + 1.0;  // + Q
    const double k = pp[t] / (pp[t] + 1.0);  // R = 1
    xf[t] = xp[t] + k * (z[t] - xp[t]);
    pf[t] = (1.0 - k) * pp[t];
  }
  if (n == 0) return xs;
  xs[n - 1] = xf[n - 1];
  for (std::size_t t = n - 1; t-- > 0;) {
    const double gain = pf[t] / pp[t + 1];
    xs[t] = xf[t] + gain * (xs[t + 1] - xp[t + 1]);
  }
  return xs;
}

/// sklearn.mixture.GaussianMixture(n_components=3) with its defaults
/// (covariance_type "full", tol 1e-3, reg_covar 1e-6, max_iter 100, n_init 1,
/// init_params "kmeans"), fit(X) then predict(X). The k-means initialisation
/// is OpenCV's (k-means++ seeding, one attempt) from `seed`, not sklearn's
/// random stream: labels match sklearn's for some seed, not for the same number.
std::vector<int> gaussianMixtureLabels(const std::vector<Eigen::Vector3d>& x, unsigned seed) {
  constexpr int K = 3;
  const int n = static_cast<int>(x.size());
  std::vector<int> labels(static_cast<std::size_t>(n), 0);
  if (n < K) return labels;
  cv::Mat data(n, 3, CV_32F);
  for (int i = 0; i < n; ++i)
    for (int a = 0; a < 3; ++a) data.at<float>(i, a) = static_cast<float>(x[static_cast<std::size_t>(i)](a));
  cv::Mat km;
  const cv::RNG saved = cv::theRNG();
  cv::theRNG() = cv::RNG(0x9E3779B97F4A7C15ULL ^ seed);
  cv::kmeans(data, K, km, cv::TermCriteria(cv::TermCriteria::COUNT + cv::TermCriteria::EPS, 300, 1e-4), 1,
             cv::KMEANS_PP_CENTERS);
  cv::theRNG() = saved;
  Eigen::MatrixXd resp = Eigen::MatrixXd::Zero(n, K);
  for (int i = 0; i < n; ++i) resp(i, km.at<int>(i)) = 1.0;

  std::vector<double> w(K);
  std::vector<Eigen::Vector3d> mu(K);
  std::vector<Eigen::Matrix3d> cov(K);
  constexpr double kRegCovar = 1e-6, kTol = 1e-3, kEps = 2.220446049250313e-16;
  auto mStep = [&] {
    for (int k = 0; k < K; ++k) {
      const double nk = resp.col(k).sum() + 10 * kEps;
      Eigen::Vector3d m = Eigen::Vector3d::Zero();
      for (int i = 0; i < n; ++i) m += resp(i, k) * x[static_cast<std::size_t>(i)];
      m /= nk;
      Eigen::Matrix3d c = Eigen::Matrix3d::Zero();
      for (int i = 0; i < n; ++i) {
        const Eigen::Vector3d d = x[static_cast<std::size_t>(i)] - m;
        c += resp(i, k) * d * d.transpose();
      }
      cov[static_cast<std::size_t>(k)] = c / nk + kRegCovar * Eigen::Matrix3d::Identity();
      mu[static_cast<std::size_t>(k)] = m;
      w[static_cast<std::size_t>(k)] = nk / n;
    }
  };
  // Weighted log-probabilities log w_k + log N(x_i | mu_k, cov_k).
  Eigen::MatrixXd logp(n, K);
  auto weightedLogProb = [&] {
    const double log2pi = std::log(2.0 * std::acos(-1.0));
    for (int k = 0; k < K; ++k) {
      const Eigen::LLT<Eigen::Matrix3d> llt(cov[static_cast<std::size_t>(k)]);
      const Eigen::Matrix3d L = llt.matrixL();
      const double logDet = 2.0 * L.diagonal().array().log().sum();
      for (int i = 0; i < n; ++i) {
        const Eigen::Vector3d y = L.triangularView<Eigen::Lower>().solve(x[static_cast<std::size_t>(i)] - mu[static_cast<std::size_t>(k)]);
        logp(i, k) = std::log(w[static_cast<std::size_t>(k)]) - 0.5 * (3 * log2pi + logDet + y.squaredNorm());
      }
    }
  };
  mStep();
  double lowerBound = -std::numeric_limits<double>::infinity();
  for (int iter = 0; iter < 100; ++iter) {
    const double previous = lowerBound;
    weightedLogProb();
    double sum = 0.0;
    for (int i = 0; i < n; ++i) {
      const double mx = logp.row(i).maxCoeff();
      const double lse = mx + std::log((logp.row(i).array() - mx).exp().sum());
      sum += lse;
      for (int k = 0; k < K; ++k) resp(i, k) = std::exp(logp(i, k) - lse);
    }
    mStep();
    lowerBound = sum / n;
    if (std::abs(lowerBound - previous) < kTol) break;
  }
  weightedLogProb();
  for (int i = 0; i < n; ++i) {
    int best = 0;
    for (int k = 1; k < K; ++k)
      if (logp(i, k) > logp(i, best)) best = k;
    labels[static_cast<std::size_t>(i)] = best;
  }
  return labels;
}

}  // namespace

Segmentation Segmenter::segmentThesisPublished(const core::PositionTrajectory& hand,
                                               const std::vector<ObjectTrack>& objects,
                                               const std::vector<std::string>& planOrder) const {
  const int n = static_cast<int>(hand.size());
  Segmentation result;
  // The hand: the thesis writes 0,0,0 where no hand box is found and smooths
  // those zeros as measurements; so do we.
  std::vector<Eigen::Vector3d> zHand(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i)
    zHand[static_cast<std::size_t>(i)] = isDetected(hand[static_cast<std::size_t>(i)]) ? hand[static_cast<std::size_t>(i)].p_m
                                                                                       : Eigen::Vector3d::Zero();
  const auto handSmooth = pykalmanIdentitySmooth(zHand);
  result.hand = core::PositionTrajectory(hand.frame());
  for (int i = 0; i < n; ++i)
    result.hand.append({hand[static_cast<std::size_t>(i)].frame, hand[static_cast<std::size_t>(i)].t_s,
                        handSmooth[static_cast<std::size_t>(i)], true});
  result.firstHandIndex = 0;
  while (result.firstHandIndex < n - 1 && !isDetected(hand[static_cast<std::size_t>(result.firstHandIndex)])) ++result.firstHandIndex;
  result.lastHandIndex = n - 1;
  while (result.lastHandIndex > 0 && !isDetected(hand[static_cast<std::size_t>(result.lastHandIndex)])) --result.lastHandIndex;

  std::map<std::string, const ObjectTrack*> byName;
  for (const auto& o : objects) byName[o.name] = &o;
  int start = result.firstHandIndex;  // EnvModule.start: the first frame with a hand box
  for (const auto& name : planOrder) {
    const ObjectTrack& track = *byName.at(name);
    ObjectSegmentation seg;
    seg.name = name;
    seg.moved = true;  // the thesis segments every plan object
    seg.searchStartIndex = start;
    // The thesis' object tracks have no gaps (its boxes are forward-filled,
    // then back-filled); a track of ours may: the same fill on the positions.
    std::vector<Eigen::Vector3d> z(static_cast<std::size_t>(n));
    int firstDetected = -1;
    for (int i = 0; i < n && firstDetected < 0; ++i)
      if (isDetected(track.positions[static_cast<std::size_t>(i)])) firstDetected = i;
    core::require(firstDetected >= 0, "trajectory of '" + name + "' has no detection");
    for (int i = 0; i < n; ++i) {
      const auto& s = track.positions[static_cast<std::size_t>(i)];
      z[static_cast<std::size_t>(i)] = isDetected(s) ? s.p_m
                                       : i == 0 || i <= firstDetected
                                           ? track.positions[static_cast<std::size_t>(firstDetected)].p_m
                                           : z[static_cast<std::size_t>(i - 1)];
    }
    const auto smooth = pykalmanIdentitySmooth(z);
    seg.smoothed = core::PositionTrajectory(track.positions.frame());
    for (int i = 0; i < n; ++i)
      seg.smoothed.append({track.positions[static_cast<std::size_t>(i)].frame, track.positions[static_cast<std::size_t>(i)].t_s,
                           smooth[static_cast<std::size_t>(i)], true});
    const std::vector<int> labels = gaussianMixtureLabels(smooth, options_.thesisSeed);
    // segmentation.py: np.where(labels == labels[-1])[0][0].
    int release = 0;
    while (labels[static_cast<std::size_t>(release)] != labels.back()) ++release;
    // env_module.py seg(): initial position = mean of the smoothed track before start.
    Eigen::Vector3d initial = Eigen::Vector3d::Zero();
    for (int i = 0; i < std::max(start, 1); ++i) initial += smooth[static_cast<std::size_t>(i)];
    initial /= std::max(start, 1);
    seg.p_initial_m = initial;
    seg.p_final_m = smooth.back();
    int from = start;
    if (release <= start) {
      // The published code stops here (min() of an empty list); we search from the demo start.
      seg.note = "object '" + name + "': the mixture's final component starts at sample " + std::to_string(release) +
                 ", not after the search start " + std::to_string(start) +
                 " (the thesis' code fails here); grasp searched from the demo start";
      result.warnings.push_back(seg.note);
      from = 0;
    }
    int grasp = from;
    double best = std::numeric_limits<double>::infinity();
    for (int i = from; i < std::max(release, from + 1) && i < n; ++i) {
      const double d = (handSmooth[static_cast<std::size_t>(i)] - initial).norm();
      if (d < best) best = d, grasp = i;
    }
    for (const auto& p : smooth) seg.maxExcursion_m = std::max(seg.maxExcursion_m, (p - initial).norm());
    // Components renumbered by first appearance (for plots; the rule above does not depend on it).
    std::map<int, int> order;
    for (int l : labels)
      if (!order.count(l)) order.emplace(l, static_cast<int>(order.size()));
    for (int l : labels) seg.component.push_back(order[l]);
    seg.graspIndex = grasp;
    seg.releaseIndex = release;
    seg.graspFrame = hand[static_cast<std::size_t>(grasp)].frame;
    seg.releaseFrame = hand[static_cast<std::size_t>(release)].frame;
    seg.graspHandDistance_m = best;
    start = release;  // env_module.py: start = release_index (even if earlier)
    result.objects.push_back(std::move(seg));
  }
  return result;
}

}  // namespace srp::motion
