#pragma once
/// \file TaskDatabase.h
/// \brief A connection to a task database file (SQLite, WAL mode, foreign keys on).

#include <memory>
#include <string>

namespace SQLite {
class Database;
}

namespace srp::taskdb {

/// The schema version this build reads and writes (`PRAGMA user_version`).
inline constexpr int kSchemaVersion = 1;

/// One connection to a task database. Opening creates the file and the schema
/// when missing, migrates older schema versions forward (in one transaction),
/// and refuses, with a FileError naming the file, a file that is not an
/// SQLite database, is corrupt (truncated, malformed pages) or has a newer
/// schema version than this build. Each thread or process opens its own
/// connection; WAL mode lets readers run while one writer writes.
///
/// \code
///   auto db = srp::taskdb::TaskDatabase::open("task.db");
///   srp::taskdb::TaskModelStore store(db);
///   const int id = store.write(model);
/// \endcode
class TaskDatabase {
 public:
  enum class Mode { ReadWrite, ReadOnly };

  static TaskDatabase open(const std::string& path, Mode mode = Mode::ReadWrite);

  TaskDatabase(TaskDatabase&&) noexcept;
  TaskDatabase& operator=(TaskDatabase&&) noexcept;
  ~TaskDatabase();

  const std::string& path() const { return path_; }
  int schemaVersion() const;

  /// The underlying connection, for the DAOs (SQLiteCpp stays out of the public API).
  SQLite::Database& connection();

 private:
  TaskDatabase(std::string path, std::unique_ptr<SQLite::Database> db);
  std::string path_;
  std::unique_ptr<SQLite::Database> db_;
};

/// RAII transaction: commits on commit(), rolls back in the destructor
/// otherwise (an exception in the middle leaves the database as it was).
class ScopedTransaction {
 public:
  explicit ScopedTransaction(TaskDatabase& db);
  ~ScopedTransaction();
  ScopedTransaction(const ScopedTransaction&) = delete;
  ScopedTransaction& operator=(const ScopedTransaction&) = delete;
  void commit();

 private:
  TaskDatabase& db_;
  bool done_ = false;
};

}  // namespace srp::taskdb
