#pragma once
/// \file TaskModelStore.h
/// \brief Writes and reads whole task models atomically.

#include <functional>
#include <utility>
#include <vector>

#include "srp/taskdb/TaskDatabase.h"
#include "srp/taskdb/TaskModel.h"

namespace srp::taskdb {

/// Whole task models in and out of a TaskDatabase, each write one transaction:
/// a kill or an exception in the middle leaves the database exactly as it was.
class TaskModelStore {
 public:
  /// Called during write() with (rows written, rows in total); may throw to abort.
  using Progress = std::function<void(std::size_t done, std::size_t total)>;
  /// Called inside write()'s transaction once every row is in, just before
  /// COMMIT, with the new model's id and version; throwing rolls the write
  /// back. For outputs that must exist exactly when the model does (a report).
  using BeforeCommit = std::function<void(int taskModelId, int version)>;

  explicit TaskModelStore(TaskDatabase& db) : db_(db) {}

  /// Writes a new task model and returns its TaskModelId. The version is
  /// 1 + the latest version of the same name (model.info.version is ignored).
  int write(const TaskModel& model, const Progress& progress = {}, const BeforeCommit& beforeCommit = {});
  /// Throws InvalidInputError when there is no such task model.
  TaskModel read(int taskModelId) const;
  std::vector<TaskModelInfo> list() const;
  /// Throws InvalidInputError when there is no such task model.
  void remove(int taskModelId);
  /// Replaces the Skills rows of a task model in one transaction.
  void replaceSkills(int taskModelId, const std::vector<SkillRow>& skills);

 private:
  friend std::vector<std::pair<int, int>> copyTaskModels(TaskDatabase&, TaskDatabase&, const std::vector<int>&);
  /// Inside the caller's transaction: the TaskModels row (a new version, or
  /// the model's own with keepVersion) and every other row; returns (id, version).
  std::pair<int, int> writeRows(const TaskModel& model, bool keepVersion, const Progress& progress);
  int writeChildren(const TaskModel& model, int taskModelId, const Progress& progress);
  TaskModel readUnchecked(int taskModelId) const;
  TaskDatabase& db_;
};

/// Copies task models (all when `ids` is empty) from one task database to
/// another, in either direction between an SQLite file and a server, in one
/// transaction of the destination: every row, with its name, version and
/// creation time (the destination numbers the ids). A name and version
/// already in the destination refuses the whole copy. Returns (source id,
/// destination id) pairs.
std::vector<std::pair<int, int>> copyTaskModels(TaskDatabase& from, TaskDatabase& to, const std::vector<int>& ids = {});

}  // namespace srp::taskdb
