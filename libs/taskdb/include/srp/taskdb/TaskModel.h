#pragma once
/// \file TaskModel.h
/// \brief The unified task model (thesis ch. 7.2): everything one programming
/// run stores, as plain values. TaskModelStore writes and reads it atomically.

#include <optional>
#include <vector>

#include "srp/taskdb/Rows.h"

namespace srp::taskdb {

/// All rows of one task model. `targetObjectIds` is the ordered plan
/// (TaskModelTargetObjects): ObjectIds of the Products to move, in order.
struct TaskModel {
  TaskModelInfo info;
  std::vector<ProductRow> products;
  std::vector<SourceLocationRow> sourceLocations;
  std::vector<TargetLocationRow> targetLocations;
  std::vector<int> targetObjectIds;
  std::vector<GroundedProductRow> groundedProducts;
  std::vector<ProductPoseRow> productPoses;
  std::vector<HandPositionRow> handPositions;
  std::vector<SkillRow> skills;
  /// The scene the demonstration was perceived in (schema 3); nullopt for a
  /// task model programmed before, or whose demonstration showed no table plane.
  std::optional<PerceivedScene> scene;

  const ProductRow* findProduct(int objectId) const;
  const GroundedProductRow* findGrounded(int classId) const;
};

/// JSON form of a task model (`srp db show --json`, example files). Round-trips
/// exactly: toJson(fromJson(j)) == j for files written by toJson. The perceived
/// scene is written as "perceived_scene" only when the model has one.
nlohmann::json toJson(const TaskModel& model);
/// Throws InvalidInputError naming the field when the JSON is not a task model.
TaskModel taskModelFromJson(const nlohmann::json& j, const std::string& context);

nlohmann::json toJson(const TaskModelInfo& info);
nlohmann::json toJson(const PerceivedScene& scene);
/// Throws InvalidInputError naming the field (every number checked finite).
PerceivedScene perceivedSceneFromJson(const nlohmann::json& j, const std::string& context);

}  // namespace srp::taskdb
