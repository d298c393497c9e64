#pragma once
/// \file Segmenter.h
/// \brief Finds the grasp and release frame of every target object of a
/// one-hand pick & place demonstration (thesis ch. 6.4.3, fig. 6.10; SPEC.md §3).
///
/// Per target object in plan order: fill and smooth the object's trajectory
/// (detections that move the object with no hand near it dropped, since
/// objects move only in the hand; detections far from their neighbours' median dropped, running median of
/// the rest against detector flicker, carry-forward, KalmanSmoother), fit a
/// 3-component Gaussian mixture (OpenCV cv::ml::EM, started at the initial
/// position, the midpoint and the final position) to its positions, and take
/// release = the first sample of the component the trajectory ends in, as the
/// change point that the fewest labels contradict (components are ordered by
/// time, components with means closer than minExcursion/2 are merged as one
/// place; a few flickering or occluded samples after the release do not move
/// it; the search starts mid-move, at the sample farthest from both rest positions). The thesis' grasp
/// (EventEstimator::Thesis) is the sample between the previous release and this
/// release where the smoothed hand is closest to the object's initial position
/// (the centre of the valley of near-closest samples, since the hand rests
/// there while grasping): it lands mid-pause, and the mixture's release lands
/// late when the object's detection drifts while the open hand still covers it.
///
/// The default (EventEstimator::HandDwellBoundary) keeps the mixture and the
/// valley as the coarse search and refines both events to the boundaries of
/// the hand's rests, which is where the object starts and stops moving with
/// the hand (the synthetic ground truth's definition: grasp = first frame the
/// object moves rigidly with the hand, release = last frame it does): grasp =
/// the last sample of the hand's rest at the object (searched over the valley
/// and a little after it), release = the first sample of the hand's rest at
/// the object's final position (searched from the grasp to just after the
/// mixture's release, among samples where the hand is within
/// releaseReachTolerance_m of its closest approach to the object's final
/// position, which excludes the hand's stops above the place). The boundary is the change point that best
/// fits the raw hand detections as a rest (their mean) on one side and a
/// smooth start from rest (p = p_rest + b dt^2 + c dt^3 per axis) on the other;
/// it needs only the hand, which the glove tag detects reliably, not the
/// object, whose detection is unreliable while the hand covers it.
///
/// Robust mode (Options::robust, default; real detector tracks): hand jumps and
/// carried values are dropped first, the object's rests are medians of its
/// detections, the coarse release is a Bernoulli change point into the final
/// rest (a nudge after the release stays inside it), and each object reports
/// its outlier fraction, release margin and cue gap (confidence). With the
/// placement cues (Options::placementCues, default) part detections on the hand
/// and ghosts (the final place of a part released earlier, labelled as this
/// one) are not evidence of the part, the grasp is searched until the hand has
/// left the part's start area, and the release is the start of the hand's rest
/// where it comes closest to the final place: a hover just above the place,
/// with the part still in the hand, is part of the move. The part itself
/// bounds both: the grasp is not before the last sample at which it is seen at
/// its initial place (unless the hand has been at the final place in between:
/// then what is seen at the start is a look-alike), the release not after the first from which it is seen
/// at its final place for good (within placeTolerance_m: a hand that stays on
/// the part, or presses it down, does not delay the release).
/// EventEstimator::ThesisPublished is the thesis' published code.
///
/// An object whose positions never leave its
/// initial position by more than `minExcursion_m` is reported as not moved
/// (no grasp/release, the search window is not advanced).
///
/// All trajectories are in one frame (e.g. "camera"), metres; the hand and
/// every object sample the same frames (same count, same frame numbers).

#include <Eigen/Core>
#include <limits>
#include <string>
#include <vector>

#include "srp/core/PositionTrajectory.h"
#include "srp/motion/KalmanSmoother.h"

namespace srp::motion {

/// One object's detected trajectory: positions (invalid = not detected) and
/// the yaw [rad] about the frame's z axis per sample (empty when unknown).
struct ObjectTrack {
  std::string name;
  core::PositionTrajectory positions;
  std::vector<double> yaw_rad;
};

/// Result for one object of the plan. Indices are sample indices (0-based)
/// into the trajectories, frames are their frame numbers; -1 when not moved.
struct ObjectSegmentation {
  std::string name;
  bool moved = false;
  int searchStartIndex = 0;  ///< previous object's release (0 for the first)
  int graspIndex = -1, releaseIndex = -1;
  int graspFrame = -1, releaseFrame = -1;
  Eigen::Vector3d p_initial_m = Eigen::Vector3d::Zero();  ///< object position before the grasp
  Eigen::Vector3d p_final_m = Eigen::Vector3d::Zero();    ///< object position after the release
  double maxExcursion_m = 0.0;       ///< largest distance of the smoothed object from p_initial
  double graspHandDistance_m = 0.0;  ///< hand to p_initial at the grasp
  std::vector<int> component;        ///< mixture component per sample, ordered by time: 0 first
  core::PositionTrajectory smoothed; ///< the filled and smoothed object trajectory
  std::string note;                  ///< what was unusual (not moved, order conflict), empty if nothing
  /// How much to trust the events (robust default estimator; NaN otherwise):
  /// share of the object's detections farther than 2 x restTolerance from its
  /// running median (outliers) ...
  double outlierFraction = std::numeric_limits<double>::quiet_NaN();
  /// ... the release change point's margin: -log-likelihood of the best
  /// change point more than 30 samples (1 s) away minus the chosen one's (nats;
  /// small = another release time, e.g. a nudge, explains the detections almost
  /// as well; about 26 when the detections are unambiguous) ...
  double releaseMargin = std::numeric_limits<double>::quiet_NaN();
  /// ... and release from the hand's rest minus release from the part's rest
  /// (two independent cues that should agree within a few samples), counted in
  /// the part's detections between them.
  int releaseCueGap = 0;
  /// Release: any of outlierFraction > 0.3, |releaseCueGap| > 10, releaseMargin < 10 (without the
  /// placement cues: with them a part hidden under the hand at its release makes every margin small).
  bool releaseLowConfidence = false;
  /// Grasp: outlierFraction > 0.3, no rest of the hand found at the part, or the hand never within
  /// handReach of the part's initial position.
  bool graspLowConfidence = false;
  bool lowConfidence = false;  ///< either event's confidence is low
};

struct Segmentation {
  core::PositionTrajectory hand;              ///< filled and smoothed hand trajectory
  int firstHandIndex = 0, lastHandIndex = 0;  ///< first/last sample with a hand detection
  std::vector<ObjectSegmentation> objects;    ///< in plan order
  std::vector<std::string> warnings;          ///< one line per unusual object
};

/// The segmenter's hand smoother: KalmanSmoother's defaults (noise estimated
/// from the data, missing samples predicted, no gate) with a process noise of
/// 2 m/s^2.
inline KalmanSmoother::Options handSmootherDefaults() {
  KalmanSmoother::Options c;
  c.accelerationStd_mps2 = 2.0;
  return c;
}

/// The segmenter's object smoother: the hand's, with an outlier gate at 5
/// sigma (gateMin_m, gateReset: KalmanSmoother's defaults) against detector flicker.
inline KalmanSmoother::Options objectSmootherDefaults() {
  KalmanSmoother::Options c = handSmootherDefaults();
  c.gateSigma = 5.0;
  return c;
}

class Segmenter {
 public:
  /// How grasp and release are placed (see the file comment).
  enum class EventEstimator {
    HandDwellBoundary,  ///< default: the ends of the hand's rests at the object
    Thesis,             ///< thesis ch. 6.4.3 made robust (flicker removal, seeded EM, change point): the estimator before issue 18
    /// The thesis' published code (shuanglu2023/SemanticRobotProgramming env_module, `srp segment --events
    /// thesis`): pykalman smoothing with identity models and unit covariances (missing object samples
    /// carried forward first, the hand's zeros kept as measurements as there), a 3-component full-covariance
    /// Gaussian mixture initialised by k-means (k-means++ seeding from `thesisSeed`) on the whole smoothed
    /// track, release = the first sample anywhere whose component is the last sample's, grasp = the smoothed
    /// hand sample closest to the mean object position before `start` within [start, release), start = the
    /// first hand detection, then the previous release.
    ThesisPublished,
  };

  struct Options {
    KalmanSmoother::Options handSmoother = handSmootherDefaults();
    /// Objects: gated against flicker; no measurement while occluded (the smoother bridges).
    KalmanSmoother::Options objectSmoother = objectSmootherDefaults();
    int medianWindow = 9;              ///< samples; removes flicker of up to 4 samples
    double flickerGate_m = 0.04;       ///< a detection this far from its neighbours' median is dropped
    double handReach_m = 0.15;         ///< an object jumping this far from the hand is a false detection
    double maxObjectSpeed_mps = 2.0;   ///< an object jumping faster is a false detection
    double minExcursion_m = 0.03;      ///< below: the object did not move
    double graspValleyDepth_m = 0.01;  ///< grasp = centre of the frames within this of the closest approach
    int emMaxIterations = 30;
    EventEstimator events = EventEstimator::HandDwellBoundary;
    unsigned thesisSeed = 0;  ///< ThesisPublished: seed of the k-means initialisation (sklearn's random_state)
    int restSamples = 6;               ///< hand detections fitted as the rest beside a boundary (>= 3)
    int moveSamples = 8;               ///< hand detections fitted as the smooth start beside a boundary (>= 3)
    double releaseReachTolerance_m = 0.02;  ///< release: |hand - p_final| within this of its minimum over the search
    /// Robust mode (issue 18, real detector tracks; false = the estimator before it, for comparisons):
    /// hand jumps and carried values dropped, object rests from medians of the raw detections, release = the
    /// change point into the final rest (detections within restTolerance of the final position).
    bool robust = true;
    double handOutlierSigmas = 4.0;   ///< hand detection dropped beyond this many robust sigmas of its neighbours' interpolation
    double handOutlierMin_m = 0.015;  ///< ... and beyond this distance
    int objectMedianHalfWindow = 15;  ///< running median of the object's detections, +-samples (at most the rest window - 1)
    int restMedianSamples = 30;       ///< initial/final position = median of the first/last this many detections
    double restTolerance_m = 0.025;   ///< a detection this close to the final position is in the final rest
    double carriedInRest = 0.05;      ///< release change point: P(detection in the final rest) while carried
    double restInRest = 0.6;          ///< ... and once placed (outliers, the lingering hand take the rest)
    double restNoiseFactor = 2.0;     ///< a hand rest admits detections within this x the hand's robust noise of its median
    double restNoiseMax_m = 0.006;    ///< ... at most this (a hand as noisy as the marker-free detector has no mm rests)
    double boundaryMinMove_m = 0.005; ///< a rest/move boundary needs the move side to leave the rest by this
    int releaseRefineAfter = 20;      ///< the hand's rest at the place is searched up to this many samples after the coarse release
    /// Placement cues (robust mode; false = the robust estimator without them, for comparisons): a part
    /// detection within handRadius of the hand is the hand labelled as the part, and one at the final place of
    /// another part released earlier in the plan is that part labelled as this one (a ghost, unless this part
    /// starts there): neither is evidence of the part; the part is at its final place once seen there in most
    /// of the samples that follow; the grasp is searched until the hand has left the part's start area; the
    /// release is where the hand arrives closest to the part's final place, so a hover just above the place
    /// is part of the move.
    bool placementCues = true;
    double handRadius_m = 0.03;        ///< the hand's own detections are within ~1 cm of it; a part held in the hand is 5-8 cm from the palm
    double sustainRest_s = 1.0;        ///< the part is at its final place once seen there in at least half of the samples of this long ...
    double sustainMinSeenShare = 0.25; ///< ... or in half of its evidence there, when that is at least this share of the samples
    double placeTolerance_m = 0.005;   ///< the part itself at its initial / final place (not in the hand just above it): this close
    double startAreaLeave_m = 0.05;    ///< the hand has left the start area when this much farther from the initial position than its closest approach
    double closestNoiseMin_m = 0.0015; ///< release: the first sample within max(this, half the hand's rest tolerance) of the closest approach
  };

  Segmenter() = default;
  explicit Segmenter(Options options) : options_(options) {}

  /// Segments the demo. Throws InvalidInputError (nothing is returned) when a
  /// plan object has no track, a trajectory is empty, has a single sample, a
  /// NaN/inf sample or no detection, or the frames of hand and objects differ.
  Segmentation segment(const core::PositionTrajectory& hand, const std::vector<ObjectTrack>& objects,
                       const std::vector<std::string>& planOrder) const;

  const Options& options() const { return options_; }

 private:
  Segmentation segmentThesisPublished(const core::PositionTrajectory& hand, const std::vector<ObjectTrack>& objects,
                                      const std::vector<std::string>& planOrder) const;
  Options options_;
};

}  // namespace srp::motion
