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
using core::kPi;

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

/// The model's random draws: one generator, uniform [0, 1) and standard normal.
struct Random {
  explicit Random(std::uint32_t seed) : rng(seed) {}
  std::mt19937 rng;
  std::uniform_real_distribution<double> uni{0.0, 1.0};
  std::normal_distribution<double> gauss{0.0, 1.0};
  double in(double lo, double hi) { return lo + (hi - lo) * uni(rng); }
};

/// A unit vector perpendicular to `axis` (random in that plane).
Eigen::Vector3d perpendicular(const Eigen::Vector3d& axis, std::mt19937& rng) {
  std::normal_distribution<double> g(0.0, 1.0);
  for (;;) {
    Eigen::Vector3d v(g(rng), g(rng), g(rng));
    v -= v.dot(axis) * axis;
    if (v.norm() > 1e-3) return v.normalized();
  }
}

double minimumJerk(double tau) {
  tau = std::clamp(tau, 0.0, 1.0);
  return tau * tau * tau * (10.0 - 15.0 * tau + 6.0 * tau * tau);
}

const Eigen::Vector3d& at(const core::PositionTrajectory& t, int i) { return t[static_cast<std::size_t>(i)].p_m; }

/// The clean demo's shape: sample count, frame rate, object index by name.
struct CleanDemo {
  const LabelledDemo& demo;
  int n = 0;
  double fps = 30.0;
  std::map<std::string, std::size_t> objectOf;
  int frames(double s) const { return static_cast<int>(std::lround(s * fps)); }
  std::size_t planObject(std::size_t k) const { return objectOf.at(demo.planOrder[k]); }
};

CleanDemo checkedDemo(const LabelledDemo& clean) {
  CleanDemo d{clean, 0, 30.0, {}};
  d.n = static_cast<int>(clean.hand.size());
  core::require(!clean.planOrder.empty(), "real-track noise: the demo has no plan object; give its moved objects");
  core::require(clean.graspIndex.size() == clean.planOrder.size() && clean.releaseIndex.size() == clean.planOrder.size(),
                "real-track noise: give one grasp and one release index per plan object");
  for (std::size_t o = 0; o < clean.objects.size(); ++o) {
    core::require(static_cast<int>(clean.objects[o].positions.size()) == d.n,
                  "real-track noise: the track of '" + clean.objects[o].name + "' has another length than the hand's");
    d.objectOf[clean.objects[o].name] = o;
  }
  for (std::size_t k = 0; k < clean.planOrder.size(); ++k) {
    if (!d.objectOf.count(clean.planOrder[k]))
      throw InvalidInputError("real-track noise: plan object '" + clean.planOrder[k] + "' has no track");
    core::require(clean.graspIndex[k] >= 0 && clean.graspIndex[k] < clean.releaseIndex[k] && clean.releaseIndex[k] < d.n,
                  "real-track noise: events of '" + clean.planOrder[k] + "' out of order or out of range");
  }
  if (d.n >= 2 && clean.hand[1].t_s > clean.hand[0].t_s) d.fps = 1.0 / (clean.hand[1].t_s - clean.hand[0].t_s);
  return d;
}

/// Frames the choreography inserts before one original sample.
struct Block {
  enum class Kind { Hover, Linger } kind = Kind::Linger;
  int before = 0;  ///< inserted before this original sample
  int anchor = 0;  ///< original sample whose state the block starts from
  int length = 0;
  std::size_t plan = 0;
  // Linger:
  int nudgeAt = -1;  ///< block-relative sample of the nudge, -1 none
  Eigen::Vector3d d_nudge = Eigen::Vector3d::Zero(), up = Eigen::Vector3d::UnitZ(), side1, side2;
  double lift_m = 0, sideways_m = 0, f1 = 0, f2 = 0, ph1 = 0, ph2 = 0;
  // Hover: `length` = hold + descent; the descent ends at the release pose `p_release`.
  int descent = 0;
  Eigen::Vector3d p_release = Eigen::Vector3d::Zero(), d_hover = Eigen::Vector3d::Zero();  ///< hover point - anchor's hand
};

/// The end of the hand's pause at the place after release r (the fingers
/// open): the first sample after r at which the hand has moved 3 mm.
int pauseEnd(const CleanDemo& d, int r) {
  int q = r + 1;
  while (q < d.n && d.demo.hand[static_cast<std::size_t>(q)].valid && (at(d.demo.hand, q) - at(d.demo.hand, r)).norm() < 0.003)
    ++q;
  return q;
}

/// After each release's pause: the hand lingers, hovering over the part, and may nudge it.
Block lingerBlock(const RealTrackNoise::Options& c, const CleanDemo& d, std::size_t k, int anchor, bool pauseKept,
                  Random& random) {
  auto& rng = random.rng;
  auto& uni = random.uni;
  const int r = d.demo.releaseIndex[k];
  const Eigen::Vector3d p_part = at(d.demo.objects[d.planObject(k)].positions, r);
  const int q = pauseEnd(d, r), pause = pauseKept ? q - r : 0;
  Block b;
  b.before = q;
  b.anchor = anchor;
  b.plan = k;
  b.length = std::max(0, d.frames(c.lingerMin_s + (c.lingerMax_s - c.lingerMin_s) * uni(rng)) - pause);
  if (uni(rng) < c.nudgeProbability) {
    b.nudgeAt = std::max(2, d.frames(c.nudgeMin_s + (c.nudgeMax_s - c.nudgeMin_s) * uni(rng)) - pause);
    b.length = std::max(b.length, b.nudgeAt + d.frames(0.4));
  }
  b.up = -p_part.normalized();  // towards the camera: away from the table
  b.side1 = perpendicular(b.up, rng);
  b.side2 = b.up.cross(b.side1);
  b.d_nudge = perpendicular(b.up, rng) * (c.nudgeMin_m + (c.nudgeMax_m - c.nudgeMin_m) * uni(rng));
  b.lift_m = c.lingerLift_m * (0.4 + 0.6 * uni(rng));
  b.sideways_m = c.lingerSideways_m * uni(rng);
  b.f1 = 0.3 + 0.5 * uni(rng), b.f2 = 0.3 + 0.5 * uni(rng);
  b.ph1 = 2 * kPi * uni(rng), b.ph2 = 2 * kPi * uni(rng);
  return b;
}

/// Before release r: the hand stops where the final approach is hoverOffset
/// from the release pose (sample s), holds there, then lowers the part to its
/// place; the original samples between s and r are replaced. Sets `removed`.
/// Returns a block of length 0 when the approach never gets that far away.
Block hoverBlock(const RealTrackNoise::Options& c, const CleanDemo& d, std::size_t k, Random& random,
                 std::vector<bool>& removed) {
  const int g = d.demo.graspIndex[k], r = d.demo.releaseIndex[k];
  const Eigen::Vector3d p_release = at(d.demo.hand, r);
  const double offset_m = random.in(c.hoverOffsetMin_m, c.hoverOffsetMax_m);
  int s = r - 1;
  while (s > g + 1 && (at(d.demo.hand, s) - p_release).norm() < offset_m) --s;
  Block b;
  b.kind = Block::Kind::Hover;
  b.plan = k;
  b.anchor = s;
  b.before = s + 1;
  b.p_release = p_release;
  // The hover point: offset from the release pose, between samples s and s + 1.
  const double ds = (at(d.demo.hand, s) - p_release).norm(), dn = (at(d.demo.hand, s + 1) - p_release).norm();
  const double w = ds > dn ? std::clamp((ds - offset_m) / (ds - dn), 0.0, 1.0) : 0.0;
  b.d_hover = w * (at(d.demo.hand, s + 1) - at(d.demo.hand, s));
  const int hold = d.frames(random.in(c.hoverMin_s, c.hoverMax_s));
  b.descent = std::max(2, d.frames(random.in(c.descentMin_s, c.descentMax_s)));
  b.f1 = 0.2 + 0.4 * random.uni(random.rng), b.f2 = 0.2 + 0.4 * random.uni(random.rng);
  b.ph1 = 2 * kPi * random.uni(random.rng), b.ph2 = 2 * kPi * random.uni(random.rng);
  b.side1 = perpendicular(Eigen::Vector3d::UnitZ(), random.rng);
  b.side2 = Eigen::Vector3d::UnitZ().cross(b.side1);
  if (s <= g + 1) return b;  // no room: no hover
  b.length = hold + b.descent;
  for (int i = s + 1; i < r; ++i) removed[static_cast<std::size_t>(i)] = true;
  return b;
}

/// Step 1: where the choreography inserts (hover before the release, lingering
/// after it) and removes samples (the pause after the release, when the hand
/// leaves at once).
std::vector<Block> planChoreography(const RealTrackNoise::Options& c, const CleanDemo& d, Random& random,
                                    Random& placement, std::vector<bool>& removed) {
  std::vector<Block> blocks;
  for (std::size_t k = 0; k < d.demo.planOrder.size(); ++k) {
    const int r = d.demo.releaseIndex[k];
    int anchor = std::max(0, pauseEnd(d, r) - 1);  // the hand's (and the parts') state at the end of the pause
    bool pauseKept = true;
    if (c.placement) {
      const Block hover = hoverBlock(c, d, k, placement, removed);
      if (hover.length > 0) blocks.push_back(hover);
      if (placement.uni(placement.rng) >= c.releasePauseProbability) {
        for (int i = r + 1; i < pauseEnd(d, r); ++i) removed[static_cast<std::size_t>(i)] = true;
        anchor = r;
        pauseKept = false;
      }
    }
    blocks.push_back(lingerBlock(c, d, k, anchor, pauseKept, random));
  }
  std::stable_sort(blocks.begin(), blocks.end(), [](const Block& a, const Block& b) { return a.before < b.before; });
  return blocks;
}

/// Step 2: the noise-free demo with the blocks inserted and the removed samples left out.
class Choreographer {
 public:
  Choreographer(const RealTrackNoise::Options& c, const CleanDemo& d, RealTrackNoise::Result& out)
      : c_(c), d_(d), out_(out), offset_(d.demo.objects.size(), Eigen::Vector3d::Zero()) {
    LabelledDemo& truth = out.truth;
    truth.planOrder = d.demo.planOrder;
    truth.hand = core::PositionTrajectory(d.demo.hand.frame());
    truth.objects.resize(d.demo.objects.size());
    for (std::size_t o = 0; o < d.demo.objects.size(); ++o) {
      truth.objects[o].name = d.demo.objects[o].name;
      truth.objects[o].positions = core::PositionTrajectory(d.demo.objects[o].positions.frame());
    }
    const std::size_t plans = d.demo.planOrder.size();
    out.nudgeIndex.assign(plans, -1);
    out.departIndex.assign(plans, -1);
    out.hoverStartIndex.assign(plans, -1);
    out.hoverEndIndex.assign(plans, -1);
  }

  void run(const std::vector<Block>& blocks, const std::vector<bool>& removed) {
    std::vector<int> newIndex(static_cast<std::size_t>(d_.n), 0);
    std::size_t nextBlock = 0;
    const auto& hand = d_.demo.hand;
    for (int i = 0; i < d_.n; ++i) {
      while (nextBlock < blocks.size() && blocks[nextBlock].before == i) {
        const Block& b = blocks[nextBlock++];
        if (b.kind == Block::Kind::Hover) hover(b);
        else linger(b);
      }
      newIndex[static_cast<std::size_t>(i)] = static_cast<int>(out_.truth.hand.size());
      if (removed[static_cast<std::size_t>(i)]) continue;
      emit(at(hand, i), hand[static_cast<std::size_t>(i)].valid && !(at(hand, i).array() == 0.0).all(), i);
    }
    for (std::size_t k = 0; k < d_.demo.planOrder.size(); ++k) {
      out_.truth.graspIndex.push_back(newIndex[static_cast<std::size_t>(d_.demo.graspIndex[k])]);
      out_.truth.releaseIndex.push_back(newIndex[static_cast<std::size_t>(d_.demo.releaseIndex[k])]);
    }
    // The parts never change while the hand is away, so the truth at a block
    // sample is exact; the truth of the nudged part includes its shift.
  }

 private:
  double yawAt(std::size_t o, int i) const {
    const auto& y = d_.demo.objects[o].yaw_rad;
    return y.empty() ? 0.0 : y[static_cast<std::size_t>(i)];
  }

  /// One sample: the hand, every part as at original sample `from` (plus its
  /// nudges; the part `carried` displaced by `d_carried`).
  void emit(const Eigen::Vector3d& p_hand, bool handValid, int from, std::size_t carried = SIZE_MAX,
            const Eigen::Vector3d& d_carried = Eigen::Vector3d::Zero()) {
    LabelledDemo& truth = out_.truth;
    const double fps = d_.fps;
    const int f = static_cast<int>(truth.hand.size());
    truth.hand.append({f, f / fps, handValid ? p_hand : Eigen::Vector3d::Zero(), handValid});
    for (std::size_t o = 0; o < d_.demo.objects.size(); ++o) {
      const Eigen::Vector3d shift = o == carried ? d_carried : Eigen::Vector3d::Zero();
      truth.objects[o].positions.append({f, f / fps, at(d_.demo.objects[o].positions, from) + offset_[o] + shift, true});
      truth.objects[o].yaw_rad.push_back(yawAt(o, from));
    }
  }

  void linger(const Block& b) {
    const double fps = d_.fps;
    const std::size_t o = d_.planObject(b.plan);
    const Eigen::Vector3d P = at(d_.demo.hand, b.anchor);
    const Eigen::Vector3d offset0 = offset_[o];
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
        offset_[o] = offset0 + push;
        if (j == b.nudgeAt) out_.nudgeIndex[b.plan] = static_cast<int>(out_.truth.hand.size());
      }
      emit(P + hover + push, true, b.anchor);
    }
    out_.departIndex[b.plan] = static_cast<int>(out_.truth.hand.size()) - 1;
    if (b.nudgeAt >= 0) offset_[o] = offset0 + b.d_nudge;
  }

  /// Hold near the hover point (slow wandering that starts and ends at it),
  /// then a minimum-jerk descent to the release pose; the part moves with the hand.
  void hover(const Block& b) {
    const double fps = d_.fps;
    const std::size_t o = d_.planObject(b.plan);
    const Eigen::Vector3d P = at(d_.demo.hand, b.anchor) + b.d_hover;
    const int hold = b.length - b.descent;
    out_.hoverStartIndex[b.plan] = static_cast<int>(out_.truth.hand.size());
    for (int j = 0; j < hold; ++j) {
      const double s = (j + 1.0) / (hold + 1.0), t = j / fps;
      const Eigen::Vector3d wander = std::sin(kPi * s) * c_.hoverWander_m *
                                     (std::sin(2 * kPi * b.f1 * t + b.ph1) * b.side1 + std::sin(2 * kPi * b.f2 * t + b.ph2) * b.side2);
      emit(P + wander, true, b.anchor, o, b.d_hover + wander);
    }
    out_.hoverEndIndex[b.plan] = static_cast<int>(out_.truth.hand.size()) - 1;
    for (int j = 1; j <= b.descent; ++j) {
      const Eigen::Vector3d d = minimumJerk(static_cast<double>(j) / (b.descent + 1)) * (b.p_release - P);
      emit(P + d, true, b.anchor, o, b.d_hover + d);
    }
  }

  const RealTrackNoise::Options& c_;
  const CleanDemo& d_;
  RealTrackNoise::Result& out_;
  std::vector<Eigen::Vector3d> offset_;  ///< nudges so far, per object
};

/// Step 3: the hand detector: Gaussian noise, jumps of 1-2 frames, missed
/// frames carried forward.
core::PositionTrajectory noisyHand(const RealTrackNoise::Options& c, const core::PositionTrajectory& truth, Random& random) {
  auto& rng = random.rng;
  auto& uni = random.uni;
  auto& gauss = random.gauss;
  core::PositionTrajectory out(truth.frame());
  Eigen::Vector3d last = Eigen::Vector3d::Zero();
  bool haveLast = false;
  int jumpLeft = 0;
  bool jumpedLast = false;
  Eigen::Vector3d jump = Eigen::Vector3d::Zero();
  for (const auto& h : truth.samples()) {
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
    out.append(s);
  }
  return out;
}

/// Where the placement behaviours replace a part's detections (truth indices).
struct PlacementPlan {
  std::vector<std::uint8_t> effect;  ///< per sample: 0 none, 1 hidden, 2 ghost candidate
  int ghost = -1;                    ///< object index of the ghost, -1 none
  double ghostFraction = 0.0;
};

/// Hidden spans around a plan part's grasp and placement, and its ghost.
PlacementPlan planPlacement(const RealTrackNoise::Options& c, const CleanDemo& d, const RealTrackNoise::Result& r,
                            std::size_t k, Random& random) {
  const LabelledDemo& truth = r.truth;
  const int m = static_cast<int>(truth.hand.size());
  PlacementPlan p;
  p.effect.assign(static_cast<std::size_t>(m), 0);
  auto mark = [&](int from, int to, std::uint8_t what) {
    for (int i = std::max(0, from); i <= std::min(m - 1, to); ++i)
      if (p.effect[static_cast<std::size_t>(i)] == 0) p.effect[static_cast<std::size_t>(i)] = what;
  };
  const int g = truth.graspIndex[k], rel = truth.releaseIndex[k];
  mark(g - d.frames(random.in(c.hiddenBeforeGraspMin_s, c.hiddenBeforeGraspMax_s)),
       g + d.frames(random.in(c.hiddenAfterGraspMin_s, c.hiddenAfterGraspMax_s)), 1);
  // The hand leaves: it starts to move (5 mm from its release pose), then is hiddenClear away.
  auto awayFrom = [&](int i, double dist_m) {
    return !truth.hand[static_cast<std::size_t>(i)].valid || (at(truth.hand, i) - at(truth.hand, rel)).norm() >= dist_m;
  };
  int depart = rel, clear = rel;
  while (depart + 1 < m && !awayFrom(depart + 1, 0.005)) ++depart;
  while (clear + 1 < m && !awayFrom(clear + 1, c.hiddenClear_m)) ++clear;
  const int hoverStart = r.hoverStartIndex[k] >= 0 ? r.hoverStartIndex[k] : rel;
  mark(hoverStart, std::min(clear, depart + d.frames(random.in(c.hiddenAfterLeaveMin_s, c.hiddenAfterLeaveMax_s))), 1);
  if (k > 0 && random.uni(random.rng) < c.ghostProbability) {
    p.ghost = static_cast<int>(d.planObject(k - 1));
    p.ghostFraction = random.in(c.ghostFractionMin, c.ghostFractionMax);
    mark(truth.releaseIndex[k - 1] + 1, m - 1, 2);
  }
  return p;
}

/// The closest other plan part to `p` at sample i (SIZE_MAX when there is none).
std::size_t nearestOtherPart(const CleanDemo& d, const LabelledDemo& truth, std::size_t o, int i) {
  std::size_t best = SIZE_MAX;
  double bestDist = std::numeric_limits<double>::infinity();
  const Eigen::Vector3d& p = at(truth.objects[o].positions, i);
  for (std::size_t k = 0; k < d.demo.planOrder.size(); ++k) {
    const std::size_t q = d.planObject(k);
    if (q == o) continue;
    const double dist = (at(truth.objects[q].positions, i) - p).norm();
    if (dist < bestDist) bestDist = dist, best = q;
  }
  return best;
}

/// Step 4b: the placement behaviours on one part's detections: hidden spans
/// (episodes of nothing / another part / the hand) and ghost episodes.
void applyPlacement(const RealTrackNoise::Options& c, const CleanDemo& d, const PlacementPlan& p, std::size_t o,
                    RealTrackNoise::Result& r, Random& random) {
  auto& rng = random.rng;
  auto& uni = random.uni;
  auto& gauss = random.gauss;
  const LabelledDemo& truth = r.truth;
  ObjectTrack& t = r.noisy.objects[o];
  auto& effect = r.placementEffect[o];
  const int m = static_cast<int>(truth.hand.size());
  const double ghostStart = p.ghostFraction / (c.outlierEpisodeMean_frames * (1.0 - p.ghostFraction));
  int left = 0, kind = 0;  // 0 nothing, 1 another part, 2 the hand, 3 ghost
  for (int i = 0; i < m; ++i) {
    const auto ui = static_cast<std::size_t>(i);
    const Eigen::Vector3d noise(c.partNoiseXY_m * gauss(rng), c.partNoiseXY_m * gauss(rng), c.partNoiseZ_m * gauss(rng));
    if (p.effect[ui] == 0 || (p.effect[ui] == 2 && p.ghost < 0)) {
      left = 0;
      continue;
    }
    if (left == 0 && p.effect[ui] == 1) {
      left = 1 + static_cast<int>(uni(rng) * c.hiddenEpisodeMax_frames);
      const double u = uni(rng);
      kind = u < c.hiddenNothing ? 0 : u < c.hiddenNothing + c.hiddenOtherPart ? 1 : 2;
    } else if (left == 0 && uni(rng) < ghostStart) {
      left = 1 + static_cast<int>(uni(rng) * (2.0 * c.outlierEpisodeMean_frames - 1.0));
      kind = 3;
    }
    if (left == 0) continue;
    --left;
    auto& s = t.positions.samples()[ui];
    const auto& h = truth.hand[ui];
    std::size_t other = kind == 3 ? static_cast<std::size_t>(p.ghost) : SIZE_MAX;
    if (kind == 1) other = p.ghost >= 0 ? static_cast<std::size_t>(p.ghost) : nearestOtherPart(d, truth, o, i);
    if (kind == 0 || (kind == 2 && !h.valid) || (kind == 1 && other == SIZE_MAX)) {
      s.p_m.setZero();
      s.valid = false;
    } else if (kind == 2) {
      s.p_m = h.p_m + 3.0 * noise;
    } else {
      s.p_m = at(truth.objects[other].positions, i) + noise;
    }
    effect[ui] = kind == 3 ? 2 : 1;
  }
}

/// Step 4a: one part's detector: sub-mm scatter, outlier episodes (wrong
/// depth, or on the hand while it is near), missed detections that keep the
/// last pixel and read the depth there now.
ObjectTrack noisyPart(const RealTrackNoise::Options& c, const LabelledDemo& truth, const std::vector<int>& carriedPlan,
                      std::size_t o, Random& random) {
  auto& rng = random.rng;
  auto& uni = random.uni;
  auto& gauss = random.gauss;
  const int m = static_cast<int>(truth.hand.size());
  auto handAt = [&](int i) -> const core::PositionSample& { return truth.hand[static_cast<std::size_t>(i)]; };
  // The hand covers a pixel (ray through p) when it is in front of p and within
  // occlusionRadius of the ray at p's depth.
  auto covers = [&](int i, const Eigen::Vector3d& p) {
    const auto& h = handAt(i);
    if (!h.valid || p.z() <= 0 || h.p_m.z() <= 0 || h.p_m.z() >= p.z() + 0.01) return false;
    return (h.p_m.head<2>() / h.p_m.z() - p.head<2>() / p.z()).norm() * p.z() < c.occlusionRadius_m;
  };
  ObjectTrack t;
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
  return t;
}

/// The placement behaviours' figures (RealTrackNoise::Statistics).
void measurePlacement(const RealTrackNoise::Result& r, double frameRate_hz, RealTrackNoise::Statistics& s) {
  const LabelledDemo& truth = r.truth;
  const int m = static_cast<int>(truth.hand.size());
  std::map<std::string, std::size_t> objectOf;
  for (std::size_t o = 0; o < truth.objects.size(); ++o) objectOf[truth.objects[o].name] = o;
  int nothing = 0, other = 0, hand = 0, hidden = 0;
  for (std::size_t k = 0; k < truth.planOrder.size(); ++k) {
    const std::size_t o = objectOf.at(truth.planOrder[k]);
    if (o >= r.placementEffect.size()) continue;
    const auto& effect = r.placementEffect[o];
    const int rel = truth.releaseIndex[k];
    if (r.hoverStartIndex[k] >= 0) {
      s.hover_s.push_back((r.hoverEndIndex[k] - r.hoverStartIndex[k] + 1) / frameRate_hz);
      double spread = 0.0;
      for (int i = r.hoverStartIndex[k]; i <= r.hoverEndIndex[k]; ++i)
        spread = std::max(spread, (at(truth.hand, i) - at(truth.hand, rel)).norm());
      s.hoverHandSpread_m.push_back(spread);
    }
    // The hidden span around an event: the run of hidden samples through it.
    auto spanAround = [&](int e) {
      int a = e, b = e;
      while (a > 0 && effect[static_cast<std::size_t>(a - 1)] != 0) --a;
      while (b + 1 < m && effect[static_cast<std::size_t>(b + 1)] != 0) ++b;
      return effect[static_cast<std::size_t>(e)] != 0 ? (b - a + 1) / frameRate_hz : 0.0;
    };
    s.hiddenGrasp_s.push_back(spanAround(truth.graspIndex[k]));
    s.hiddenRelease_s.push_back(spanAround(rel));
    int ghosts = 0;
    for (int i = 0; i < m; ++i) {
      const auto ui = static_cast<std::size_t>(i);
      ghosts += effect[ui] == 2;
      if (effect[ui] != 1) continue;
      ++hidden;
      const auto& det = r.noisy.objects[o].positions[ui];
      if (!det.valid) ++nothing;
      else if (truth.hand[ui].valid && (det.p_m - truth.hand[ui].p_m).norm() < 0.01) ++hand;
      else ++other;
    }
    if (r.ghostOf[k] >= 0) {
      const int from = truth.releaseIndex[static_cast<std::size_t>(r.ghostOf[k])] + 1;
      s.ghostFraction.push_back(static_cast<double>(ghosts) / std::max(1, m - from));
    }
  }
  if (hidden > 0) {
    s.hiddenNothingShare = static_cast<double>(nothing) / hidden;
    s.hiddenOtherShare = static_cast<double>(other) / hidden;
    s.hiddenHandShare = static_cast<double>(hand) / hidden;
  }
}

}  // namespace

RealTrackNoise::Result RealTrackNoise::apply(const LabelledDemo& clean) const {
  const auto& c = options_;
  const CleanDemo d = checkedDemo(clean);
  Random random(c.seed);
  // The placement behaviours draw from their own generator: off, the model is the first recording's, draw for draw.
  Random placement(c.seed * 2654435761u + 0x9e3779b9u);
  std::vector<bool> removed(static_cast<std::size_t>(d.n), false);
  const std::vector<Block> blocks = planChoreography(c, d, random, placement, removed);

  Result out;
  const std::size_t plans = clean.planOrder.size();
  Choreographer(c, d, out).run(blocks, removed);
  LabelledDemo& truth = out.truth;
  out.pauseKept.assign(plans, true);
  if (c.placement)
    for (std::size_t k = 0; k < plans; ++k)
      out.pauseKept[k] = !removed[static_cast<std::size_t>(std::min(d.n - 1, clean.releaseIndex[k] + 1))];

  LabelledDemo& noisy = out.noisy;
  noisy.planOrder = truth.planOrder;
  noisy.graspIndex = truth.graspIndex;
  noisy.releaseIndex = truth.releaseIndex;
  noisy.hand = noisyHand(c, truth.hand, random);
  // Which part is in the hand at each sample.
  const int m = static_cast<int>(truth.hand.size());
  std::vector<int> carriedPlan(static_cast<std::size_t>(m), -1);
  for (std::size_t k = 0; k < plans; ++k)
    for (int i = truth.graspIndex[k]; i <= truth.releaseIndex[k]; ++i) carriedPlan[static_cast<std::size_t>(i)] = static_cast<int>(k);
  for (std::size_t o = 0; o < truth.objects.size(); ++o) noisy.objects.push_back(noisyPart(c, truth, carriedPlan, o, random));
  out.ghostOf.assign(plans, -1);
  out.placementEffect.assign(truth.objects.size(), std::vector<std::uint8_t>(static_cast<std::size_t>(m), 0));
  if (c.placement)
    for (std::size_t k = 0; k < plans; ++k) {
      const PlacementPlan p = planPlacement(c, d, out, k, placement);
      if (p.ghost >= 0) out.ghostOf[k] = static_cast<int>(k) - 1;
      applyPlacement(c, d, p, d.planObject(k), out, placement);
    }
  return out;
}

RealTrackNoise::Statistics RealTrackNoise::measure(const Result& r, double frameRate_hz) {
  Statistics s;
  const int m = static_cast<int>(r.truth.hand.size());
  std::vector<double> scatter, outliers, steps;
  int onHand = 0;
  auto affected = [&](std::size_t o, int i) {
    return o < r.placementEffect.size() && r.placementEffect[o][static_cast<std::size_t>(i)] != 0;
  };
  for (std::size_t o = 0; o < r.truth.objects.size(); ++o) {
    const auto& truth = r.truth.objects[o].positions;
    const auto& det = r.noisy.objects[o].positions;
    int rest = 0, out = 0;
    for (int i = 0; i < m; ++i) {
      const auto ui = static_cast<std::size_t>(i);
      if (affected(o, i)) continue;  // measured below
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
  measurePlacement(r, frameRate_hz, s);
  return s;
}

}  // namespace srp::motion
