#include "srp/motion/RealTrackNoise.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <map>
#include <random>

#include "srp/core/Angles.h"
#include "srp/core/Error.h"

namespace srp::motion {
namespace {

using core::InvalidInputError;

double medianOf(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
  return v[v.size() / 2];
}

double quantileOf(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<std::size_t>(q * static_cast<double>(v.size())))];
}

/// A unit vector perpendicular to `axis` (random in that plane).
Eigen::Vector3d perpendicular(const Eigen::Vector3d& axis, std::mt19937& rng) {
  std::normal_distribution<double> g(0.0, 1.0);
  for (;;) {
    Eigen::Vector3d v(g(rng), g(rng), g(rng));
    v -= v.dot(axis) * axis;
    if (v.norm() > 1e-3) return v.normalized();
  }
}

}  // namespace

RealTrackNoise::Result RealTrackNoise::apply(const LabelledDemo& clean) const {
  const auto& c = config_;
  const int n = static_cast<int>(clean.hand.size());
  core::require(!clean.planOrder.empty(), "real-track noise: the demo has no plan object; give its moved objects");
  core::require(clean.graspIndex.size() == clean.planOrder.size() && clean.releaseIndex.size() == clean.planOrder.size(),
                "real-track noise: give one grasp and one release index per plan object");
  std::map<std::string, std::size_t> objectOf;
  for (std::size_t o = 0; o < clean.objects.size(); ++o) {
    core::require(static_cast<int>(clean.objects[o].positions.size()) == n,
                  "real-track noise: the track of '" + clean.objects[o].name + "' has another length than the hand's");
    objectOf[clean.objects[o].name] = o;
  }
  for (std::size_t k = 0; k < clean.planOrder.size(); ++k) {
    if (!objectOf.count(clean.planOrder[k]))
      throw InvalidInputError("real-track noise: plan object '" + clean.planOrder[k] + "' has no track");
    core::require(clean.graspIndex[k] >= 0 && clean.graspIndex[k] < clean.releaseIndex[k] && clean.releaseIndex[k] < n,
                  "real-track noise: events of '" + clean.planOrder[k] + "' out of order or out of range");
  }
  double fps = 30.0;
  if (n >= 2 && clean.hand[1].t_s > clean.hand[0].t_s) fps = 1.0 / (clean.hand[1].t_s - clean.hand[0].t_s);
  const auto frames = [&](double s) { return static_cast<int>(std::lround(s * fps)); };

  std::mt19937 rng(c.seed);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  std::normal_distribution<double> gauss(0.0, 1.0);
  using core::kPi;

  // ---- 1. Choreography: a lingering block after each release's pause --------
  struct Block {
    int before = 0;  ///< inserted before this original sample
    int length = 0;
    std::size_t plan = 0;
    int nudgeAt = -1;  ///< block-relative sample of the nudge, -1 none
    Eigen::Vector3d d_nudge = Eigen::Vector3d::Zero(), up = Eigen::Vector3d::UnitZ(), side1, side2;
    double lift_m = 0, sideways_m = 0, f1 = 0, f2 = 0, ph1 = 0, ph2 = 0;
  };
  std::vector<Block> blocks;
  for (std::size_t k = 0; k < clean.planOrder.size(); ++k) {
    const int r = clean.releaseIndex[k];
    const Eigen::Vector3d p_part = clean.objects[objectOf[clean.planOrder[k]]].positions[static_cast<std::size_t>(r)].p_m;
    int q = r + 1;  // end of the hand's pause at the place (the fingers open)
    while (q < n && clean.hand[static_cast<std::size_t>(q)].valid &&
           (clean.hand[static_cast<std::size_t>(q)].p_m - clean.hand[static_cast<std::size_t>(r)].p_m).norm() < 0.003)
      ++q;
    Block b;
    b.before = q;
    b.plan = k;
    b.length = std::max(0, frames(c.lingerMin_s + (c.lingerMax_s - c.lingerMin_s) * uni(rng)) - (q - r));
    if (uni(rng) < c.nudgeProbability) {
      b.nudgeAt = std::max(2, frames(c.nudgeMin_s + (c.nudgeMax_s - c.nudgeMin_s) * uni(rng)) - (q - r));
      b.length = std::max(b.length, b.nudgeAt + frames(0.4));
    }
    b.up = -p_part.normalized();  // towards the camera: away from the table
    b.side1 = perpendicular(b.up, rng);
    b.side2 = b.up.cross(b.side1);
    b.d_nudge = perpendicular(b.up, rng) * (c.nudgeMin_m + (c.nudgeMax_m - c.nudgeMin_m) * uni(rng));
    b.lift_m = c.lingerLift_m * (0.4 + 0.6 * uni(rng));
    b.sideways_m = c.lingerSideways_m * uni(rng);
    b.f1 = 0.3 + 0.5 * uni(rng), b.f2 = 0.3 + 0.5 * uni(rng);
    b.ph1 = 2 * kPi * uni(rng), b.ph2 = 2 * kPi * uni(rng);
    blocks.push_back(b);
  }
  std::sort(blocks.begin(), blocks.end(), [](const Block& a, const Block& b) { return a.before < b.before; });

  Result out;
  LabelledDemo& truth = out.truth;
  truth.planOrder = clean.planOrder;
  truth.hand = core::PositionTrajectory(clean.hand.frame());
  truth.objects.resize(clean.objects.size());
  for (std::size_t o = 0; o < clean.objects.size(); ++o) {
    truth.objects[o].name = clean.objects[o].name;
    truth.objects[o].positions = core::PositionTrajectory(clean.objects[o].positions.frame());
  }
  out.nudgeIndex.assign(clean.planOrder.size(), -1);
  out.departIndex.assign(clean.planOrder.size(), -1);
  std::vector<int> newIndex(static_cast<std::size_t>(n), 0);
  std::vector<Eigen::Vector3d> offset(clean.objects.size(), Eigen::Vector3d::Zero());  // nudges so far
  auto yawAt = [&](std::size_t o, int i) {
    const auto& y = clean.objects[o].yaw_rad;
    return y.empty() ? 0.0 : y[static_cast<std::size_t>(i)];
  };
  auto emit = [&](const Eigen::Vector3d& p_hand, bool handValid, int from) {
    const int f = static_cast<int>(truth.hand.size());
    truth.hand.append({f, f / fps, handValid ? p_hand : Eigen::Vector3d::Zero(), handValid});
    for (std::size_t o = 0; o < clean.objects.size(); ++o) {
      truth.objects[o].positions.append(
          {f, f / fps, clean.objects[o].positions[static_cast<std::size_t>(from)].p_m + offset[o], true});
      truth.objects[o].yaw_rad.push_back(yawAt(o, from));
    }
  };
  std::size_t nextBlock = 0;
  for (int i = 0; i < n; ++i) {
    while (nextBlock < blocks.size() && blocks[nextBlock].before == i) {
      const Block& b = blocks[nextBlock++];
      const std::size_t o = objectOf[clean.planOrder[b.plan]];
      const int anchor = std::max(0, i - 1);  // the hand's (and the parts') state at the end of the pause
      const Eigen::Vector3d P = clean.hand[static_cast<std::size_t>(anchor)].p_m;
      const Eigen::Vector3d offset0 = offset[o];
      for (int j = 0; j < b.length; ++j) {
        const double s = (j + 1.0) / (b.length + 1.0), bump = std::sin(kPi * s), t = j / fps;
        Eigen::Vector3d hover = bump * (b.lift_m * b.up + b.sideways_m * (std::sin(2 * kPi * b.f1 * t + b.ph1) * b.side1 +
                                                                            std::sin(2 * kPi * b.f2 * t + b.ph2) * b.side2));
        Eigen::Vector3d push = Eigen::Vector3d::Zero();
        if (b.nudgeAt >= 0) {
          // The hand comes down onto the part and shifts it within 4 frames.
          const double w = std::exp(-0.5 * std::pow((j - b.nudgeAt) / 4.0, 2));
          const double progress = std::clamp((j - b.nudgeAt + 2) / 4.0, 0.0, 1.0);
          hover *= 1.0 - w;
          push = progress * b.d_nudge;
          offset[o] = offset0 + push;
          if (j == b.nudgeAt) out.nudgeIndex[b.plan] = static_cast<int>(truth.hand.size());
        }
        emit(P + hover + push, true, anchor);
      }
      out.departIndex[b.plan] = static_cast<int>(truth.hand.size()) - 1;
      if (b.nudgeAt >= 0) offset[o] = offset0 + b.d_nudge;
    }
    newIndex[static_cast<std::size_t>(i)] = static_cast<int>(truth.hand.size());
    emit(clean.hand[static_cast<std::size_t>(i)].p_m, clean.hand[static_cast<std::size_t>(i)].valid &&
                                                          !(clean.hand[static_cast<std::size_t>(i)].p_m.array() == 0.0).all(),
         i);
  }
  for (std::size_t k = 0; k < clean.planOrder.size(); ++k) {
    truth.graspIndex.push_back(newIndex[static_cast<std::size_t>(clean.graspIndex[k])]);
    truth.releaseIndex.push_back(newIndex[static_cast<std::size_t>(clean.releaseIndex[k])]);
  }
  // The parts never change while the hand is away, so the truth at a block
  // sample is exact; the truth of the nudged part includes its shift.

  // ---- 2. Sensor ------------------------------------------------------------
  const int m = static_cast<int>(truth.hand.size());
  LabelledDemo& noisy = out.noisy;
  noisy.planOrder = truth.planOrder;
  noisy.graspIndex = truth.graspIndex;
  noisy.releaseIndex = truth.releaseIndex;
  noisy.hand = core::PositionTrajectory(truth.hand.frame());
  auto handAt = [&](int i) -> const core::PositionSample& { return truth.hand[static_cast<std::size_t>(i)]; };
  // The hand covers a pixel (ray through p) when it is in front of p and within
  // occlusionRadius of the ray at p's depth.
  auto covers = [&](int i, const Eigen::Vector3d& p) {
    const auto& h = handAt(i);
    if (!h.valid || p.z() <= 0 || h.p_m.z() <= 0 || h.p_m.z() >= p.z() + 0.01) return false;
    return (h.p_m.head<2>() / h.p_m.z() - p.head<2>() / p.z()).norm() * p.z() < c.occlusionRadius_m;
  };
  {
    Eigen::Vector3d last = Eigen::Vector3d::Zero();
    bool haveLast = false;
    int jumpLeft = 0;
    bool jumpedLast = false;
    Eigen::Vector3d jump = Eigen::Vector3d::Zero();
    for (int i = 0; i < m; ++i) {
      const auto& h = handAt(i);
      core::PositionSample s{h.frame, h.t_s, Eigen::Vector3d::Zero(), false};
      if (h.valid) {
        const Eigen::Vector3d noise(c.handNoiseXY_m * gauss(rng), c.handNoiseXY_m * gauss(rng), c.handNoiseZ_m * gauss(rng));
        if (jumpLeft == 0 && !jumpedLast && uni(rng) < c.handJumpRate) {
          jumpLeft = uni(rng) < 0.8 ? 1 : 2;
          Eigen::Vector3d dir = uni(rng) < 0.5 ? Eigen::Vector3d(h.p_m.normalized()) : perpendicular(h.p_m.normalized(), rng);
          if (uni(rng) < 0.5) dir = -dir;
          jump = dir * (c.handJumpMin_m + (c.handJumpMax_m - c.handJumpMin_m) * uni(rng));
        }
        jumpedLast = jumpLeft > 0;  // a jump ends at the true hand: no new jump right after it
        if (jumpLeft > 0) {
          --jumpLeft;
          s.p_m = h.p_m + jump + noise;
        } else if (haveLast && uni(rng) < c.handMiss) {
          s.p_m = last;
        } else {
          s.p_m = h.p_m + noise;
        }
        s.valid = true;
        last = s.p_m;
        haveLast = true;
      }
      noisy.hand.append(s);
    }
  }
  // Which part is in the hand at each sample.
  std::vector<int> carriedPlan(static_cast<std::size_t>(m), -1);
  for (std::size_t k = 0; k < truth.planOrder.size(); ++k)
    for (int i = truth.graspIndex[k]; i <= truth.releaseIndex[k]; ++i) carriedPlan[static_cast<std::size_t>(i)] = static_cast<int>(k);
  noisy.objects.resize(truth.objects.size());
  for (std::size_t o = 0; o < truth.objects.size(); ++o) {
    ObjectTrack& t = noisy.objects[o];
    t.name = truth.objects[o].name;
    t.positions = core::PositionTrajectory(truth.objects[o].positions.frame());
    int plan = -1;
    for (std::size_t k = 0; k < truth.planOrder.size(); ++k)
      if (truth.planOrder[k] == t.name) plan = static_cast<int>(k);
    const double rho = c.outlierFractionMin + (c.outlierFractionMax - c.outlierFractionMin) * uni(rng);
    const double startRate = rho / (c.outlierEpisodeMean_frames * (1.0 - rho));
    int episodeLeft = 0;
    bool onHand = false;
    double depthError_m = 0.0;
    Eigen::Vector3d last = Eigen::Vector3d::Zero();
    for (int i = 0; i < m; ++i) {
      const Eigen::Vector3d p = truth.objects[o].positions[static_cast<std::size_t>(i)].p_m;
      const auto& h = handAt(i);
      const bool near = h.valid && (h.p_m - p).norm() < c.handNear_m;
      const bool carried = plan >= 0 && carriedPlan[static_cast<std::size_t>(i)] == plan;
      const Eigen::Vector3d noise(c.partNoiseXY_m * gauss(rng), c.partNoiseXY_m * gauss(rng), c.partNoiseZ_m * gauss(rng));
      if (episodeLeft == 0 && i > 0 && uni(rng) < startRate * (near ? c.nearHandRateFactor : 1.0)) {
        episodeLeft = 1 + static_cast<int>(uni(rng) * (2.0 * c.outlierEpisodeMean_frames - 1.0));
        onHand = near && uni(rng) < c.onHandProbability;
        depthError_m = (c.wrongDepthMin_m + (c.wrongDepthMax_m - c.wrongDepthMin_m) * uni(rng)) * (uni(rng) < 0.5 ? -1 : 1);
        if (p.z() + depthError_m < 0.25) depthError_m = -depthError_m;
      }
      Eigen::Vector3d value;
      if (episodeLeft > 0) {
        --episodeLeft;
        value = onHand ? Eigen::Vector3d(h.p_m + 3.0 * noise) : Eigen::Vector3d(p * ((p.z() + depthError_m) / p.z()) + noise);
      } else if (i > 0 && uni(rng) < (carried || covers(i, p) ? c.partMissCovered : c.partMissFree)) {
        // Not detected: the last pixel, the depth there now.
        const double depth_m = covers(i, last) ? h.p_m.z() + c.handNoiseZ_m * gauss(rng) : last.z() + c.partNoiseZ_m * gauss(rng);
        value = last * (depth_m / last.z());
      } else {
        value = p + noise;
      }
      last = value;
      t.positions.append({truth.hand[static_cast<std::size_t>(i)].frame, truth.hand[static_cast<std::size_t>(i)].t_s, value, true});
      t.yaw_rad.push_back(truth.objects[o].yaw_rad[static_cast<std::size_t>(i)] + 0.02 * gauss(rng));
    }
  }
  return out;
}

RealTrackNoise::Statistics RealTrackNoise::measure(const Result& r, double frameRate_hz) {
  Statistics s;
  const int m = static_cast<int>(r.truth.hand.size());
  std::vector<double> scatter, outliers, steps;
  int onHand = 0;
  for (std::size_t o = 0; o < r.truth.objects.size(); ++o) {
    const auto& truth = r.truth.objects[o].positions;
    const auto& det = r.noisy.objects[o].positions;
    int rest = 0, out = 0;
    for (int i = 0; i < m; ++i) {
      const auto ui = static_cast<std::size_t>(i);
      if (!det[ui].valid) ++s.notDetectedPartSamples;
      const bool atRest = (i == 0 || (truth[ui].p_m - truth[ui - 1].p_m).norm() < 1e-9) &&
                          (i == m - 1 || (truth[ui].p_m - truth[ui + 1].p_m).norm() < 1e-9);
      if (!atRest) continue;
      ++rest;
      const double e = (det[ui].p_m - truth[ui].p_m).norm();
      if (e <= 0.05) {
        scatter.push_back(e);
        continue;
      }
      ++out;
      outliers.push_back(e);
      const auto& h = r.truth.hand[ui];
      if (h.valid && (det[ui].p_m - h.p_m).norm() < 0.05) ++onHand;
    }
    s.partOutlierFraction.push_back(rest > 0 ? static_cast<double>(out) / rest : 0.0);
  }
  s.partRestScatterMedian_m = medianOf(scatter);
  if (!outliers.empty()) {
    s.outlierMin_m = *std::min_element(outliers.begin(), outliers.end());
    s.outlierMax_m = *std::max_element(outliers.begin(), outliers.end());
    s.onHandOutlierShare = static_cast<double>(onHand) / static_cast<double>(outliers.size());
  }
  for (int i = 1; i < m; ++i) {
    const auto& a = r.noisy.hand[static_cast<std::size_t>(i - 1)];
    const auto& b = r.noisy.hand[static_cast<std::size_t>(i)];
    if (a.valid && b.valid) steps.push_back((b.p_m - a.p_m).norm());
  }
  s.handStepMedian_m = medianOf(steps);
  s.handStepP95_m = quantileOf(steps, 0.95);
  s.handStepMax_m = steps.empty() ? 0.0 : *std::max_element(steps.begin(), steps.end());
  for (std::size_t k = 0; k < r.truth.planOrder.size(); ++k) {
    s.linger_s.push_back((r.departIndex[k] - r.truth.releaseIndex[k]) / frameRate_hz);
    if (r.nudgeIndex[k] >= 0) s.nudgeAfter_s.push_back((r.nudgeIndex[k] - r.truth.releaseIndex[k]) / frameRate_hz);
    s.carry_s.push_back((r.truth.releaseIndex[k] - r.truth.graspIndex[k]) / frameRate_hz);
  }
  return s;
}

}  // namespace srp::motion
