#pragma once
/// \file RealTrackNoise.h
/// \brief A seeded, trajectory-level model of the tracks a real detector
/// pipeline (RealSense depth, a hand detector, oriented boxes on the parts)
/// produces, applied to noise-free ground-truth trajectories with known
/// grasp/release frames. It reproduces the statistics of two real recordings
/// of the thesis author (held out; only their statistics are used); every
/// parameter below names the figure it reproduces. RealTrackNoise::measure()
/// measures the generated tracks the same way (libs/motion/README.md has the
/// table).
///
/// Three parts:
///  1. Choreography (the demonstrator): before each release the hand hovers
///     over the place, nearly still with the part in the hand, then lowers it
///     (the hover is part of the carry: the truth release stays the last frame
///     the part moves with the hand); the hand may leave at once or after the
///     choreography's pause; after the release it lingers near the target,
///     hovering a few cm above it, and may nudge the part again (a small
///     second shift of its position) before it leaves. Frames are inserted or
///     removed, so every later truth index moves.
///  2. Sensor (the detectors), camera frame (z = depth): parts at rest with
///     sub-mm scatter; outlier episodes (a wrong depth along the part's ray, or
///     a detection on the hand while the hand is near/over the part); a part
///     not detected keeps its last pixel and reads the depth there now (the
///     thesis' forward-filled box centre), which is the hand's depth when the
///     hand covers that pixel. The hand: Gaussian noise, single-frame jumps of
///     up to 25 cm, missed frames carried forward; zeros only while it is out
///     of view (as the clean input).
///  3. Placement behaviours of the second recording (Options::placement): the
///     part hidden under the hand around its grasp and its placement (its
///     column holds nothing, another part's position or the hand labelled as
///     the part), and ghosts: the previous plan part, already at its
///     destination, labelled as this one.

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
  struct Options {
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
    // --- placement behaviours (second recording) -----------------------------
    /// Off: the model of the first recording alone (its figures stay reproducible).
    bool placement = true;
    /// "the demonstrator hovers 1.5-3.5 s over each destination before letting
    /// go, hand nearly still, the part still in the hand": the hover's duration,
    /// uniform in [min, max]; the hover point is where the final approach is
    /// hoverOffset (uniform 1-2 cm) from the release pose; the hand wanders up to
    /// hoverWander_m around it (slow), then lowers the part to its place in
    /// descent (uniform) s ("arrives ~10 frames before the part is let go").
    double hoverMin_s = 1.5, hoverMax_s = 3.5;
    double hoverOffsetMin_m = 0.01, hoverOffsetMax_m = 0.02;
    double hoverWander_m = 0.003;
    double descentMin_s = 0.2, descentMax_s = 0.4;
    /// The choreography's pause at the place after the release (the fingers
    /// open) is kept with this probability; otherwise the hand leaves as soon
    /// as it lets go (the pause's frames are removed).
    double releasePauseProbability = 0.5;
    /// "parts are hidden under the hand at every grasp and every placement":
    /// hidden from hiddenBeforeGrasp (uniform) s before the grasp to
    /// hiddenAfterGrasp s after it, and from the hover's start until the hand,
    /// after the release, is hiddenClear from its release pose or has been
    /// moving (5 mm from it) for hiddenAfterLeave s, whichever comes first.
    double hiddenBeforeGraspMin_s = 0.3, hiddenBeforeGraspMax_s = 0.8;
    double hiddenAfterGraspMin_s = 0.1, hiddenAfterGraspMax_s = 0.4;
    double hiddenClear_m = 0.02;
    double hiddenAfterLeaveMin_s = 0.1, hiddenAfterLeaveMax_s = 0.8;
    /// "... the part's column then holds nothing, the position of another part,
    /// or the hand itself labelled as that part": episodes of 1..hiddenEpisodeMax
    /// frames, each nothing / another part / the hand with these probabilities
    /// (the rest: the hand).
    int hiddenEpisodeMax_frames = 8;
    double hiddenNothing = 0.4, hiddenOtherPart = 0.3;
    /// "ghost detections: another part mislabelled as this one, already at the
    /// destination (the first part, seen there from its own release on,
    /// labelled as the second part)": per plan part after the first, with this
    /// probability the previous plan part is its ghost from that part's release
    /// on, replacing a fraction (uniform [min, max]) of its detections in
    /// episodes of outlierEpisodeMean_frames on average.
    double ghostProbability = 0.5;
    double ghostFractionMin = 0.1, ghostFractionMax = 0.4;
    std::uint32_t seed = 1;
  };

  /// Noisy demo, its noise-free counterpart (same frames, lingering and
  /// nudges included) and what the choreography did.
  struct Result {
    LabelledDemo noisy, truth;
    std::vector<int> nudgeIndex;     ///< per plan object: sample of the nudge, -1 none
    std::vector<int> departIndex;    ///< per plan object: the hand's last lingering sample
    /// Placement behaviours, per plan object (-1 / empty when off): the hover's
    /// first and last sample, whether the pause after the release was kept, the
    /// plan index of its ghost ...
    std::vector<int> hoverStartIndex, hoverEndIndex;
    std::vector<bool> pauseKept;
    std::vector<int> ghostOf;
    /// ... and per tracked object (as in `noisy.objects`) and sample: 0 as the
    /// sensor model of the first recording made it, 1 hidden (nothing, another
    /// part or the hand), 2 a ghost.
    std::vector<std::vector<std::uint8_t>> placementEffect;
  };

  /// Statistics of a generated demo, measured like the real recordings' figures.
  struct Statistics {
    double partRestScatterMedian_m = 0;       ///< median |detection - truth| of non-outlier rest samples
    std::vector<double> partOutlierFraction;  ///< per object: rest samples > 5 cm from the truth
    double outlierMin_m = 0, outlierMax_m = 0;  ///< distance range of those outliers
    double onHandOutlierShare = 0;           ///< share of outliers within 5 cm of the true hand
    double handStepMedian_m = 0, handStepP95_m = 0, handStepMax_m = 0;  ///< consecutive in-view detections
    std::vector<double> linger_s;            ///< per placement: release to the hand leaving 10 cm
    std::vector<double> nudgeAfter_s;        ///< per nudge: time after the release
    std::vector<double> carry_s;             ///< per placement: grasp to release
    int notDetectedPartSamples = 0;          ///< part samples marked not detected outside hidden spans (must be 0)
    // Placement behaviours:
    std::vector<double> hover_s;             ///< per placement: the hover's duration
    std::vector<double> hoverHandSpread_m;   ///< per placement: largest distance of the hand from its release pose while hovering
    std::vector<double> hiddenGrasp_s, hiddenRelease_s;  ///< per plan object: length of the hidden spans
    double hiddenNothingShare = 0, hiddenOtherShare = 0, hiddenHandShare = 0;  ///< what hidden samples hold
    std::vector<double> ghostFraction;       ///< per ghosted part: share of ghost samples from the ghost's release on
  };

  RealTrackNoise() = default;
  explicit RealTrackNoise(Options options) : options_(options) {}

  /// Applies the model. Throws InvalidInputError when the demo has no plan
  /// object, event indices out of range or a plan object without a track.
  /// With Options::placement off the result is the first recording's model alone.
  Result apply(const LabelledDemo& clean) const;

  /// Measures `r.noisy` against `r.truth`.
  static Statistics measure(const Result& r, double frameRate_hz = 30.0);

  const Options& options() const { return options_; }

 private:
  Options options_;
};

}  // namespace srp::motion
