#pragma once
/// \file GroundedProductDao.h
/// \brief DAO of table GroundedProducts: object classes grounded in the demonstration.

#include <optional>
#include <vector>

#include "srp/taskdb/Rows.h"
#include "srp/taskdb/TaskDatabase.h"

namespace srp::taskdb {

/// Data access object of table GroundedProducts, rows keyed by (TaskModelId, ClassId, InstanceId);
/// `instanceId` "" is the one instance of a class (schema 1 rows).
/// Each call is one statement; compose several in a ScopedTransaction.
class GroundedProductDao {
 public:
  explicit GroundedProductDao(TaskDatabase& db) : db_(db) {}
  void add(int taskModelId, const GroundedProductRow& row);
  std::optional<GroundedProductRow> get(int taskModelId, int classId, const std::string& instanceId = "") const;
  /// Throws InvalidInputError when the row does not exist.
  void update(int taskModelId, const GroundedProductRow& row);
  /// Returns false when there was no such row.
  bool remove(int taskModelId, int classId, const std::string& instanceId = "");
  /// All rows of a task model, ordered by classId.
  std::vector<GroundedProductRow> list(int taskModelId) const;

 private:
  TaskDatabase& db_;
};

}  // namespace srp::taskdb
