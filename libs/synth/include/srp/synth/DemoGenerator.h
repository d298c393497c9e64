#pragma once
/// \file DemoGenerator.h
/// \brief `srp synth-demo`: a scene and an instruction's plan in, a synthetic
/// RGB-D demonstration (MRPT rawlog) and its ground truth out.

#include <cstdint>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "srp/core/CameraIntrinsics.h"
#include "srp/core/ObjectCatalogue.h"
#include "srp/core/Scene.h"
#include "srp/synth/DemoGroundTruth.h"
#include "srp/synth/DemoTimeline.h"
#include "srp/synth/HandModel.h"
#include "srp/synth/HeadSway.h"
#include "srp/synth/SensorModel.h"

namespace srp::synth {

/// A depth camera of its own, as RealSense-like sensors have: depth is rendered
/// by this camera (its size, intrinsics and pose; the same sensor model) and
/// colour by the scene camera.
struct SynthDepthCamera {
  srp::core::CameraIntrinsics intrinsics;
  srp::core::Pose3 X_colour_depth = srp::core::Pose3::Identity();  ///< the depth camera in the colour camera's frame
};

struct SynthDemoOptions {
  DemoOptions demo;
  SensorModel::Options sensor;
  HandModel::Options hand;
  /// The light's colour: the scene's ambient and diffuse intensities scaled per channel (linear RGB;
  /// white (1, 1, 1) by default; e.g. (1, 0.9, 0.78) a warm lamp seen by a camera balanced for daylight).
  Eigen::Vector3d lightRgb = Eigen::Vector3d::Ones();
  int width_px = 0;   ///< 0: the scene camera's; otherwise the intrinsics are scaled
  int height_px = 0;
  double rawlogDepthUnit_m = 1e-4;   ///< depth step stored in the rawlog
  int rawlogCompressionLevel = 1;    ///< libdeflate level 0..12 (RawlogWriter)
  int rawlogEncoderThreads = -1;     ///< threads compressing frames; -1: one per core
  int maxFrames = -1;                ///< stop after this many frames (tests); -1: all
  /// A head-mounted camera: the camera sways about the scene's camera pose (HeadSway.h, seeded by
  /// demo.seed); every frame's camera pose goes into the ground truth (GroundTruthFrame::X_world_camera).
  HeadSway::Options headSway;
  /// Record only the timeline's frames with a part in the hand, renumbered from 0 (times from the
  /// first of them; events' frames mapped onto them): a clip in which the hand holds a part from the
  /// first frame on, as an egocentric recording cut from a longer one. With a plan of one step, one
  /// continuous carry. Throws when the plan carries nothing.
  bool carryOnly = false;
  /// Render the table and resting objects once and only the moving bodies per
  /// frame, composed by depth (same images, several times faster in software).
  bool layeredRendering = true;
  /// When set, the demo is recorded as an unregistered two-camera sensor and
  /// written as an image folder (the `rawlogPath` argument names the folder)
  /// in `srp import`'s layout: color_NNNN.png, depth_NNNN.png (16-bit, depth
  /// camera's size, rawlogDepthUnit_m per unit), cam.json (colour camera,
  /// depthScale), depth_cam.json, depth_M_color.txt (ViSP: p_depth =
  /// depth_M_color p_colour). The ground truth is the colour camera's.
  std::optional<SynthDepthCamera> depthCamera;
  std::string contactSheetPath;      ///< PNG of a few frames (colour + depth) when set
  int contactSheetFrames = 6;
};

/// What a generation produced, with timing. Wall times [s] of the stages
/// overlap (they run on different threads); CPU times [s] add up to the
/// process's CPU time less set-up and ground-truth saving, and do not depend
/// on how busy the machine is.
struct SynthDemoResult {
  std::string rawlogPath, groundTruthPath, contactSheetPath;
  int frameCount = 0;
  double duration_s = 0.0;
  std::uint64_t rawlogBytes = 0;
  double renderTime_s = 0.0;   ///< wall: rendering and composing (MRPT/EGL)
  double sensorTime_s = 0.0;   ///< wall: masks, ground truth, sensor realism
  double writeTime_s = 0.0;    ///< wall: waiting for the rawlog writer (queue full, final drain)
  double totalTime_s = 0.0;    ///< wall: the whole call
  double renderCpuTime_s = 0.0;  ///< CPU: render thread while rendering + llvmpipe's rasteriser threads
  double sensorCpuTime_s = 0.0;  ///< CPU: masks, ground truth, sensor realism
  double writeCpuTime_s = 0.0;   ///< CPU: rawlog conversion, serialisation, compression (encoder threads)
  double processCpuTime_s = 0.0; ///< CPU: the whole process during the call (all threads)
  double meanHandValidDepth = -1.0;    ///< over frames with a visible hand
  double meanObjectValidDepth = -1.0;  ///< over frames with visible parts
};

/// Ground-truth path belonging to a rawlog path: `demo.rawlog` -> `demo.gt.json`.
std::string groundTruthPathFor(const std::string& rawlogPath);

/// Intrinsics scaled to another image size (same field of view).
srp::core::CameraIntrinsics scaleIntrinsics(const srp::core::CameraIntrinsics& K, int width_px, int height_px);

/// Generates the demonstration of `plan` (srp parse --json step format; see
/// PickPlacePlan.h) in `scene`: validates the scene against the catalogue
/// (errors name the field), plans the hand motion (DemoTimeline.h), renders
/// every frame, degrades it (SensorModel.h) and writes `rawlogPath` plus the
/// ground truth next to it. `progress(frame, frameCount)` is called per frame.
SynthDemoResult generateSyntheticDemo(const srp::core::Scene& scene, const srp::core::ObjectCatalogue& catalogue,
                                      const nlohmann::json& plan, const SynthDemoOptions& options,
                                      const std::string& rawlogPath,
                                      const std::function<void(int, int)>& progress = {});

}  // namespace srp::synth
