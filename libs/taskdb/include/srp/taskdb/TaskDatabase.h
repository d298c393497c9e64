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
inline constexpr int kSchemaVersion = 3;

/// One connection to a task database.
///
/// ReadWrite creates the file and the schema when missing and migrates older
/// schema versions forward, both inside one `BEGIN IMMEDIATE` transaction, so
/// programs opening a new file at the same moment take turns (each waits up to
/// the busy timeout) instead of failing; then it switches the file to WAL.
/// ReadOnly opens with SQLITE_OPEN_READONLY: nothing is written, the journal
/// mode stays as it is, and a database in a folder the user cannot write to
/// is still readable.
///
/// Both refuse, with a FileError naming the file, what happened and what to
/// do: a file that is not an SQLite database, an SQLite file of another
/// application (tables but no task schema; an empty file is fine), a corrupt
/// file (truncated, malformed pages), a newer schema version than this build,
/// a file locked by another writer for longer than the busy timeout, and
/// missing permissions. Each thread or process opens its own connection;
/// WAL mode lets readers run while one writer writes.
///
/// \code
///   auto db = srp::taskdb::TaskDatabase::open("task.db");
///   srp::taskdb::TaskModelStore store(db);
///   const int id = store.write(model);
/// \endcode
class TaskDatabase {
 public:
  enum class Mode { ReadWrite, ReadOnly };

  /// How long an open or a write waits for another writer's lock by default.
  static constexpr int kDefaultBusyTimeout_ms = 10000;

  static TaskDatabase open(const std::string& path, Mode mode = Mode::ReadWrite,
                           int busyTimeout_ms = kDefaultBusyTimeout_ms);

  TaskDatabase(TaskDatabase&&) noexcept;
  TaskDatabase& operator=(TaskDatabase&&) noexcept;
  ~TaskDatabase();

  const std::string& path() const { return path_; }
  int schemaVersion() const;
  int busyTimeout_ms() const { return busyTimeout_ms_; }

  /// The underlying connection, for the DAOs (SQLiteCpp stays out of the public API).
  SQLite::Database& connection();

 private:
  TaskDatabase(std::string path, std::unique_ptr<SQLite::Database> db, int busyTimeout_ms);
  std::string path_;
  int busyTimeout_ms_ = kDefaultBusyTimeout_ms;
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
