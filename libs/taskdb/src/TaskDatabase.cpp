#include "srp/taskdb/TaskDatabase.h"

#include <SQLiteCpp/SQLiteCpp.h>

#include <cstring>
#include <filesystem>
#include <fstream>

#include "Schema.h"
#include "srp/core/Error.h"

namespace srp::taskdb {

using core::FileError;

namespace {

constexpr int kBusyTimeout_ms = 10000;

// SQLite files start with this 16-byte header; checking it first gives a
// clearer message than SQLite's "file is not a database".
void checkHeader(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) return;
  const auto size = std::filesystem::file_size(path, ec);
  if (ec) throw FileError(path, "cannot read task database (" + ec.message() + ")");
  if (size == 0) return;  // an empty file becomes a new database
  std::ifstream in(path, std::ios::binary);
  char header[16] = {};
  in.read(header, sizeof header);
  if (in.gcount() < static_cast<std::streamsize>(sizeof header) ||
      std::memcmp(header, "SQLite format 3\0", 16) != 0)
    throw FileError(path, "not a task database (no SQLite header; truncated or a different kind of file). "
                          "Restore it from a backup or create a new one with 'srp db init'");
}

void migrate(SQLite::Database& db, const std::string& path, int from) {
  const auto& steps = detail::migrations();
  SQLite::Transaction tx(db);
  for (int v = from; v < static_cast<int>(steps.size()); ++v) db.exec(steps[static_cast<std::size_t>(v)]);
  db.exec("PRAGMA user_version = " + std::to_string(steps.size()));
  tx.commit();
  (void)path;
}

}  // namespace

TaskDatabase::TaskDatabase(std::string path, std::unique_ptr<SQLite::Database> db)
    : path_(std::move(path)), db_(std::move(db)) {}
TaskDatabase::TaskDatabase(TaskDatabase&&) noexcept = default;
TaskDatabase& TaskDatabase::operator=(TaskDatabase&&) noexcept = default;
TaskDatabase::~TaskDatabase() = default;

TaskDatabase TaskDatabase::open(const std::string& path, Mode mode) {
  if (path.empty()) throw core::InvalidInputError("task database path is empty (give one with --db FILE)");
  checkHeader(path);
  if (mode == Mode::ReadOnly && !std::filesystem::exists(path))
    throw FileError(path, "task database not found (create one with 'srp db init' or 'srp program')");
  std::unique_ptr<SQLite::Database> db;
  try {
    const int flags = mode == Mode::ReadOnly ? SQLite::OPEN_READONLY : (SQLite::OPEN_READWRITE | SQLite::OPEN_CREATE);
    db = std::make_unique<SQLite::Database>(path, flags, kBusyTimeout_ms);
    // quick_check reads every page: it catches truncation and corrupt pages
    // before any task model is trusted.
    const std::string check = db->execAndGet("PRAGMA quick_check").getString();
    if (check != "ok") throw FileError(path, "task database is corrupt (SQLite quick_check: " + check + ")");
    const int version = db->execAndGet("PRAGMA user_version").getInt();
    if (version > kSchemaVersion)
      throw FileError(path, "task database has schema version " + std::to_string(version) +
                                ", newer than this build of srp reads (" + std::to_string(kSchemaVersion) +
                                "); use a newer srp");
    db->exec("PRAGMA foreign_keys = ON");
    if (mode == Mode::ReadWrite) {
      db->execAndGet("PRAGMA journal_mode = WAL");
      db->exec("PRAGMA synchronous = NORMAL");
      // A demo's task model (~100k rows, a few MB) stays in memory until it commits.
      db->exec("PRAGMA cache_size = -65536");
      if (version < kSchemaVersion) migrate(*db, path, version);
    } else if (version < kSchemaVersion) {
      throw FileError(path, "task database has schema version " + std::to_string(version) +
                                "; open it once read-write to migrate it to version " + std::to_string(kSchemaVersion));
    }
  } catch (const SQLite::Exception& e) {
    throw FileError(path, std::string("cannot open task database: ") + e.what() +
                              " (a truncated or corrupt file? restore it or create a new one with 'srp db init')");
  }
  return TaskDatabase(path, std::move(db));
}

int TaskDatabase::schemaVersion() const { return db_->execAndGet("PRAGMA user_version").getInt(); }

SQLite::Database& TaskDatabase::connection() { return *db_; }

ScopedTransaction::ScopedTransaction(TaskDatabase& db) : db_(db) {
  // IMMEDIATE takes the write lock now, so a concurrent writer waits here
  // (busy timeout) instead of failing at its first write.
  db_.connection().exec("BEGIN IMMEDIATE");
}

ScopedTransaction::~ScopedTransaction() {
  if (!done_) {
    try {
      db_.connection().exec("ROLLBACK");
    } catch (...) {
    }
  }
}

void ScopedTransaction::commit() {
  db_.connection().exec("COMMIT");
  done_ = true;
}

}  // namespace srp::taskdb
