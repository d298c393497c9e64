#pragma once
/// \file HandPositionDao.h
/// \brief DAO of table HandPositions: the palm centre per frame.

#include <optional>
#include <vector>

#include "srp/taskdb/Rows.h"
#include "srp/taskdb/TaskDatabase.h"

namespace srp::taskdb {

/// Data access object of table HandPositions, rows keyed by (TaskModelId, TimeId).
class HandPositionDao {
 public:
  explicit HandPositionDao(TaskDatabase& db) : db_(db) {}
  void add(int taskModelId, const HandPositionRow& row);
  /// Bulk insert with one prepared statement (call inside a transaction for speed).
  void addMany(int taskModelId, const std::vector<HandPositionRow>& rows);
  std::optional<HandPositionRow> get(int taskModelId, int timeId) const;
  void update(int taskModelId, const HandPositionRow& row);
  bool remove(int taskModelId, int timeId);
  /// Rows with firstTimeId <= TimeId <= lastTimeId, in time order.
  std::vector<HandPositionRow> inFrameRange(int taskModelId, int firstTimeId, int lastTimeId) const;
  std::vector<HandPositionRow> list(int taskModelId) const;

 private:
  TaskDatabase& db_;
};

}  // namespace srp::taskdb
