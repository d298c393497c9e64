#include "srp/taskdb/TaskDatabase.h"

#include <SQLiteCpp/SQLiteCpp.h>
#include <sqlite3.h>

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstring>
#include <thread>
#include <filesystem>
#include <fstream>

#include "Backend.h"
#include "Schema.h"
#include "srp/core/Error.h"

namespace srp::taskdb {

using core::FileError;

namespace {

constexpr int kWalSwitchAttempts = 50;

// SQLite files start with this 16-byte header; checking it first gives a
// clearer message than SQLite's "file is not a database".
void checkHeader(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) return;
  const auto size = std::filesystem::file_size(path, ec);
  if (ec) throw FileError(path, "cannot read task database (" + ec.message() + ")");
  if (size == 0) return;  // an empty file becomes a new database
  std::ifstream in(path, std::ios::binary);
  if (!in) throw FileError(path, "cannot read task database (no read permission? check the file's permissions)");
  char header[16] = {};
  in.read(header, sizeof header);
  if (in.gcount() < static_cast<std::streamsize>(sizeof header) ||
      std::memcmp(header, "SQLite format 3\0", 16) != 0)
    throw FileError(path, "not a task database (no SQLite header; truncated or a different kind of file). "
                          "Restore it from a backup or create a new one with 'srp db init'");
}

// What happened and what to do, from SQLite's error code (not one guess for all).
std::string explain(const SQLite::Exception& e, bool readOnly, int busyTimeout_ms) {
  const std::string what = e.what();
  switch (e.getErrorCode()) {
    case SQLITE_BUSY:
    case SQLITE_LOCKED:
      return "task database is locked by another program (another srp writing to it?) for more than " +
             std::to_string(busyTimeout_ms) + " ms (" + what + "); wait for it to finish and retry";
    case SQLITE_READONLY:
    case SQLITE_PERM:
    case SQLITE_AUTH:
      return std::string("no permission to ") + (readOnly ? "read" : "write") + " the task database (" + what +
             "); check the permissions of the file and its folder" +
             (readOnly ? "" : ", or copy it somewhere writable");
    case SQLITE_CANTOPEN:
      return "cannot open the task database (" + what +
             "); check that the folder exists and that you may read (and, to write, write) the file and its folder";
    case SQLITE_CORRUPT:
    case SQLITE_NOTADB:
      return "task database is corrupt (" + what +
             "); restore it from a backup or create a new one with 'srp db init'";
    case SQLITE_FULL:
    case SQLITE_IOERR:
      return "cannot read or write the task database (" + what + "); is the disk full or failing?";
    default:
      return "cannot open the task database (" + what + ")";
  }
}

std::string tableList(SQLite::Database& db) {
  SQLite::Statement st(db, "SELECT name FROM sqlite_master WHERE type = 'table' AND name NOT LIKE 'sqlite_%' ORDER BY name");
  std::string names;
  int n = 0;
  while (st.executeStep()) {
    if (n++ < 5) names += (names.empty() ? "" : ", ") + st.getColumn(0).getString();
  }
  if (n > 5) names += ", ...";
  return names;
}

bool hasTable(SQLite::Database& db, const char* name) {
  SQLite::Statement st(db, "SELECT 1 FROM sqlite_master WHERE type = 'table' AND name = ?");
  st.bind(1, name);
  return st.executeStep();
}

// Checks what the file holds; returns its schema version. Refuses newer
// schemas and SQLite files of other applications (an empty one is fine).
int checkContents(SQLite::Database& db, const std::string& path) {
  // quick_check reads every page: it catches truncation and corrupt pages
  // before any task model is trusted.
  const std::string check = db.execAndGet("PRAGMA quick_check").getString();
  if (check != "ok")
    throw FileError(path, "task database is corrupt (SQLite quick_check: " + check +
                              "); restore it from a backup or create a new one with 'srp db init'");
  const int version = db.execAndGet("PRAGMA user_version").getInt();
  if (version > kSchemaVersion)
    throw FileError(path, "task database has schema version " + std::to_string(version) +
                              ", newer than this build of srp reads (" + std::to_string(kSchemaVersion) +
                              "); use a newer srp");
  const std::string tables = tableList(db);
  if ((version == 0 && !tables.empty()) || (version > 0 && !hasTable(db, "TaskModels")))
    throw FileError(path, "an SQLite file but not a task database (it has tables " + tables +
                              "); left unchanged. Give a new file name (or an empty file) for a task database");
  return version;
}

// A new file gets the current schema at once; an older one each migration in turn.
void migrate(SQLite::Database& db, int from) {
  if (from == 0) {
    db.exec(detail::createSchemaSql(detail::Dialect::SQLite, kSchemaVersion));
    return;
  }
  for (int v = from; v < kSchemaVersion; ++v) db.exec(detail::migrationSql(detail::Dialect::SQLite, v));
}

// WAL lets readers run while one writer writes. The switch cannot run inside
// a transaction and fails with SQLITE_BUSY while another connection reads,
// so it is retried (it is done once per file; later opens find WAL already).
void switchToWal(SQLite::Database& db) {
  for (int attempt = 0;; ++attempt) {
    try {
      if (db.execAndGet("PRAGMA journal_mode").getString() == "wal") return;
      db.execAndGet("PRAGMA journal_mode = WAL");
      return;
    } catch (const SQLite::Exception& e) {
      const bool busy = e.getErrorCode() == SQLITE_BUSY || e.getErrorCode() == SQLITE_LOCKED;
      if (!busy || attempt + 1 >= kWalSwitchAttempts) throw;
      std::this_thread::sleep_for(std::chrono::milliseconds(20 * (1 + attempt % 5)));
    }
  }
}

// Read-only access to a WAL database needs its -shm file; in a folder we may
// not write to (and without a -wal left by a writer) SQLite can only read the
// file as immutable, which is right there: nobody can be writing to it.
bool needsImmutable(const std::string& path) {
  std::error_code ec;
  const auto folder = std::filesystem::absolute(path, ec).parent_path();
  if (ec) return false;
  if (std::filesystem::exists(path + "-wal", ec)) return false;
  return ::access(folder.c_str(), W_OK) != 0;
}

std::string uriOf(const std::string& path) {
  std::string uri = "file:";
  for (const char c : std::filesystem::absolute(path).string()) {
    if (c == '?' || c == '#' || c == '%') {
      char buf[4];
      std::snprintf(buf, sizeof buf, "%%%02X", static_cast<unsigned char>(c));
      uri += buf;
    } else {
      uri += c;
    }
  }
  return uri + "?immutable=1";
}

}  // namespace

TaskDatabase::TaskDatabase(std::string path, std::unique_ptr<detail::Backend> backend, int busyTimeout_ms)
    : path_(std::move(path)), busyTimeout_ms_(busyTimeout_ms), backend_(std::move(backend)) {}
TaskDatabase::TaskDatabase(TaskDatabase&&) noexcept = default;
TaskDatabase& TaskDatabase::operator=(TaskDatabase&&) noexcept = default;
TaskDatabase::~TaskDatabase() = default;

bool TaskDatabase::isServerUri(const std::string& target) { return detail::isServerUri(target); }

std::string TaskDatabase::displayName(const std::string& target) {
  return isServerUri(target) ? detail::redactUri(target) : target;
}

bool TaskDatabase::isPostgres() const { return backend_->isPostgres(); }

TaskDatabase TaskDatabase::open(const std::string& path, Mode mode, int busyTimeout_ms) {
  if (path.empty()) throw core::InvalidInputError("task database path is empty (give one with --db FILE)");
  const bool readOnly = mode == Mode::ReadOnly;
  if (isServerUri(path)) {
    std::string shown = displayName(path);
    auto backend = detail::openPostgres(path, shown, readOnly);
    return TaskDatabase(std::move(shown), std::move(backend), busyTimeout_ms);
  }
  if (readOnly && !std::filesystem::exists(path))
    throw FileError(path, "task database not found (create one with 'srp db init' or 'srp program')");
  checkHeader(path);
  std::unique_ptr<SQLite::Database> db;
  try {
    if (readOnly) {
      // Read-only: SQLITE_OPEN_READONLY, no journal-mode switch, no migration.
      if (needsImmutable(path))
        db = std::make_unique<SQLite::Database>(uriOf(path), SQLite::OPEN_READONLY | SQLite::OPEN_URI, busyTimeout_ms);
      else
        db = std::make_unique<SQLite::Database>(path, SQLite::OPEN_READONLY, busyTimeout_ms);
      const int version = checkContents(*db, path);
      if (version < kSchemaVersion)
        throw FileError(path, version == 0 ? std::string("an empty file, not yet a task database (create one with 'srp db init')")
                                           : "task database has schema version " + std::to_string(version) +
                                                 "; open it once read-write to migrate it to version " +
                                                 std::to_string(kSchemaVersion));
      db->exec("PRAGMA foreign_keys = ON");
      return TaskDatabase(path, detail::makeSqliteBackend(std::move(db)), busyTimeout_ms);
    }
    db = std::make_unique<SQLite::Database>(path, SQLite::OPEN_READWRITE | SQLite::OPEN_CREATE, busyTimeout_ms);
    {
      // Checking and creating/migrating the schema in one IMMEDIATE
      // transaction: two programs opening a new file at once take turns (the
      // second waits up to the busy timeout, then finds the schema there).
      SQLite::Transaction tx(*db, SQLite::TransactionBehavior::IMMEDIATE);
      const int version = checkContents(*db, path);
      if (version < kSchemaVersion) migrate(*db, version);
      tx.commit();
    }
    switchToWal(*db);
    db->exec("PRAGMA foreign_keys = ON");
    db->exec("PRAGMA synchronous = NORMAL");
    // A demo's task model (~100k rows, a few MB) stays in memory until it commits.
    db->exec("PRAGMA cache_size = -65536");
  } catch (const SQLite::Exception& e) {
    throw FileError(path, explain(e, readOnly, busyTimeout_ms));
  }
  return TaskDatabase(path, detail::makeSqliteBackend(std::move(db)), busyTimeout_ms);
}

int TaskDatabase::schemaVersion() const { return backend_->schemaVersion(); }

SQLite::Database& TaskDatabase::connection() {
  if (auto* db = backend_->sqlite()) return *db;
  throw core::InvalidInputError("task database '" + path_ + "' is a PostgreSQL server, not an SQLite file");
}

ScopedTransaction::ScopedTransaction(TaskDatabase& db) : db_(db) {
  // IMMEDIATE takes the write lock now, so a concurrent writer waits here
  // (busy timeout) instead of failing at its first write.
  try {
    db_.backend().beginWrite();
  } catch (const SQLite::Exception& e) {
    throw FileError(db_.path(), explain(e, false, db_.busyTimeout_ms()));
  } catch (const detail::DbError& e) {
    if (e.sqliteCode() == 0) throw FileError(db_.path(), std::string("cannot start a transaction (") + e.what() + ")");
    throw FileError(db_.path(), explain(SQLite::Exception(e.what(), e.sqliteCode()), false, db_.busyTimeout_ms()));
  }
}

ScopedTransaction::~ScopedTransaction() {
  if (!done_) {
    try {
      db_.backend().exec("ROLLBACK");
    } catch (...) {
    }
  }
}

void ScopedTransaction::commit() {
  db_.backend().exec("COMMIT");
  done_ = true;
}

}  // namespace srp::taskdb
