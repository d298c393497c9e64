#pragma once
/// \file Rows.h
/// \brief Row types of the task database (thesis ch. 7.2, figs. 7.3/7.4,
/// Appendix C), one struct per table. Ids (ObjectId, LocationId, ClassId) are
/// local to a task model and 0-based, as in Appendix C; TimeId is the frame
/// index of the demonstration (1-based in the thesis' tables, any int here).
/// Positions are in the task model's frame (`TaskModelInfo::frame`, normally
/// the camera's optical frame), metres.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "srp/core/CameraIntrinsics.h"
#include "srp/core/ObjectCatalogue.h"
#include "srp/core/Pose.h"
#include "srp/core/SkillType.h"

namespace srp::taskdb {

/// Table Products: every object mention of the instruction.
struct ProductRow {
  int objectId = 0;
  std::string objectName;
  std::optional<int> sourceLocationId;  ///< -> SourceLocations.LocationId
  std::optional<int> targetLocationId;  ///< -> TargetLocations.LocationId
  std::optional<std::string> colour;
  std::optional<int> tokenId;           ///< token index in its sentence
  std::optional<int> sentenceId;
  std::optional<int> classId;           ///< knowledge-base class once grounded
  std::string instanceId;               ///< scene instance once grounded ("cuboid_red"); "" = the class' one instance
  bool operator==(const ProductRow&) const;
};

/// Table SourceLocations: a spatial indicator ("from", "in", "next to") and
/// the landmark object it relates to. The thesis calls the landmark column
/// TrajectorObjectId; it references Products.ObjectId.
struct SourceLocationRow {
  int locationId = 0;
  int trajectorObjectId = 0;
  std::string description;
  bool operator==(const SourceLocationRow&) const;
};

/// Table TargetLocations: a goal indicator ("in", "beside") and its landmark
/// (IndicatorObjectId -> Products.ObjectId).
struct TargetLocationRow {
  int locationId = 0;
  int indicatorObjectId = 0;
  std::string description;
  bool operator==(const TargetLocationRow&) const;
};

/// Table GroundedProducts: the object instances seen in the demonstration and
/// linked to the instruction, keyed by (ClassId, InstanceId) since schema 2.
struct GroundedProductRow {
  int classId = 0;
  std::string objectName;
  std::optional<int> sourceLocationId;
  std::optional<int> targetLocationId;
  std::optional<std::string> colour;
  /// Which instance of the class (the scene's object id, e.g. "cuboid_red");
  /// "" = the one instance of its class (every schema-1 row).
  std::string instanceId;
  bool operator==(const GroundedProductRow&) const;
};

/// Table ProductPose (normalised: one table keyed by TaskModelId, ClassId,
/// InstanceId, TimeId instead of the thesis' table per object): the object's
/// pose in one frame and the skill it is in.
struct ProductPoseRow {
  int classId = 0;
  int timeId = 0;
  Eigen::Vector3d p_m = Eigen::Vector3d::Zero();
  Eigen::Quaterniond q = Eigen::Quaterniond::Identity();  ///< orientation in the task model's frame
  bool reach = false, grasp = false, move = false, release = false;
  bool detected = true;     ///< false: carried forward, not seen in this frame
  std::optional<double> confidence;
  std::string instanceId;   ///< instance of the class ("" = its one instance)
  /// Yaw [rad] about the frame's z axis (the thesis' Rz column).
  double yaw_rad() const;
  bool operator==(const ProductPoseRow&) const;
};

/// Table HandPositions: the palm centre per frame.
struct HandPositionRow {
  int timeId = 0;
  Eigen::Vector3d p_m = Eigen::Vector3d::Zero();
  bool detected = true;  ///< false: carried forward, not seen in this frame
  bool operator==(const HandPositionRow&) const;
};

/// Table Skills: one learned skill of one grounded object (Reach, Grasp, Move,
/// Release), its frame range in the demonstration and its parameters (for
/// Reach/Move the DMP, serialised by the motion module; for Grasp/Release the
/// pre/post poses). `parameters` is stored as JSON text, doubles round-trip exactly.
struct SkillRow {
  int classId = 0;
  core::SkillType skill = core::SkillType::Reach;
  int startTimeId = 0;
  int endTimeId = 0;
  nlohmann::json parameters = nlohmann::json::object();
  std::string instanceId;  ///< instance of the class ("" = its one instance)
  bool operator==(const SkillRow&) const;
};

/// Table SceneObjects: one object of the scene a demonstration showed, where it
/// stood when the demonstration began.
struct SceneObjectRow {
  std::string objectId;     ///< unique in the scene: the instance id, else the class name ("cuboid_red", "toy")
  int classId = 0;          ///< a catalogue class, or an ObservedClasses row of the same task model
  std::string className;    ///< that class' name
  core::Pose3 X_table_object = core::Pose3::Identity();  ///< the class' object frame in the scene's table frame
  std::optional<std::string> colour;   ///< colour word of the instance; nullopt = its class'
  std::optional<Eigen::Vector3d> rgb;  ///< linear RGB [0, 1] of the instance; nullopt = its class'
};

/// The scene a demonstration was perceived in (tables PerceivedScenes,
/// SceneObjects, ObservedClasses, schema 3), so that the task can be executed
/// in the scene of its own demonstration. Frame `table`: the perceived support
/// plane, origin at the centre of the table rectangle `tableSize_m` that holds
/// every object with a margin, z up (towards the camera's side of the plane), x
/// along the camera's x axis projected on the plane; metres.
struct PerceivedScene {
  std::string catalogue;    ///< the knowledge base the catalogue classes are named in (path given to srp program)
  Eigen::Vector2d tableSize_m = Eigen::Vector2d(1.2, 0.8);
  core::Pose3 X_table_camera = core::Pose3::Identity();  ///< the camera's optical frame when the demonstration began
  std::vector<SceneObjectRow> objects;
  /// Classes seen in the demonstration without a CAD file (ObjectClass::observed,
  /// shape "hull" or "open_box"), stored whole: they live in this task model.
  std::vector<core::ObjectClass> observedClasses;
};

/// Table TaskModels: one programmed task (name + version), with what a reader
/// needs to interpret the other tables (frame, frame rate, camera).
struct TaskModelInfo {
  int id = 0;               ///< assigned by the database
  std::string name;
  int version = 1;          ///< re-programming a name makes version + 1
  std::string createdUtc;   ///< ISO 8601, set by the database when empty
  std::string instruction;
  std::string frame = "camera";
  double frameRate_hz = 30.0;
  std::optional<core::CameraIntrinsics> intrinsics;
  std::optional<core::Pose3> X_base_camera;
};

}  // namespace srp::taskdb
