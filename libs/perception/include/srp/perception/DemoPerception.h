#pragma once
/// \file DemoPerception.h
/// \brief The Environment module end to end: a demo's RGB-D frames -> the
/// hand trajectory and every object of interest's pose per frame, in the
/// camera optical frame (metres, radians, seconds).

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "srp/core/ObjectCatalogue.h"
#include "srp/core/PositionTrajectory.h"
#include "srp/core/Scene.h"
#include "srp/perception/CameraMotionEstimator.h"
#include "srp/perception/MarkerFreeHandDetector.h"
#include "srp/perception/MarkerHandDetector.h"
#include "srp/perception/ModelBasedTracker.h"
#include "srp/perception/ObjectDetector.h"
#include "srp/perception/ObjectDiscovery.h"
#include "srp/perception/ObjectTracker.h"
#include "srp/perception/ObjectTrajectory.h"
#include "srp/rawlog/RgbdFrame.h"

namespace srp::perception {

/// An object the task plan names, and whether the instruction moves it.
/// Static objects (containers, landmarks) are fixed at their most confident
/// detection; moving ones are tracked frame by frame.
///
/// Instances: a scene may hold several parts of one class (two cuboids, red
/// and blue). Each is a PlanObject of its own with an `instanceId` (unique in
/// the plan, e.g. the scene's "cuboid_red") and, when known, its colour
/// `rgb` (linear RGB [0, 1], the scene's or the catalogue's). Each instance
/// is detected and tracked with a model of its own: the class's shape with
/// the instance's colour, so that the colour of a segment (its mean against
/// `rgb`, ObjectDetector::colourScore) is evidence for which instance it is,
/// alongside the last pose (tracking, "parts move only in the hand"). An
/// empty `instanceId` is the class's one instance, tracked as before instances
/// existed (its catalogue colour).
struct PlanObject {
  std::string className;
  bool isStatic = false;
  std::string instanceId;              ///< "" = the class's one instance
  std::optional<Eigen::Vector3d> rgb;  ///< instance colour; nullopt = the class's
  /// The key of this object in the tracker and the detector: its instance
  /// id, else its class name.
  const std::string& key() const { return instanceId.empty() ? className : instanceId; }
};

struct PerceptionOptions {
  /// None: objects only (a recording without a demonstrator, e.g. to check
  /// object poses); finish() then does not require a hand. Auto: the preview
  /// pass (DemoPerceiver::preview) looks for the glove's tag (`marker`) in
  /// every autoHandProbeStride-th frame; seen in autoHandMinTagFrames of them,
  /// the marker hand, else the marker-free one (which learnt from the same
  /// preview). Without a preview pass, Auto is the marker hand.
  enum class HandMethod { Marker, MarkerFree, None, Auto };
  HandMethod hand = HandMethod::Marker;
  MarkerHandDetector::Options marker;  ///< defaults: srp synth-demo's glove (tag 0, 5 cm, palm 13.6 mm under the tag)
  MarkerFreeHandDetector::Options markerFree;
  /// A palm depth that differs from the last measured one by more than this
  /// speed x the time since [m/s] is carried like a depth hole (the depth
  /// behind a blurred hand: 0.9 m off in 4 frames of HRT1 task3); 0: off.
  double maxPalmDepthSpeed_mps = 2.0;
  int autoHandProbeStride = 5;
  int autoHandMinTagFrames = 2;
  ObjectDetector::Options objects;
  /// Frame-to-frame reuse (static classes are taken from `plan`).
  ObjectTracker::Options tracking;
  /// Objects of interest (from the task plan); empty = every catalogue class, all
  /// moving. Keys (PlanObject::key) must be unique and differ from the other
  /// plan objects' class names.
  std::vector<PlanObject> plan;
  /// Objects of the task that the catalogue does not know (or knows without
  /// a mesh or a shape): found in the demonstration (ObjectDiscovery), their
  /// classes and trajectories added to the result. Their names must differ
  /// from the plan's keys.
  std::vector<UnknownObject> unknownObjects;
  ObjectDiscovery::Options discovery;
  /// Fit the support plane once on the first frame (the camera is fixed).
  bool fixedSupportPlane = true;
  /// A hand-held or moving camera: the support plane is fitted in every
  /// frame and every frame is detected on its own (ObjectDetector::detect; no
  /// reuse of unchanged segments, no "parts move only in the hand" rule, no
  /// rest consolidation, all of which assume a fixed camera).
  bool movingCamera = false;
  /// A camera not declared moving is watched (CameraMotionEstimator, depth
  /// ICP against the first frame): from the frame its pose leaves the first
  /// frame's by more than cameraMotion's thresholds on, the recording is
  /// perceived as with movingCamera, and the result says so
  /// (PerceptionResult::cameraMoved). false: the camera is taken as fixed
  /// whatever it does (`srp perceive --fixed-camera`).
  bool detectCameraMotion = true;
  CameraMotionEstimator::Options cameraMotion;
  /// Moving camera: the support plane's normal is looked for within this of
  /// the previous frame's [rad] (a hand-held camera turns a few degrees
  /// between frames; a wall or board is 45-90 deg away).
  double maxPlaneTurnPerFrame_rad = 15.0 * 3.14159265358979323846 / 180.0;
  /// A part moves only in the hand: consecutive detections of a moving class
  /// within restRadius_m of their period's median are one rest, reported
  /// with the rest's median yaw (modulo the model's symmetry; positions stay
  /// per detection). A single detection of a part half hidden by the
  /// reaching hand then neither turns the rest nor is carried through the grasp.
  /// How a moving part is followed from frame to frame once detected:
  /// Fitter: detected in every frame (ObjectDetector / ObjectPoseFitter);
  /// Mbt: ViSP's model-based tracker (ModelBasedTracker) from the first
  /// detection on, back to detection when it is lost or the depth disagrees
  /// with its pose (coverage below mbtMinCoverage, mbtDepthShiftTolerance_m),
  /// the tracked pose kept when the colour supports it better than the
  /// detection (mbtCompareBeforeReinit);
  /// Auto: Mbt with a moving camera, Fitter with a fixed one (chosen on the
  /// real cube's development frames, see the perception README).
  enum class ObjectTracking { Fitter, Mbt, Auto };
  ObjectTracking objectTracking = ObjectTracking::Auto;
  ModelBasedTracker::Options mbt;
  /// Mbt: share of the model's camera-facing surface samples with depth
  /// evidence that the depth must confirm at the tracked pose (see
  /// ObjectPoseFitter::coverage); below it the tracker is lost.
  double mbtMinCoverage = 0.5;
  /// Mbt: the coverage check also tries the tracked pose moved along its
  /// viewing ray by up to this much (1 mm steps) and keeps the best: a depth
  /// image that disagrees with the colour by a few millimetres along the ray
  /// (the real RealSense cube: 3.9 mm) then does not lose a tracker that
  /// follows the colour. 5 mm since session 8 (chosen on the real cube's
  /// development frames 0-29 and their stress variants: no false loss, equal
  /// or closer to both references; 0 = the pose as tracked, session 7).
  double mbtDepthShiftTolerance_m = 0.005;
  /// Mbt: when the coverage check fails on a pose ViSP still tracks, that
  /// pose and the frame's detection are compared on the colour image
  /// (ModelBasedTracker::edgeDistance_px) and the tracker goes on from the
  /// one the image supports better; the detection must be better by
  /// mbtReinitEdgeMargin_px [px] to replace the tracked pose. Without a
  /// detection the part is lost. false: the detection always re-initialises
  /// (session 7, which took a blurred frame's detection 13.7 mm off).
  /// The tracked pose is weighed only when the depth still confirms at least
  /// mbtKeepMinCoverage [share] of it. 0 (always weighed): on the development
  /// stress variants 0.3 let a depth image out of step with the colour
  /// (coverage 0.10) re-initialise the tracker 3 cm off, and 0 changed
  /// nothing with a hand hiding the part (its hidden edges are no evidence).
  bool mbtCompareBeforeReinit = true;
  double mbtReinitEdgeMargin_px = 0.0;
  double mbtKeepMinCoverage = 0.0;
  /// Mbt: gate on the pose that would (re)initialise the tracker (a
  /// detection, or the tracked pose the colour comparison kept). The model's
  /// camera-facing surface samples inside the image, at that pose: a sample
  /// is *hidden* when the measured depth there is nearer than the model by
  /// more than mbtOccluderMargin_m [m], *supported* when within the fitter's
  /// inlier tolerance. The pose is not used -- the frame reports the part not
  /// detected and the tracker waits for the next detection -- when fewer
  /// than mbtMinDetectionVisibleFraction [share] of the samples are not
  /// hidden, at that pose or at the part's last confirmed place (the last
  /// pose the depth confirmed or the tracker started from), or when fewer
  /// than mbtMinDetectionSupport [share] are supported at that pose (a part
  /// behind a passing hand: the detector may report another object or the
  /// few visible pixels of the part, which the tracker would then carry).
  /// 0.5 / 0: chosen on the real cube's development frames 0-29 and their
  /// stress variants (0.3-0.7 all stop the hidden frames' wrong detection;
  /// a support minimum drops the right pose when depth and colour are out of
  /// step). 0 / 0 = no gate (session 8 before the gate).
  double mbtOccluderMargin_m = 0.02;
  double mbtMinDetectionVisibleFraction = 0.5;
  double mbtMinDetectionSupport = 0.0;
  bool consolidateRests = true;
  double restRadius_m = 0.005;
  /// Called with each frame's index and its detections before any refinement
  /// (the detector alone, e.g. for `srp experiment objects`); may be empty
  /// (also when the model-based tracker followed every moving class: no detection ran).
  std::function<void(int, const std::vector<ObjectDetection>&)> onFrameDetections;
};

struct PerceptionResult {
  /// Palm centre per frame; valid = the hand was detected (depth holes are
  /// filled by carrying the last valid depth forward along the pixel's ray).
  core::PositionTrajectory hand{"camera"};
  std::vector<ObjectTrajectory> objects;
  core::CameraIntrinsics intrinsics;
  int frames = 0;
  int handDetected = 0;        ///< frames with a hand detection
  int handDepthCarried = 0;    ///< of those, frames whose depth was carried forward
  /// The support plane's frame (PlaneFit.h: z = the plane normal towards the
  /// camera, x = the camera x axis on the plane) in the first frame's camera
  /// (fitSupportPlane on the first frame); nullopt when no plane was found.
  /// Relations such as "on" or "left of" between perceived objects are read
  /// in it (programming's grounding); with a moving camera, on the samples of
  /// inFirstCameraFrame().
  std::optional<core::Pose3> X_camera_table;
  /// The camera moved: declared (PerceptionOptions::movingCamera) or noticed
  /// (detectCameraMotion). Each sample stays in the camera of its own frame;
  /// inFirstCameraFrame() brings them into one frame.
  bool cameraMoved = false;
  /// The first frame (frame number) perceived as with a moving camera; -1 when none.
  int cameraMovedAtFrame = -1;
  /// Per frame (the hand's sample order): its camera in the first frame's
  /// camera, from CameraMotionEstimator (frames between the checks of a still
  /// camera keep the last checked pose); empty when the camera was neither
  /// watched nor declared moving.
  std::vector<core::Pose3> X_camera0_camera;
  /// The largest distance [m] and turn [rad] of the camera from its pose in the first frame.
  double cameraTravel_m = 0.0, cameraTurn_rad = 0.0;
  /// The hand detector used (Auto resolved to Marker or MarkerFree).
  PerceptionOptions::HandMethod handMethod = PerceptionOptions::HandMethod::Marker;
  /// The classes of PerceptionOptions::unknownObjects as found in the
  /// demonstration (shape "hull" for a part, "open_box" for a container,
  /// observed = true, ids after the catalogue's); their trajectories are in
  /// `objects` under the same names. A run-local catalogue is the knowledge
  /// base plus these (withObservedClasses).
  std::vector<core::ObjectClass> observedClasses;
  /// What the discovery decided, one line per object (for reports).
  std::vector<std::string> discoveryNotes;
};

/// `catalogue` with `observed` appended (the classes a demonstration showed;
/// their names and ids must be free in it). Throws InvalidInputError naming a
/// taken name or id.
core::ObjectCatalogue withObservedClasses(const core::ObjectCatalogue& catalogue,
                                          const std::vector<core::ObjectClass>& observed);

/// `result` with every hand and object sample in the first frame's camera
/// (each frame's X_camera0_camera applied; the frame in which
/// X_camera_table holds); `result` itself when the camera did not move.
PerceptionResult inFirstCameraFrame(const PerceptionResult& result);

/// The module as a stream: add() frames in time order (each is checked
/// against the first), then finish(). Keeps per frame only the detections, so
/// long demos need little memory. Models are built once, at construction.
class DemoPerceiver {
 public:
  DemoPerceiver(const core::ObjectCatalogue& catalogue, const PerceptionOptions& options);
  ~DemoPerceiver();
  DemoPerceiver(const DemoPerceiver&) = delete;
  DemoPerceiver& operator=(const DemoPerceiver&) = delete;

  /// Optional pre-pass: every frame of the recording, in order, before the
  /// first add() (the marker-free hand learns its background and skin colour
  /// from the whole recording; see HandDetector::preview; HandMethod::Auto
  /// decides between the hands).
  void preview(const rawlog::RgbdFrame& frame);
  /// True when the hand method learns from (or is decided in) a preview pass.
  bool wantsPreview() const;
  /// True when the preview pass may stop early (Auto found the glove's tag).
  bool previewComplete() const;
  /// Throws InvalidInputError when the frame lacks depth or colour, or its
  /// size or intrinsics differ from the first frame's.
  void add(const rawlog::RgbdFrame& frame);
  int framesAdded() const;
  /// Refinement and the result. Throws InvalidInputError for zero frames or
  /// when the hand was never detected.
  PerceptionResult finish() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// `plan` with the scene's instances: a class of the plan that the scene
/// holds several times is replaced by one PlanObject per instance (the
/// scene's id, its colour: core::instanceRgb; static as the class was), in
/// scene order; a class the scene holds once or not at all stays as it is
/// (its one instance, as before instances existed).
std::vector<PlanObject> withSceneInstances(const std::vector<PlanObject>& plan, const core::Scene& scene,
                                           const core::ObjectCatalogue& catalogue);

/// Runs the module on frames (in time order; previewed first for the
/// marker-free hand). Throws InvalidInputError when
/// there are no frames, a frame lacks depth or colour, the sizes or
/// intrinsics change between frames, or the hand is never detected.
/// `progress(frameIndex, frameCount)` is called after each frame when given
/// (frameCount -1 when unknown, as for a rawlog read as a stream).
PerceptionResult perceiveFrames(const std::vector<rawlog::RgbdFrame>& frames, const core::ObjectCatalogue& catalogue,
                                const PerceptionOptions& options, const std::function<void(int, int)>& progress = {});

/// Writes the `srp segment` CSV: frame,hand_x,hand_y,hand_z,<name>_x,<name>_y,
/// <name>_z,<name>_rz,... (camera frame, metres, radians; <name> = the
/// object's key, i.e. its instance id when it has one, else its class name;
/// names with spaces written with '_'; rz = yaw of the object about the camera's z axis). A
/// sample not detected in its frame is written as exact zeros (0,0,0 and rz 0,
/// motion::TrajectoryTable's "not detected"): the hand when it was not seen,
/// an object when it was not detected in that frame (carried in the hand,
/// hidden, not yet seen; also a static object between its detections), so
/// `srp segment --trajectories` sees the same samples as the ProductPose
/// rows' `detected` flag. Atomic (temporary file renamed).
void writeSegmentCsv(const PerceptionResult& result, const std::string& path);

/// Rotation of an object about the camera z axis [rad] (the `_rz` column).
double cameraYaw(const core::Pose3& X_camera_object);

}  // namespace srp::perception
