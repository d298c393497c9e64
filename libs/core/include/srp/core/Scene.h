#pragma once
/// \file Scene.h
/// \brief A work-cell scene: table, camera, robot base and object placements.
/// Read by the synthetic-demo generator (to render), the execution module (as
/// the current scene) and the experiment apps.
///
/// Frames: `world` is the table frame (origin at the centre of the table top,
/// z up, metres). `X_world_camera` is the camera's optical frame (x right, y
/// down, z forward) in world; `X_world_base` the robot base (ROS base_link) in
/// world; each object's `X_world_object` its class' object frame (centre of
/// the bottom face, z up; see ObjectCatalogue.h). The camera-to-base transform
/// is always derived from these, never hard-coded:
/// X_base_camera = X_world_base^-1 * X_world_camera.
///
/// \code{.json}
/// {"schema_version": 1, "name": "thesis-default", "seed": 1,
///  "catalogue": "../../datasets/kb/catalogue.json",
///  "table": {"size_m": [1.2, 0.8], "rgb": [0.76, 0.7, 0.6]},
///  "camera": {"intrinsics": {"fx": 607.2, "fy": 607.2, "cx": 319.5, "cy": 239.5, "width": 640, "height": 480},
///             "fps": 30, "X_world_camera": {"translation": [0, 0.05, 0.85], "quaternion": [0, 1, 0, 0]}},
///  "robot": {"X_world_base": {"translation": [0, -0.38, 0], "quaternion": [0.7071068, 0, 0, 0.7071068]}},
///  "lighting": {"ambient": 0.45, "diffuse": 0.7, "direction": [0.3, 0.2, -1.0]},
///  "objects": [{"id": "blue_box", "class": "blue box", "X_world_object": {...}}, ...]}
/// \endcode
/// Optional fields: name, seed, catalogue (default: the bundled one), table.rgb,
/// lighting, and per object "color" and "rgb". Relative paths resolve against the
/// scene file's folder.
///
/// Instances: a scene may hold several objects of one class (ids "cuboid_red",
/// "cuboid_blue"); the catalogue gives the class' default colour (colour word
/// `color_name` and `rgb`), an object may override it with
/// `"color": "blue"` (the colour word instructions use; its rgb then comes from
/// `rgbOfColourName` unless `"rgb": [r, g, b]` is given too) and/or `"rgb"`.
///
/// Observed classes: a scene perceived in a demonstration (`srp program` writes
/// one) may hold parts and containers that no catalogue file knows, seen without
/// a CAD file. It carries their full definitions (ObjectClass::observed, shape
/// "hull" or "open_box"; ObjectClassJson.h) in `"observed_classes": [...]`, and
/// its objects name them by class like catalogue classes.

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "srp/core/CameraIntrinsics.h"
#include "srp/core/ObjectCatalogue.h"
#include "srp/core/Pose.h"

namespace srp::core {

/// One object instance placed in the scene.
struct SceneObject {
  std::string id;         ///< unique in the scene, e.g. "cuboid" or "cuboid_2"
  std::string className;  ///< catalogue class name
  Pose3 X_world_object = Pose3::Identity();
  std::string colour;                   ///< colour word of this instance; "" = the class' colour
  std::optional<Eigen::Vector3d> rgb;  ///< linear RGB in [0, 1]; nullopt = from `colour` or the class
};

/// The colour word of an instance: its own, else its class' (`colourName`, may be "").
std::string instanceColour(const SceneObject& object, const ObjectClass& cls);
/// The rendering colour of an instance: its "rgb", else the rgb of its own colour
/// word, else its class' rgb.
Eigen::Vector3d instanceRgb(const SceneObject& object, const ObjectClass& cls);
/// Linear RGB of a basic colour word (red, green, blue, yellow, orange, purple,
/// pink, brown, black, white, gray/grey, cyan); nullopt for any other word.
std::optional<Eigen::Vector3d> rgbOfColourName(const std::string& colour);
/// The basic colour word whose rgb is nearest to `rgb` (Euclidean in linear RGB),
/// "" when none is within `maxDistance`: names the colour of an instance whose
/// class gives no colour word (the catalogue's red cuboid is "red").
std::string nearestColourName(const Eigen::Vector3d& rgb, double maxDistance = 0.25);

struct SceneLighting {
  double ambient = 0.45;
  double diffuse = 0.7;
  Eigen::Vector3d direction_world = Eigen::Vector3d(0.3, 0.2, -1.0);
};

/// A whole scene. `validate` checks it against a catalogue.
struct Scene {
  std::string name = "scene";
  int seed = 0;
  std::string cataloguePath;  ///< resolved absolute path
  Eigen::Vector2d tableSize_m = Eigen::Vector2d(1.2, 0.8);
  Eigen::Vector3d tableRgb = Eigen::Vector3d(0.76, 0.7, 0.6);
  CameraIntrinsics intrinsics;
  double fps = 30.0;
  Pose3 X_world_camera = Pose3::Identity();
  Pose3 X_world_base = Pose3::Identity();
  SceneLighting lighting;
  std::vector<SceneObject> objects;
  /// Classes seen in a demonstration without a CAD file, carried by the scene
  /// itself (JSON "observed_classes"); empty for a scene of catalogue classes.
  std::vector<ObjectClass> observedClasses;

  Pose3 X_base_camera() const { return X_world_base.inverse() * X_world_camera; }
  const SceneObject* findObject(const std::string& id) const;

  /// Parses a scene file; errors name the file and the missing/bad field.
  static Scene load(const std::string& path);
  static Scene fromJson(const nlohmann::json& j, const std::string& context,
                        const std::string& baseFolder);
  nlohmann::json toJson() const;
  /// `catalogue` plus this scene's observed classes: what its objects' class
  /// names are looked up in. Throws InvalidInputError naming an observed class
  /// whose name or class_id the catalogue already uses.
  ObjectCatalogue withObservedClasses(const ObjectCatalogue& catalogue) const;
  /// Throws InvalidInputError naming the object/field when an object's class is
  /// unknown (to the catalogue and the scene's observed classes), an id repeats, an object's footprint lies outside the table, or
  /// an object's "color" is no known colour word and it gives no "rgb".
  void validate(const ObjectCatalogue& catalogue) const;
};

}  // namespace srp::core
