#pragma once
/// \file DemonstrationScene.h
/// \brief The scene of a task model's own demonstration: the perceived scene
/// `srp program` stores (taskdb::PerceivedScene) as a scene the simulated cell
/// runs in (`srp execute` without `--scene`), with the robot base from a
/// camera-to-robot calibration or, without one, a default placement.
///
/// Frames: world = the perceived table frame (taskdb::PerceivedScene: origin at
/// the centre of the table rectangle, z up). With the extrinsics X_base_camera
/// (`srp calibrate extrinsics` / `hand-eye`, or stored with the task model),
/// X_world_base = X_world_camera * X_base_camera^-1. Without them, the base
/// stands on the table top at the edge opposite the camera: on the line from the
/// table centre away from the camera's foot point (the image's bottom edge when
/// the camera looks straight down), `kDefaultBaseInset_m` inside the edge, its x
/// axis towards the table centre. On the thesis' default scene this is exactly
/// its robot base (0, -0.3, 0), yaw 90 deg. With the perceived table's margin
/// (programming::kPerceivedTableMargin_m, 0.4 m) the base stands 0.3 m from the
/// nearest object's footprint, as the thesis cell's does (0.335 m).
///
/// \code
///   const auto placement = srp::execution::RobotPlacement::of(*model.scene, extrinsics);
///   const srp::core::Scene scene = srp::execution::demonstrationScene(model, placement);
/// \endcode

#include <optional>
#include <string>

#include "srp/core/Scene.h"
#include "srp/taskdb/TaskModel.h"

namespace srp::execution {

/// How far inside the table edge the default robot base stands [m] (as in the
/// thesis cell, sim/scenes/default.json).
inline constexpr double kDefaultBaseInset_m = 0.1;

/// Where the robot base of a demonstration's scene comes from.
struct RobotPlacement {
  srp::core::Pose3 X_world_base = srp::core::Pose3::Identity();
  bool isDefault = true;    ///< no calibration: the default placement
  std::string description;  ///< for reports: "from extrinsics calib/extrinsics.json" or the default's wording

  /// From a calibration (X_base_camera) when given, else the default placement;
  /// `source` names the calibration in the description.
  static RobotPlacement of(const taskdb::PerceivedScene& scene, const std::optional<srp::core::Pose3>& X_base_camera,
                           const std::string& source = "");
};

/// The default robot base of a perceived scene (see the file comment).
srp::core::Pose3 defaultRobotBase(const taskdb::PerceivedScene& scene);

/// A perceived scene as a scene: its table, camera pose, objects where they
/// stood when the demonstration began (world = the table frame), its observed
/// classes and the robot base of `placement`; intrinsics and frame rate are left
/// as given in `base`.
srp::core::Scene demonstrationScene(const taskdb::PerceivedScene& scene, const RobotPlacement& placement,
                                    srp::core::Scene base = {});

/// The scene of the task model's own demonstration (the above, with the task
/// model's intrinsics and frame rate). Throws InvalidInputError when the task
/// model stores no perceived scene (programmed by an older srp, or no table
/// plane was seen: give a scene file).
srp::core::Scene demonstrationScene(const taskdb::TaskModel& model, const RobotPlacement& placement);

}  // namespace srp::execution
