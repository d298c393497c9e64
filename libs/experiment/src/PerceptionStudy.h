#pragma once
/// \file PerceptionStudy.h
/// \brief (private) The perception-heavy part of `srp experiment hand` and
/// `objects`: seeded synthetic demos run through the Environment module once,
/// the per-frame output cached under `<out>/perception/`, so the two
/// experiments (and a rerun) share one perception pass per demo.

#include <Eigen/Core>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "srp/core/ObjectCatalogue.h"
#include "srp/core/Pose.h"
#include "srp/experiment/ExperimentResult.h"
#include "srp/synth/DemoGroundTruth.h"

namespace srp::experiment::detail {

/// How big the study is: demos and frames per demo (the demo's first frames).
struct PerceptionStudySize
{
  int demoCount = 5;
  int framesPerDemo = 200;     ///< 1.5 s hand-free, then instruction 1's first pick & place (the cuboid)
  std::string describe() const;  ///< "5 seeded demos × first 200 frames (640×480, ...)"
};
PerceptionStudySize studySize(const ExperimentOptions& options);

/// A hand detector's output in one frame (camera optical frame, metres).
struct PerceivedHand
{
  bool detected = false;  ///< the detector reported a hand
  bool hasPoint = false;  ///< a 3D palm point (its own depth or depth carried along the pixel's ray)
  Eigen::Vector3d p_camera_palm_m = Eigen::Vector3d::Zero();
};

/// One object box hypothesis: a raw detection, or a refined trajectory sample.
struct PerceivedObject
{
  std::string className;
  double confidence = 0.0;
  core::Pose3 X_camera_object = core::Pose3::Identity();
  bool detected = true;  ///< refined samples: false when carried from another frame
};

/// One demo, perceived. Vectors are per frame (the first `frames` of the demo).
struct PerceivedDemo
{
  unsigned seed = 0;
  int frames = 0;
  synth::DemoGroundTruth groundTruth;            ///< frames cut to `frames`
  std::vector<PerceivedHand> marker;             ///< the module's hand (AprilTag glove), depth holes filled as the module does
  std::vector<PerceivedHand> markerFree;         ///< MarkerFreeHandDetector, the same hole filling
  std::vector<std::vector<PerceivedObject>> raw;      ///< the detector's output per frame, before refinement
  std::vector<std::vector<PerceivedObject>> refined;  ///< per plan object once seen: static fixed, moving carried
  std::map<std::string, bool> isStatic;          ///< the plan's objects of interest
  double perceptionTime_s = 0.0;                 ///< wall time of the perception pass (as cached)
};

/// The study's demos, perceived: read from `<out>/perception/seed-<n>.json`
/// when present and of the same size, else rendered (or taken from the demo
/// cache), perceived and cached. `what` names the caller for progress.
std::vector<PerceivedDemo> perceivedDemos(const ExperimentOptions& options, const std::string& what);

/// The knowledge base the demos were rendered with (the default scene's catalogue).
core::ObjectCatalogue studyCatalogue(const ExperimentOptions& options);

/// Median and given percentile of values (NaN when empty); nearest-rank.
double percentile(std::vector<double> values, double fraction);

}  // namespace srp::experiment::detail
