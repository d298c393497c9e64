#pragma once
/// \file TaskModelTargetObjectDao.h
/// \brief DAO of table TaskModelTargetObjects: the ordered plan of a task model.

#include <vector>

#include "srp/taskdb/Rows.h"
#include "srp/taskdb/TaskDatabase.h"

namespace srp::taskdb {

/// Data access object of table TaskModelTargetObjects, rows keyed by
/// (TaskModelId, StepIndex); StepIndex gives the execution order.
class TaskModelTargetObjectDao {
 public:
  explicit TaskModelTargetObjectDao(TaskDatabase& db) : db_(db) {}
  void add(int taskModelId, int stepIndex, int targetObjectId);
  /// Throws InvalidInputError when the step does not exist.
  void update(int taskModelId, int stepIndex, int targetObjectId);
  bool remove(int taskModelId, int stepIndex);
  /// TargetObjectIds in step order.
  std::vector<int> list(int taskModelId) const;
  /// The planner's query: the target Products in step order.
  std::vector<ProductRow> orderedTargetObjects(int taskModelId) const;

 private:
  TaskDatabase& db_;
};

}  // namespace srp::taskdb
