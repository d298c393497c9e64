#pragma once
/// \file SourceLocationDao.h
/// \brief DAO of table SourceLocations: source locations (spatial indicator + landmark).

#include <optional>
#include <vector>

#include "srp/taskdb/Rows.h"
#include "srp/taskdb/TaskDatabase.h"

namespace srp::taskdb {

/// Data access object of table SourceLocations, rows keyed by (TaskModelId, locationId).
/// Each call is one statement; compose several in a ScopedTransaction.
class SourceLocationDao {
 public:
  explicit SourceLocationDao(TaskDatabase& db) : db_(db) {}
  void add(int taskModelId, const SourceLocationRow& row);
  std::optional<SourceLocationRow> get(int taskModelId, int locationId) const;
  /// Throws InvalidInputError when the row does not exist.
  void update(int taskModelId, const SourceLocationRow& row);
  /// Returns false when there was no such row.
  bool remove(int taskModelId, int locationId);
  /// All rows of a task model, ordered by locationId.
  std::vector<SourceLocationRow> list(int taskModelId) const;

 private:
  TaskDatabase& db_;
};

}  // namespace srp::taskdb
