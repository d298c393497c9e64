#pragma once
/// \file ProductDao.h
/// \brief DAO of table Products: the object mentions of an instruction.

#include <optional>
#include <vector>

#include "srp/taskdb/Rows.h"
#include "srp/taskdb/TaskDatabase.h"

namespace srp::taskdb {

/// Data access object of table Products, rows keyed by (TaskModelId, objectId).
/// Each call is one statement; compose several in a ScopedTransaction.
class ProductDao {
 public:
  explicit ProductDao(TaskDatabase& db) : db_(db) {}
  void add(int taskModelId, const ProductRow& row);
  std::optional<ProductRow> get(int taskModelId, int objectId) const;
  /// Throws InvalidInputError when the row does not exist.
  void update(int taskModelId, const ProductRow& row);
  /// Returns false when there was no such row.
  bool remove(int taskModelId, int objectId);
  /// All rows of a task model, ordered by objectId.
  std::vector<ProductRow> list(int taskModelId) const;

 private:
  TaskDatabase& db_;
};

}  // namespace srp::taskdb
