#pragma once
/// \file PerceivedSceneDao.h
/// \brief DAO of a task model's perceived scene: tables PerceivedScenes (one
/// row), SceneObjects and ObservedClasses (schema 3), read and written together.

#include <optional>

#include "srp/taskdb/Rows.h"
#include "srp/taskdb/TaskDatabase.h"

namespace srp::taskdb {

/// Data access object of the perceived scene of one task model (the three
/// tables are one value, PerceivedScene). Every number is checked on the way
/// in (InvalidInputError naming the object and the field) and on the way out:
/// a row holding a non-finite number, a zero quaternion or an observed class
/// that does not read back is refused with a FileError naming the table, the
/// row and the column. Each call is one or a few statements; compose them in a
/// ScopedTransaction.
class PerceivedSceneDao {
 public:
  explicit PerceivedSceneDao(TaskDatabase& db) : db_(db) {}
  /// Throws InvalidInputError (nothing written by this call's failing
  /// statement) for a non-finite number, a table size that is not positive, or
  /// two objects / classes with one id.
  void add(int taskModelId, const PerceivedScene& scene);
  /// nullopt when the task model stores no perceived scene (programmed before
  /// schema 3, or its demonstration showed no table plane).
  std::optional<PerceivedScene> get(int taskModelId) const;
  /// Returns false when there was no scene.
  bool remove(int taskModelId);

 private:
  TaskDatabase& db_;
};

}  // namespace srp::taskdb
