#pragma once
/// \file ProductPoseDao.h
/// \brief DAO of table ProductPose: object poses per frame with skill flags.

#include <optional>
#include <vector>

#include "srp/taskdb/Rows.h"
#include "srp/taskdb/TaskDatabase.h"

namespace srp::taskdb {

/// Grasp and release frames of one object, from the skill flags.
struct GraspReleaseFrames {
  std::optional<int> graspTimeId;    ///< first frame flagged Grasp
  std::optional<int> releaseTimeId;  ///< first frame flagged Release
};

/// Data access object of table ProductPose, rows keyed by (TaskModelId,
/// ClassId, InstanceId, TimeId); `instanceId` "" is the one instance of a class.
class ProductPoseDao {
 public:
  explicit ProductPoseDao(TaskDatabase& db) : db_(db) {}
  void add(int taskModelId, const ProductPoseRow& row);
  /// Bulk insert with one prepared statement (call inside a transaction for speed).
  void addMany(int taskModelId, const std::vector<ProductPoseRow>& rows);
  std::optional<ProductPoseRow> get(int taskModelId, int classId, int timeId, const std::string& instanceId = "") const;
  void update(int taskModelId, const ProductPoseRow& row);
  bool remove(int taskModelId, int classId, int timeId, const std::string& instanceId = "");
  /// Poses of one class with firstTimeId <= TimeId <= lastTimeId, in time order.
  std::vector<ProductPoseRow> inFrameRange(int taskModelId, int classId, int firstTimeId, int lastTimeId,
                                           const std::string& instanceId = "") const;
  /// Every pose row of a task model, by class then time.
  std::vector<ProductPoseRow> list(int taskModelId) const;
  GraspReleaseFrames graspReleaseFrames(int taskModelId, int classId, const std::string& instanceId = "") const;

 private:
  TaskDatabase& db_;
};

}  // namespace srp::taskdb
