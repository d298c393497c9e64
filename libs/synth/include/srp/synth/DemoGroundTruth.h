#pragma once
/// \file DemoGroundTruth.h
/// \brief Ground truth of a synthetic demonstration (`<demo>.gt.json`), written
/// by the generator and read by perception, motion and the experiments.

#include <Eigen/Core>
#include <array>
#include <map>
#include <set>
#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>
#include <vector>

#include "srp/core/CameraIntrinsics.h"
#include "srp/core/Pose.h"

namespace srp::synth {

/// Ground truth of one frame. Frames: `world` = table (z up), `camera` =
/// optical frame, `hand` = palm centre (HandModel.h), `tag` = AprilTag frame.
struct GroundTruthFrame {
  int index = 0;                 ///< rawlog frame index (from 0)
  double t_s = 0.0;              ///< time since the first frame [s]
  std::string phase = "idle";    ///< idle, reach, grasp, move, release, retract
  int step = -1;                 ///< plan step (0-based), -1 when idle
  double grip = 0.0;             ///< finger closure [0, 1]
  bool handInView = false;       ///< some hand pixel is visible in the image
  int handPixels = 0;            ///< visible hand pixels (incl. forearm)
  /// A detector could read the tag: the whole plate (black square and white
  /// margin) inside the image, seen within 60 deg of its normal, and no pixel
  /// of it hidden by other geometry in the rendered depth.
  bool tagInView = false;
  double tagVisibleFraction = 0.0;  ///< fraction of the plate's pixels where the plate is the visible surface
  srp::core::Pose3 X_world_hand = srp::core::Pose3::Identity();
  Eigen::Vector3d p_camera_palm_m = Eigen::Vector3d::Zero();  ///< palm centre in the camera frame
  srp::core::Pose3 X_camera_tag = srp::core::Pose3::Identity();
  std::array<Eigen::Vector2d, 4> tagCorners_px{};  ///< TL, TR, BR, BL as the tag is read (may lie outside)
  std::string carriedObject;     ///< id of the object in the hand, empty when none
  /// The camera in this frame when it moves (a head-mounted camera's sway); nullopt: the
  /// recording's DemoGroundTruth::X_world_camera.
  std::optional<srp::core::Pose3> X_world_camera;
  std::map<std::string, srp::core::Pose3> X_world_objects;  ///< every scene object, by id
  /// Ids of the objects the hand hides in part: some visible hand pixel lies
  /// inside the object's projected bounding box. nullopt in ground truth
  /// written before this field existed (occlusion unknown).
  std::optional<std::set<std::string>> handOccludedObjects;
  /// Fraction of valid depth pixels on the visible hand / moved parts; nullopt
  /// when none is visible.
  std::optional<double> handValidDepthFraction, objectsValidDepthFraction;
};

/// An object of the scene: class and where it starts and ends.
struct GroundTruthObject {
  std::string id, className;
  int classId = -1;
  srp::core::Pose3 X_world_object_initial = srp::core::Pose3::Identity();
  srp::core::Pose3 X_world_object_final = srp::core::Pose3::Identity();
};

/// One pick & place of the demonstration.
struct GroundTruthEvent {
  std::string objectId;
  int step = 0;
  int graspFrame = 0;    ///< first frame the object moves rigidly with the hand
  int releaseFrame = 0;  ///< last frame it does
  std::string sourceId, targetId, referenceId;
  srp::core::Pose3 X_hand_object = srp::core::Pose3::Identity();  ///< constant while carried
};

/// The whole ground-truth file.
///
/// \code
///   auto gt = srp::synth::DemoGroundTruth::load("demo.gt.json");
///   for (const auto& e : gt.events) std::cout << e.objectId << " grasped at frame " << e.graspFrame << "\n";
///   Eigen::Vector3d p = gt.frames[100].p_camera_palm_m;
/// \endcode
struct DemoGroundTruth {
  static constexpr int kSchemaVersion = 1;
  std::string sceneName;
  std::string rawlogFile;   ///< the rawlog's file name (same folder)
  std::uint32_t seed = 0;
  double fps = 30.0;
  double speedFactor = 1.0;
  std::string instruction;  ///< when the plan carried one
  srp::core::CameraIntrinsics intrinsics;
  /// The camera; with a moving camera its nominal pose, and each frame's pose in its GroundTruthFrame
  /// (use X_world_camera_at).
  srp::core::Pose3 X_world_camera = srp::core::Pose3::Identity();
  srp::core::Pose3 X_world_base = srp::core::Pose3::Identity();
  std::string tagFamily = "tag36h11";
  int tagId = 0;
  double tagSize_m = 0.05;
  srp::core::Pose3 X_hand_tag = srp::core::Pose3::Identity();
  bool sensorRealism = true;
  std::vector<GroundTruthObject> objects;
  std::vector<GroundTruthEvent> events;
  std::vector<GroundTruthFrame> frames;

  srp::core::Pose3 X_base_camera() const { return X_world_base.inverse() * X_world_camera; }
  /// The camera at frame `index`: the frame's own pose when the camera moves, else X_world_camera;
  /// throws InvalidInputError when `index` is out of range.
  srp::core::Pose3 X_world_camera_at(int index) const;
  /// Whether any frame has a camera pose of its own (a moving camera).
  bool cameraMoves() const;
  /// Pose of object `id` in frame `index`'s camera frame; throws InvalidInputError naming it when absent.
  srp::core::Pose3 X_camera_object(int index, const std::string& id) const;
  const GroundTruthEvent* eventFor(const std::string& objectId) const;

  nlohmann::json toJson() const;
  static DemoGroundTruth fromJson(const nlohmann::json& j, const std::string& context);
  /// Writes atomically; throws FileError naming the path.
  void save(const std::string& path) const;
  /// Reads a ground-truth file; throws FileError/InvalidInputError naming the
  /// file and the field (and refuses a newer schema_version).
  static DemoGroundTruth load(const std::string& path);
};

}  // namespace srp::synth
