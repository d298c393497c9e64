#include "srp/motion/SyntheticPickPlace.h"

#include <cmath>
#include <random>

#include "srp/core/Error.h"

namespace srp::motion {
namespace {

double minJerk(double s) { return s * s * s * (10 - 15 * s + 6 * s * s); }

/// Detector-like observations of the noise-free timeline (`hand`, `obj`, `yaw` per frame): the hand
/// with dropouts and bursts of loss, each object with noise, dropouts (more under the hand) and
/// flicker onto another object's place. Draws from `rng` in a fixed order (the demo's seed decides).
void observe(const SyntheticPickPlaceGenerator::Options& c, const std::vector<Eigen::Vector3d>& hand,
             const std::vector<bool>& handVisible, const std::vector<std::vector<Eigen::Vector3d>>& obj,
             const std::vector<std::vector<double>>& yaw, std::mt19937& rng,
             std::uniform_real_distribution<double>& uni, std::normal_distribution<double>& gauss,
             SyntheticPickPlace& out) {
  const double dt = 1.0 / c.frameRate_hz;
  const std::size_t nMoved = c.movedObjects.size(), nAll = obj.size();
  const int n = static_cast<int>(hand.size());
  out.hand = core::PositionTrajectory("camera");
  int burst = 0;
  for (int k = 0; k < n; ++k) {
    core::PositionSample s;
    s.frame = k;
    s.t_s = k * dt;
    if (burst == 0 && uni(rng) < 0.01) burst = 2 + static_cast<int>(6 * uni(rng));  // hand lost for a moment
    const bool detected = handVisible[static_cast<std::size_t>(k)] && burst == 0 && uni(rng) >= c.handDropoutRate;
    if (burst > 0) --burst;
    if (detected)
      s.p_m = hand[static_cast<std::size_t>(k)] +
              Eigen::Vector3d(c.handNoiseXY_m * gauss(rng), c.handNoiseXY_m * gauss(rng), c.handNoiseZ_m * gauss(rng));
    else s.p_m.setZero(), s.valid = false;
    out.hand.append(s);
  }
  for (std::size_t i = 0; i < nAll; ++i) {
    ObjectTrack t;
    t.name = i < nMoved ? c.movedObjects[i] : c.staticObjects[i - nMoved];
    t.positions = core::PositionTrajectory("camera");
    int flicker = 0;
    Eigen::Vector3d decoy = Eigen::Vector3d::Zero();
    for (int k = 0; k < n; ++k) {
      const Eigen::Vector3d truth = obj[i][static_cast<std::size_t>(k)];
      core::PositionSample s;
      s.frame = k;
      s.t_s = k * dt;
      const bool occluded = handVisible[static_cast<std::size_t>(k)] &&
                            (hand[static_cast<std::size_t>(k)] - truth).norm() < 0.06 + c.handAboveObject_m;
      const double missRate = occluded ? c.occlusionDropoutRate : c.objectDropoutRate;
      if (flicker == 0 && uni(rng) < c.flickerRate) {
        flicker = 1 + static_cast<int>(3 * uni(rng));
        const std::size_t other = (i + 1 + static_cast<std::size_t>(uni(rng) * (nAll - 1))) % nAll;
        decoy = other != i ? obj[other][static_cast<std::size_t>(k)] : truth + Eigen::Vector3d(0.1, 0.0, 0.0);
      }
      if (flicker > 0) {
        --flicker;
        s.p_m = decoy + c.objectNoise_m * Eigen::Vector3d(gauss(rng), gauss(rng), gauss(rng));
      } else if (uni(rng) < missRate) {
        s.p_m.setZero(), s.valid = false;
      } else {
        s.p_m = truth + c.objectNoise_m * Eigen::Vector3d(gauss(rng), gauss(rng), gauss(rng));
      }
      t.positions.append(s);
      t.yaw_rad.push_back(yaw[i][static_cast<std::size_t>(k)] + 0.02 * gauss(rng));
    }
    out.objects.push_back(std::move(t));
  }
}

}  // namespace

SyntheticPickPlace SyntheticPickPlaceGenerator::generate() const {
  const auto& c = options_;
  core::require(!c.movedObjects.empty(), "synthetic demo: no object to move");
  core::require(c.frameRate_hz > 0, "synthetic demo: frame rate must be positive");
  std::mt19937 rng(c.seed);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  std::normal_distribution<double> gauss(0.0, 1.0);
  const auto frames = [&](double seconds) {
    return std::max(1, static_cast<int>(std::lround(seconds * c.frameRate_hz)));
  };

  // Scene: sources in the "blue box" (left), targets in the "gray box" (right).
  const std::size_t nMoved = c.movedObjects.size(), nAll = nMoved + c.staticObjects.size();
  std::vector<Eigen::Vector3d> p0(nAll), p1(nAll);
  std::vector<double> yaw0(nAll), yaw1(nAll);
  for (std::size_t i = 0; i < nAll; ++i) {
    p0[i] = Eigen::Vector3d(-0.25 + 0.07 * (i % 3), -0.08 + 0.08 * static_cast<double>(i / 3), 0.9 + 0.01 * uni(rng));
    p1[i] = Eigen::Vector3d(0.15 + 0.07 * (i % 3), -0.08 + 0.08 * static_cast<double>(i / 3), 0.9 + 0.01 * uni(rng));
    if (i >= nMoved || c.putBackWhereTaken) p1[i] = p0[i];
    yaw0[i] = -1.0 + 2.0 * uni(rng);
    yaw1[i] = i < nMoved ? -1.0 + 2.0 * uni(rng) : yaw0[i];
  }
  const Eigen::Vector3d home(0.0, 0.3, 0.6), above(0.0, 0.0, -c.handAboveObject_m);

  // Noise-free timeline.
  std::vector<Eigen::Vector3d> hand;
  std::vector<bool> handVisible;
  std::vector<std::vector<Eigen::Vector3d>> obj(nAll);
  std::vector<std::vector<double>> yaw(nAll);
  std::vector<Eigen::Vector3d> objNow = p0;
  std::vector<double> yawNow = yaw0;
  SyntheticPickPlace out;
  auto push = [&](const Eigen::Vector3d& h, bool visible) {
    hand.push_back(h);
    handVisible.push_back(visible);
    for (std::size_t i = 0; i < nAll; ++i) obj[i].push_back(objNow[i]), yaw[i].push_back(yawNow[i]);
  };
  Eigen::Vector3d h = home;
  for (int k = 0; k < frames(c.handAbsent_s); ++k) push(h, false);
  auto jitter = [&](double d) { return d * (0.75 + 0.5 * uni(rng)); };
  for (std::size_t i = 0; i < nMoved; ++i) {
    const Eigen::Vector3d from = h, to = p0[i] + above;
    const int nr = frames(jitter(c.reachDuration_s));
    for (int k = 1; k <= nr; ++k) push(from + minJerk(static_cast<double>(k) / nr) * (to - from), true);
    h = to;
    // Grasp: the fingers close in the middle of the still period at the object.
    out.graspIndex.push_back(static_cast<int>(hand.size()) + c.graspHoldFrames / 2);
    for (int k = 0; k < c.graspHoldFrames; ++k) push(h, true);
    const int nm = frames(jitter(c.moveDuration_s));
    const Eigen::Vector3d goal = p1[i] + above;
    for (int k = 1; k <= nm; ++k) {
      const double s = static_cast<double>(k) / nm, m = minJerk(s);
      h = to + m * (goal - to) + Eigen::Vector3d(0, 0, -c.lift_m * std::sin(M_PI * m));
      objNow[i] = h - above;
      yawNow[i] = yaw0[i] + m * (yaw1[i] - yaw0[i]);
      push(h, true);
    }
    // Placed: the first frame the object is within kPlacedTol_m of where it comes to rest.
    constexpr double kPlacedTol_m = 0.002;
    int placed = static_cast<int>(hand.size()) - 1;
    while (placed > 0 && (obj[i][static_cast<std::size_t>(placed - 1)] - objNow[i]).norm() < kPlacedTol_m) --placed;
    out.releaseIndex.push_back(placed);
    for (int k = 0; k < c.releaseHoldFrames; ++k) push(h, true);
    // Let go and lift the hand off the object.
    const Eigen::Vector3d released = h, lifted = h + Eigen::Vector3d(0, 0, -0.06);
    const int nl = frames(c.idleBetween_s);
    for (int k = 1; k <= nl; ++k) push(released + minJerk(static_cast<double>(k) / nl) * (lifted - released), true);
    h = lifted;
  }
  {
    const Eigen::Vector3d from = h;
    const int nb = frames(1.0);
    for (int k = 1; k <= nb; ++k) push(from + minJerk(static_cast<double>(k) / nb) * (home - from), true);
    for (int k = 0; k < frames(c.handAbsent_s); ++k) push(home, false);
  }

  // Detector-like observations.
  observe(c, hand, handVisible, obj, yaw, rng, uni, gauss, out);
  out.planOrder = c.movedObjects;
  return out;
}

std::string SyntheticPickPlace::instruction() const {
  std::string text = "Synthetic demo: pick and place";
  for (std::size_t i = 0; i < planOrder.size(); ++i) text += std::string(i ? ", then " : " ") + "the " + planOrder[i];
  return text;
}

}  // namespace srp::motion
