#pragma once
/// \file TargetLocationDao.h
/// \brief DAO of table TargetLocations: target locations (goal indicator + landmark).

#include <optional>
#include <vector>

#include "srp/taskdb/Rows.h"
#include "srp/taskdb/TaskDatabase.h"

namespace srp::taskdb {

/// Data access object of table TargetLocations, rows keyed by (TaskModelId, locationId).
/// Each call is one statement; compose several in a ScopedTransaction.
class TargetLocationDao {
 public:
  explicit TargetLocationDao(TaskDatabase& db) : db_(db) {}
  void add(int taskModelId, const TargetLocationRow& row);
  std::optional<TargetLocationRow> get(int taskModelId, int locationId) const;
  /// Throws InvalidInputError when the row does not exist.
  void update(int taskModelId, const TargetLocationRow& row);
  /// Returns false when there was no such row.
  bool remove(int taskModelId, int locationId);
  /// All rows of a task model, ordered by locationId.
  std::vector<TargetLocationRow> list(int taskModelId) const;

 private:
  TaskDatabase& db_;
};

}  // namespace srp::taskdb
