#pragma once
/// \file TaskDatabase.h
/// \brief A connection to a task database: an SQLite file (WAL mode, foreign keys
/// on) or a PostgreSQL server (a postgresql:// URI).

#include <memory>
#include <string>

#include "srp/taskdb/SchemaVersion.h"

namespace SQLite {
class Database;
}

namespace srp::taskdb {
namespace detail {
class Backend;
}

/// One connection to a task database.
///
/// The target is an SQLite file path (the default) or a PostgreSQL URI
/// `postgresql://user@host:port/dbname` (also `postgres://`). For a server the
/// schema is created on first use inside one transaction holding an advisory
/// lock (two programs connecting to a new database take turns), with the same
/// tables, columns and schema version as a file; read-only connections run
/// every transaction READ ONLY. Credentials come from the URI, `PGPASSFILE`
/// or libpq's environment (`PGPASSWORD`, ...) and are never shown: path()
/// and every message show the URI without its password.
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
  /// True for a `postgresql://` or `postgres://` URI (a server), false for a file path.
  static bool isServerUri(const std::string& target);
  /// The target as it may be shown: a URI loses its password.
  static std::string displayName(const std::string& target);

  TaskDatabase(TaskDatabase&&) noexcept;
  TaskDatabase& operator=(TaskDatabase&&) noexcept;
  ~TaskDatabase();

  /// The file path, or the server URI without credentials.
  const std::string& path() const { return path_; }
  bool isPostgres() const;
  int schemaVersion() const;
  int busyTimeout_ms() const { return busyTimeout_ms_; }

  /// The SQLite connection (tests, file maintenance); throws InvalidInputError on a server.
  SQLite::Database& connection();
  /// The backend, for the DAOs (SQLiteCpp and libpqxx stay out of the public API).
  detail::Backend& backend() { return *backend_; }

 private:
  TaskDatabase(std::string path, std::unique_ptr<detail::Backend> backend, int busyTimeout_ms);
  std::string path_;
  int busyTimeout_ms_ = kDefaultBusyTimeout_ms;
  std::unique_ptr<detail::Backend> backend_;
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
