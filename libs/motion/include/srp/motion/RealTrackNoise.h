#pragma once
/// \file RealTrackNoise.h
/// \brief A seeded, trajectory-level model of the tracks a real detector
/// pipeline (the thesis': RealSense depth, a hand detector, oriented boxes on
/// the parts) produces, applied to noise-free ground-truth trajectories with
/// known grasp/release frames (issue 18). It reproduces the statistics that
/// issue 18 gives for the thesis author's real recording; every parameter
/// below names the figure it reproduces. RealTrackNoise::measure() measures
/// the generated tracks the same way (libs/motion/README.md has the table).
///
/// Two parts:
///  1. Choreography (the demonstrator): after each release the hand lingers
///     near the target, hovering a few cm above it, and may nudge the part
///     again (a small second shift of its position) before it leaves. Frames
///     are inserted, so every later truth index moves; the truth release stays
///     the first placement.
///  2. Sensor (the detectors), camera frame (z = depth): parts at rest with
///     sub-mm scatter; outlier episodes (a wrong depth along the part's ray, or
///     a detection on the hand while the hand is near/over the part); a part
///     not detected keeps its last pixel and reads the depth there now (the
///     thesis' forward-filled box centre), which is the hand's depth when the
///     hand covers that pixel; no sample is ever marked "not detected". The
///     hand: Gaussian noise, single-frame jumps of up to 25 cm, missed frames
///     carried forward; zeros only while it is out of view (as the clean input).

#include <cstdint>
#include <string>
#include <vector>

#include "srp/motion/Segmenter.h"

namespace srp::motion {

/// Hand and object tracks with the true event indices of the moved objects.
struct LabelledDemo {
  core::PositionTrajectory hand;              ///< invalid (zeros) = hand out of view
  std::vector<ObjectTrack> objects;           ///< every tracked object
  std::vector<std::string> planOrder;         ///< moved objects in plan order
  std::vector<int> graspIndex, releaseIndex;  ///< truth per plan object (sample indices)
};

class RealTrackNoise {
 public:
  struct Config {
    // --- choreography -------------------------------------------------------
    /// "after a release the hand may stay near the target for 2-4 s": time
    /// from the release to the hand's departure, uniform in [min, max].
    double lingerMin_s = 2.0, lingerMax_s = 4.0;
    /// Hover while lingering: up to this far above the part (towards the
    /// camera) and this far sideways, slow (0.3-0.8 Hz) wandering.
    double lingerLift_m = 0.05, lingerSideways_m = 0.02;
    /// "a part may be nudged again (a second small jump of its position 3-4 s
    /// after the first) before the hand leaves": probability per placement,
    /// time after the release, size of the shift (assumed: "small").
    double nudgeProbability = 0.5;
    double nudgeMin_s = 3.0, nudgeMax_s = 4.0;
    double nudgeMin_m = 0.004, nudgeMax_m = 0.015;
    // --- parts ----------------------------------------------------------------
    /// "objects at rest: median scatter < 1 mm": Gaussian per axis.
    double partNoiseXY_m = 0.0004, partNoiseZ_m = 0.0006;
    /// "4-21 % of the frames are outliers": per part, a target fraction of
    /// outlier frames uniform in [min, max]; episodes of 1..2*mean-1 frames.
    double outlierFractionMin = 0.03, outlierFractionMax = 0.13;
    double outlierEpisodeMean_frames = 4.0;
    /// "5-70 cm away (a wrong depth ...)": depth error magnitude.
    double wrongDepthMin_m = 0.05, wrongDepthMax_m = 0.70;
    /// "... or a detection on the hand while it occludes the part": while the
    /// hand is within handNear_m of the part, an episode is this likely to be
    /// a detection on the hand, and episodes start this many times as often.
    double handNear_m = 0.20;
    double onHandProbability = 0.7;
    double nearHandRateFactor = 1.5;
    /// "no frame is marked 'not detected': the pipeline carries the last value":
    /// miss rates (part free / covered by the hand or carried); a miss keeps the
    /// last pixel and reads the depth there now.
    double partMissFree = 0.02, partMissCovered = 0.15;
    double occlusionRadius_m = 0.07;  ///< the hand covers a pixel within this of its centre (at the part's depth)
    // --- hand -----------------------------------------------------------------
    /// "the hand: median step 2.6 mm per frame, p95 22 mm": Gaussian per axis.
    double handNoiseXY_m = 0.0005, handNoiseZ_m = 0.001;
    /// "single-frame jumps up to 25 cm": rate per frame, size uniform in [min, max].
    double handJumpRate = 0.02;
    double handJumpMin_m = 0.03, handJumpMax_m = 0.25;
    double handMiss = 0.03;  ///< missed hand detections, carried forward
    std::uint32_t seed = 1;
  };

  /// Noisy demo, its noise-free counterpart (same frames, lingering and
  /// nudges included) and what the choreography did.
  struct Result {
    LabelledDemo noisy, truth;
    std::vector<int> nudgeIndex;     ///< per plan object: sample of the nudge, -1 none
    std::vector<int> departIndex;    ///< per plan object: the hand's last lingering sample
  };

  /// Statistics of a generated demo, measured like issue 18's figures.
  struct Statistics {
    double partRestScatterMedian_m = 0;       ///< median |detection - truth| of non-outlier rest samples
    std::vector<double> partOutlierFraction;  ///< per object: rest samples > 5 cm from the truth
    double outlierMin_m = 0, outlierMax_m = 0;  ///< distance range of those outliers
    double onHandOutlierShare = 0;           ///< share of outliers within 5 cm of the true hand
    double handStepMedian_m = 0, handStepP95_m = 0, handStepMax_m = 0;  ///< consecutive in-view detections
    std::vector<double> linger_s;            ///< per placement: release to the hand leaving 10 cm
    std::vector<double> nudgeAfter_s;        ///< per nudge: time after the release
    std::vector<double> carry_s;             ///< per placement: grasp to release
    int notDetectedPartSamples = 0;          ///< part samples marked not detected (must be 0)
  };

  RealTrackNoise() = default;
  explicit RealTrackNoise(Config config) : config_(config) {}

  /// Applies the model. Throws InvalidInputError when the demo has no plan
  /// object, event indices out of range or a plan object without a track.
  Result apply(const LabelledDemo& clean) const;

  /// Measures `r.noisy` against `r.truth`.
  static Statistics measure(const Result& r, double frameRate_hz = 30.0);

  const Config& config() const { return config_; }

 private:
  Config config_;
};

}  // namespace srp::motion
