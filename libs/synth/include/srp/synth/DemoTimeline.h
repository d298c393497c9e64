#pragma once
/// \file DemoTimeline.h
/// \brief The choreography of a synthetic one-hand demonstration: hand and
/// object poses per frame, before any rendering.

#include <Eigen/Core>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "srp/core/ObjectCatalogue.h"
#include "srp/core/Pose.h"
#include "srp/core/Scene.h"
#include "srp/synth/HandModel.h"
#include "srp/synth/PickPlacePlan.h"

namespace srp::synth {

/// How the demonstrator behaves and what the seed randomises.
struct DemoOptions {
  std::uint32_t seed = 1;
  /// Randomise by seed: part placements inside their source container, camera
  /// pose jitter (±5 mm, ±0.5°), lighting and colours (±10 %), demonstrator
  /// speed (±15 %), target spots (±3 mm). Off: the scene as given, nominal speed.
  bool randomise = true;
  double speedFactor = 1.0;       ///< > 1 moves faster (durations divided by it)
  double idleStart_s = 1.5;       ///< no hand in view at the start
  double idleEnd_s = 1.5;         ///< no hand in view at the end
  double tremorAmplitude_m = 8e-4;  ///< physiological tremor (8-12 Hz) during motions
  /// Where the demonstrator stands: the horizontal direction (world x, y)
  /// from the table point the camera looks at towards them; the hand rests
  /// out of view that way and the forearm points back to them. Zero: away
  /// from the robot base through the camera's foot (a camera above the
  /// demonstrator's side of the table). Set it for a camera beside the table
  /// or at the demonstrator's head.
  Eigen::Vector2d demonstratorSide_world = Eigen::Vector2d::Zero();
};

/// State of the demonstration at one frame. Poses in the world (table) frame.
struct FrameState {
  int index = 0;
  double t_s = 0.0;
  srp::core::Pose3 X_world_hand = srp::core::Pose3::Identity();  ///< palm centre, see HandModel.h
  double grip = 0.0;           ///< finger closure in [0, 1]
  std::string phase = "idle";  ///< idle, reach, grasp, move, release, retract
  int step = -1;               ///< plan step (0-based) the frame belongs to, -1 when idle
  int carriedObject = -1;      ///< index into scene.objects of the object held, -1 none
  std::vector<srp::core::Pose3> X_world_objects;  ///< per scene object (scene order)
};

/// What happened to one moved object. Frames are indices into the timeline.
struct ObjectEvent {
  std::string objectId;
  int step = 0;
  int graspFrame = 0;    ///< first frame the object moves rigidly with the hand
  int releaseFrame = 0;  ///< last frame it does (the hand opens after it)
  std::string sourceId, targetId, referenceId;
  srp::core::Pose3 X_world_object_start = srp::core::Pose3::Identity();
  srp::core::Pose3 X_world_object_end = srp::core::Pose3::Identity();
  srp::core::Pose3 X_hand_object = srp::core::Pose3::Identity();  ///< while carried
};

/// A planned demonstration: the (randomised) scene it happens in, the colours
/// to render each object with, and the per-frame states at scene.fps.
struct DemoTimeline {
  srp::core::Scene scene;  ///< with randomised placements, camera pose and lighting
  std::map<std::string, Eigen::Vector3d> objectRgb;  ///< by object id
  std::vector<PickPlaceStep> steps;
  std::vector<FrameState> frames;
  std::vector<ObjectEvent> events;
  double speedFactor = 1.0;  ///< the one used (after randomisation)
  double duration_s() const { return frames.empty() ? 0.0 : frames.back().t_s; }
};

/// Plans the demonstration of `steps` in `scene`: the hand waits outside the
/// view, then per step reaches (minimum-jerk, slowing down on the final
/// descent), pauses to grasp, lifts, carries the object rigidly, lowers it to
/// a free spot in the target container (beside the reference object when
/// given), pauses to release and lifts; finally it leaves the view.
/// Throws InvalidInputError naming the step when no free spot fits.
DemoTimeline planDemonstration(const srp::core::Scene& scene, const srp::core::ObjectCatalogue& catalogue,
                               const std::vector<PickPlaceStep>& steps, const HandModel& hand,
                               const DemoOptions& options);

/// Minimum-jerk profile s(τ) = 10τ³ − 15τ⁴ + 6τ⁵ for τ in [0, 1] (clamped).
double minimumJerk(double tau);

}  // namespace srp::synth
