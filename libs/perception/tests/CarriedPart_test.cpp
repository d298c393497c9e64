// A part being carried is never reported at another part's spot, and a part
// left in place is not swapped with it: the per-frame object report on a
// rendered synthetic demo with ground truth (srp::synth, default scene, thesis
// instruction 1, default sensor noise), short: the first pick & place only,
// the demonstrator twice as fast (~100 frames, a few seconds).
#include <gtest/gtest.h>

#include "RenderedDemo.h"
#include "srp/perception/RawlogPerception.h"

namespace srp::perception {
namespace {

using ShortDemo = testing::RenderedDemo;

const ShortDemo& shortDemo() {
  static const ShortDemo d = [] {
    synth::SynthDemoOptions o;
    o.demo.speedFactor = 2.0;
    o.demo.idleStart_s = 0.5;
    o.maxFrames = 100;
    return testing::renderDefaultDemo("perception_carried_demo.rawlog", o);
  }();
  return d;
}

TEST(CarriedPart, FollowsTheHandOrIsNotDetectedAndNothingIsSwapped) {
  constexpr double kCorrect_m = 0.02;  // a detection this close to the truth is of the right object
  const ShortDemo& d = shortDemo();
  const PerceptionResult r = perceiveRawlog(d.rawlog, d.catalogue, testing::instruction1Options(d.gt));
  ASSERT_EQ(r.frames, static_cast<int>(d.gt.frames.size()));

  // The demo must hold a carry and the release after it, else it tests nothing.
  int carried = 0, lastCarried = -1;
  for (std::size_t i = 0; i < d.gt.frames.size(); ++i)
    if (!d.gt.frames[i].carriedObject.empty()) {
      ++carried;
      lastCarried = static_cast<int>(i);
    }
  ASSERT_GT(carried, 10);
  ASSERT_LT(lastCarried + 10, static_cast<int>(d.gt.frames.size())) << "the demo ends before the part is released";

  const core::Pose3 X_camera_world = d.gt.X_world_camera.inverse();
  int carriedDetections = 0, wrong = 0, detections = 0;
  for (const auto& traj : r.objects) {
    for (std::size_t i = 0; i < d.gt.frames.size(); ++i) {
      const auto& f = d.gt.frames[i];
      const auto& s = traj.samples.at(i);
      if (!s.detected) continue;
      ++detections;
      const double e_m =
          core::translationDistance(s.X_camera_object, X_camera_world * f.X_world_objects.at(traj.className));
      if (f.carriedObject == traj.className) ++carriedDetections;
      if (e_m >= kCorrect_m) {
        ++wrong;
        ADD_FAILURE() << traj.className << " reported " << 1e3 * e_m << " mm from its true place in frame " << i
                      << (f.carriedObject.empty() ? "" : " (" + f.carriedObject + " in the hand)");
      }
    }
  }
  std::printf("[ figures  ] %d carried frames; %d detections, %d of a carried part, %d wrong (> 2 cm)\n", carried,
              detections, carriedDetections, wrong);
  // After the release every part is where the ground truth has it.
  const auto& last = d.gt.frames.back();
  for (const auto& traj : r.objects) {
    const double e_m = core::translationDistance(traj.samples.back().X_camera_object,
                                                 X_camera_world * last.X_world_objects.at(traj.className));
    EXPECT_LT(e_m, kCorrect_m) << traj.className << " at the end";
  }
}

// The tracker searches a frame's segments on two threads: every object
// sample is the one a single thread gives, bit for bit.
TEST(CarriedPart, SegmentSearchOnTwoThreadsGivesTheAnswersOfOne) {
  const ShortDemo& d = shortDemo();
  PerceptionOptions one = testing::instruction1Options(d.gt), two = one;
  one.tracking.searchThreads = 1;
  two.tracking.searchThreads = 2;
  const PerceptionResult a = perceiveRawlog(d.rawlog, d.catalogue, one), b = perceiveRawlog(d.rawlog, d.catalogue, two);
  ASSERT_EQ(a.objects.size(), b.objects.size());
  int detections = 0;
  for (std::size_t k = 0; k < a.objects.size(); ++k) {
    ASSERT_EQ(a.objects[k].samples.size(), b.objects[k].samples.size());
    for (std::size_t i = 0; i < a.objects[k].samples.size(); ++i) {
      const auto &sa = a.objects[k].samples[i], &sb = b.objects[k].samples[i];
      EXPECT_EQ(sa.detected, sb.detected) << a.objects[k].className << " frame " << i;
      EXPECT_EQ(sa.confidence, sb.confidence) << a.objects[k].className << " frame " << i;
      EXPECT_TRUE(sa.X_camera_object.matrix() == sb.X_camera_object.matrix())
          << a.objects[k].className << " frame " << i;
      detections += sa.detected;
    }
  }
  EXPECT_GT(detections, 100) << "the demo must show the parts";
}

}  // namespace
}  // namespace srp::perception
