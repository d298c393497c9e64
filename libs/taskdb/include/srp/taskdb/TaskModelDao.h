#pragma once
/// \file TaskModelDao.h
/// \brief DAO of table TaskModels.

#include <optional>
#include <vector>

#include "srp/taskdb/Rows.h"
#include "srp/taskdb/TaskDatabase.h"

namespace srp::taskdb {

/// Data access object of table TaskModels. Deleting a task model deletes all
/// its rows in every other table (ON DELETE CASCADE).
class TaskModelDao {
 public:
  explicit TaskModelDao(TaskDatabase& db) : db_(db) {}
  /// Inserts and returns the new TaskModelId (info.id is ignored; an empty
  /// createdUtc is set to now).
  int add(const TaskModelInfo& info);
  std::optional<TaskModelInfo> get(int taskModelId) const;
  void update(const TaskModelInfo& info);
  bool remove(int taskModelId);
  /// All task models, by id.
  std::vector<TaskModelInfo> list() const;
  /// 1 + the highest version stored under this name (1 when new).
  int nextVersion(const std::string& name) const;
  /// The latest version stored under a name.
  std::optional<TaskModelInfo> latestByName(const std::string& name) const;

 private:
  TaskDatabase& db_;
};

}  // namespace srp::taskdb
