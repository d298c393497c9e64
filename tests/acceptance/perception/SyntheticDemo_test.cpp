// Issue 5 acceptance on a synthetic demo with ground truth (srp::synth, default
// scene, thesis instruction 1, default sensor noise): the first frames up to
// the end of the first pick & place. Slow (renders ~200 frames): CTest label `slow`.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "HandEvaluation.h"
#include "RenderedDemo.h"
#include "srp/perception/RawlogPerception.h"

namespace srp::perception {
namespace {

constexpr int kFrames = 200;

using testing::percentile;  // NaN for no samples: every assertion on it fails

using Demo = testing::RenderedDemo;

/// The first kFrames frames of the default demo, rendered; or, when the
/// environment names one (SRP_PERCEPTION_DEMO=demo.rawlog, its ground truth
/// demo.gt.json next to it, e.g. the whole demo of `make demo`), that demo.
const Demo& demo() {
  static const Demo d = [] {
    synth::SynthDemoOptions o;
    o.maxFrames = kFrames;
    return testing::renderDefaultDemo("perception_synthetic_demo.rawlog", o, std::getenv("SRP_PERCEPTION_DEMO"));
  }();
  return d;
}

TEST(SyntheticDemo, MarkerHandAndObjects) {
  const Demo& d = demo();
  const PerceptionResult r = perceiveRawlog(d.rawlog, d.catalogue, testing::instruction1Options(d.gt));
  ASSERT_EQ(r.frames, static_cast<int>(d.gt.frames.size()));

  std::vector<double> handErr_m;
  int tagFrames = 0;
  for (std::size_t i = 0; i < d.gt.frames.size(); ++i) {
    const auto& f = d.gt.frames[i];
    if (!f.handInView && r.hand[i].valid) ADD_FAILURE() << "hand reported in frame " << i << " without a hand in view";
    if (!f.tagInView) continue;
    ++tagFrames;
    if (r.hand[i].valid) handErr_m.push_back((r.hand[i].p_m - f.p_camera_palm_m).norm());
  }
  const double rate = static_cast<double>(handErr_m.size()) / std::max(1, tagFrames);
  std::printf("[ figures  ] marker hand: %zu/%d tag-visible frames (%.1f %%), median %.1f mm, p95 %.1f mm\n",
              handErr_m.size(), tagFrames, 100 * rate, 1e3 * percentile(handErr_m, 0.5), 1e3 * percentile(handErr_m, 0.95));
  constexpr double kHandMedianTol_m = 0.005, kHandP95Tol_m = 0.015;  // issue 5
  EXPECT_LT(percentile(handErr_m, 0.5), kHandMedianTol_m);
  EXPECT_LT(percentile(handErr_m, 0.95), kHandP95Tol_m);
  EXPECT_GE(rate, 0.99);  // issue 5: tag-visible = readable in the rendered frame (srp::synth ground truth)

  const core::Pose3 X_camera_world = d.gt.X_world_camera.inverse();
  // Per-frame errors for diagnosis: SRP_PERCEPTION_FRAMES_CSV=errors.csv.
  std::ofstream perFrame;
  if (const char* path = std::getenv("SRP_PERCEPTION_FRAMES_CSV")) {
    perFrame.open(path);
    perFrame << "frame,class,phase,carried,detected,confidence,error_mm,dx_world_mm,dy_world_mm,dz_world_mm,yaw_error_deg,"
                "hand_distance_mm\n";
  }
  for (const auto& traj : r.objects) {
    const auto* cls = d.catalogue.find(traj.className);
    ASSERT_NE(cls, nullptr);
    const double symmetry = ObjectModel::fromCatalogue(*cls).yawSymmetry_rad;
    std::vector<double> pos_m, yaw_rad;
    int frames = 0, detected = 0, correct = 0, carriedWrong = 0;
    // Unoccluded = not carried and no hand pixel over the object's projected box
    // (ground truth): detected in the frame / reported within 2 cm after refinement.
    int unoccluded = 0, unoccludedDetected = 0, unoccludedReported = 0;
    for (std::size_t i = 0; i < d.gt.frames.size() && i < traj.samples.size(); ++i) {
      const auto& f = d.gt.frames[i];
      if (!f.X_world_objects.count(traj.className)) continue;
      if (f.carriedObject == traj.className) {
        // In the hand: not detected, or where the hand carries it.
        const core::Pose3 truth = X_camera_world * f.X_world_objects.at(traj.className);
        carriedWrong += traj.samples[i].detected && core::translationDistance(traj.samples[i].X_camera_object, truth) >= 0.02;
        continue;
      }
      ++frames;
      const core::Pose3 truth = X_camera_world * f.X_world_objects.at(traj.className);
      const auto& s = traj.samples[i];
      const double e = core::translationDistance(s.X_camera_object, truth);
      if (s.detected) {
        ++detected;
        correct += e < 0.02;
      }
      if (f.handOccludedObjects && !f.handOccludedObjects->count(traj.className)) {
        ++unoccluded;
        unoccludedDetected += s.detected && e < 0.02;
        unoccludedReported += e < 0.02;
      }
      pos_m.push_back(e);
      const Eigen::Matrix3d R_world = d.gt.X_world_camera.linear() * s.X_camera_object.linear();
      const Eigen::Matrix3d R_truth = f.X_world_objects.at(traj.className).linear();
      double dy = std::fmod(std::abs(core::angleDifference(core::yawOf(R_world), core::yawOf(R_truth))), symmetry);
      yaw_rad.push_back(std::min(dy, symmetry - dy));
      if (perFrame.is_open()) {
        const Eigen::Vector3d d_world_m = (d.gt.X_world_camera * s.X_camera_object).translation() -
                                          f.X_world_objects.at(traj.className).translation();
        const double signedYaw = std::remainder(core::angleDifference(core::yawOf(R_world), core::yawOf(R_truth)), symmetry);
        perFrame << i << ',' << traj.className << ',' << f.phase << ',' << (f.carriedObject == traj.className) << ','
                 << s.detected << ',' << s.confidence << ',' << 1e3 * e << ',' << 1e3 * d_world_m.x() << ','
                 << 1e3 * d_world_m.y() << ',' << 1e3 * d_world_m.z() << ',' << signedYaw * 180 / M_PI << ','
                 << (f.handInView ? 1e3 * (f.p_camera_palm_m - truth.translation()).norm() : -1.0) << '\n';
      }
    }
    EXPECT_EQ(carriedWrong, 0) << traj.className << " reported away from the hand carrying it";
    const double precision = detected ? static_cast<double>(correct) / detected : 0.0;
    const double recallDetected = static_cast<double>(unoccludedDetected) / std::max(1, unoccluded);
    const double recallRefined = static_cast<double>(unoccludedReported) / std::max(1, unoccluded);
    std::printf("[ figures  ] %-14s %s: detected %d/%d frames, precision %.1f %%, position median %.1f mm, yaw median %.2f deg; "
                "unoccluded %d frames: detected %.1f %%, reported after refinement %.1f %%\n",
                traj.className.c_str(), traj.isStatic ? "static" : "moving", detected, frames, 100 * precision,
                1e3 * percentile(pos_m, 0.5), percentile(yaw_rad, 0.5) * 180 / M_PI, unoccluded, 100 * recallDetected,
                100 * recallRefined);
    constexpr double kPrecision = 0.99, kPositionMedian_m = 0.005, kYawMedian_rad = 3.0 * M_PI / 180;  // issue 5
    EXPECT_GE(precision, kPrecision) << traj.className;
    // Issue 5: recall >= 99 % on unoccluded frames, of what the module reports
    // (after refinement: a fixed box or a tracked part's pose within 2 cm).
    constexpr double kUnoccludedRecall = 0.99;
    if (unoccluded > 0) EXPECT_GE(recallRefined, kUnoccludedRecall) << traj.className << " on unoccluded frames";
    EXPECT_LT(percentile(pos_m, 0.5), kPositionMedian_m) << traj.className;
    // The octagon's and the cuboid's yaw come from the colour edges (EdgeYawRefiner):
    // in depth the octagon's corners move ~1 px over 9 deg at 0.84 m.
    EXPECT_LT(percentile(yaw_rad, 0.5), kYawMedian_rad)
        << traj.className;
  }
}

TEST(SyntheticDemo, MarkerFreeHand) {
  const Demo& d = demo();
  PerceptionOptions o;
  o.hand = PerceptionOptions::HandMethod::MarkerFree;
  o.plan = {{"cuboid", false}};
  const PerceptionResult r = perceiveRawlog(d.rawlog, d.catalogue, o);
  std::vector<double> err_m;
  int inView = 0;
  for (std::size_t i = 0; i < d.gt.frames.size(); ++i) {
    if (!d.gt.frames[i].handInView) continue;
    ++inView;
    if (r.hand[i].valid) err_m.push_back((r.hand[i].p_m - d.gt.frames[i].p_camera_palm_m).norm());
  }
  const double rate = static_cast<double>(err_m.size()) / std::max(1, inView);
  std::printf("[ figures  ] marker-free hand: %zu/%d frames with the hand in view (%.1f %%), median %.1f mm, p95 %.1f mm\n",
              err_m.size(), inView, 100 * rate, 1e3 * percentile(err_m, 0.5), 1e3 * percentile(err_m, 0.95));
  EXPECT_GE(rate, 0.95);  // issue 5
  EXPECT_LE(percentile(err_m, 0.5), 0.015);  // issue 5: median palm error <= 15 mm
}

}  // namespace
}  // namespace srp::perception
