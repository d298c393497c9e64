#pragma once
/// \file SyntheticPickPlace.h
/// \brief Generates hand and object trajectories of a one-hand multi-step pick
/// & place demonstration with known grasp/release frames, with detector-like
/// noise, dropouts, occlusion and flicker. Used by the tests, the benchmark
/// and the `srp segment` / `srp motion` examples; it is test data, not a model
/// of real hands (rendered RGB-D demos: DemoGenerator).
///
/// Camera frame (x right, y down, z forward = depth), metres, radians; table
/// at depth ~0.9 m. Timeline: no hand for `handAbsent_s`, then per object
/// reach (minimum jerk) to the object, `graspHoldFrames` still, move with the
/// object (lifted by `lift_m` towards the camera), `releaseHoldFrames` still;
/// then back home and no hand. Ground truth: grasp = the middle frame of the
/// still period at the object (the fingers close), release = first frame the object is within 2 mm of where
/// it comes to rest (what an annotator marks as "placed").

#include <cstdint>
#include <string>
#include <vector>

#include "srp/motion/LearnSkills.h"

namespace srp::motion {

/// The demo's tracks (hand: invalid samples have p = (0, 0, 0) as the CSV
/// convention; objects; plan order = the moved objects) and the truth.
struct SyntheticPickPlace : DemoTracks {
  std::vector<int> graspIndex, releaseIndex;  ///< truth per moved object, plan order

  /// "Synthetic demo: pick and place the cuboid, then the star, ..." (plan order).
  std::string instruction() const;
};

/// Seeded synthetic pick-and-place tracks (hand and objects with detector-like noise) and their truth.
class SyntheticPickPlaceGenerator {
 public:
  /// The demo: objects, timing, noise of the tracks, seed.
  struct Options {
    std::vector<std::string> movedObjects = {"cuboid", "star", "parallelogram", "octagon"};  ///< in plan order
    std::vector<std::string> staticObjects;                                                  ///< tracked but never moved
    double frameRate_hz = 30.0;
    double handAbsent_s = 1.0;                           ///< at the start and at the end
    double reachDuration_s = 1.3, moveDuration_s = 1.6;  ///< +-25 % random per object
    double idleBetween_s = 0.3;                          ///< hand lifts off 6 cm after each release
    int graspHoldFrames = 4, releaseHoldFrames = 3;
    double lift_m = 0.12;
    bool putBackWhereTaken = false;  ///< each object is lifted and put back where it was
    double handAboveObject_m = 0.04;
    double handNoiseXY_m = 0.004, handNoiseZ_m = 0.008, objectNoise_m = 0.002;
    double handDropoutRate = 0.10;  ///< per frame, on top of bursts
    double objectDropoutRate = 0.03;
    double occlusionDropoutRate = 0.4;  ///< object missing when the hand is within 6 cm (plus its height above it)
    double flickerRate = 0.03;          ///< per frame: detection jumps to another object for 1-3 frames
    std::uint32_t seed = 1;
  };

  SyntheticPickPlaceGenerator() : SyntheticPickPlaceGenerator(Options{}) {}
  explicit SyntheticPickPlaceGenerator(Options options) : options_(std::move(options)) {}
  SyntheticPickPlace generate() const;

 private:
  Options options_;
};

}  // namespace srp::motion
