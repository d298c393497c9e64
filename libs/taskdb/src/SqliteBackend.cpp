// The SQLite backend (SQLiteCpp): statements as SQLite prepares them.
#include <SQLiteCpp/SQLiteCpp.h>
#include <sqlite3.h>

#include "Backend.h"

namespace srp::taskdb::detail {

namespace {

DbError::Kind kindOf(int code, int extended) {
  switch (code) {
    case SQLITE_BUSY:
    case SQLITE_LOCKED: return DbError::Kind::Busy;
    case SQLITE_READONLY: return DbError::Kind::ReadOnly;
    case SQLITE_PERM:
    case SQLITE_AUTH: return DbError::Kind::Permission;
    case SQLITE_CANTOPEN: return DbError::Kind::CantOpen;
    case SQLITE_CORRUPT:
    case SQLITE_NOTADB: return DbError::Kind::Corrupt;
    case SQLITE_FULL:
    case SQLITE_IOERR: return DbError::Kind::Full;
    case SQLITE_CONSTRAINT:
      return extended == SQLITE_CONSTRAINT_UNIQUE ? DbError::Kind::UniqueViolation : DbError::Kind::Constraint;
    default: return DbError::Kind::Other;
  }
}

[[noreturn]] void rethrow(const SQLite::Exception& e) {
  throw DbError(e.what(), kindOf(e.getErrorCode(), e.getExtendedErrorCode()), e.getErrorCode());
}

template <typename F>
auto translated(F&& f) -> decltype(f()) {
  try {
    return f();
  } catch (const SQLite::Exception& e) {
    rethrow(e);
  }
}

class SqliteStatement final : public StatementImpl {
 public:
  SqliteStatement(SQLite::Database& db, const std::string& sql)
      : st_(translated([&] { return SQLite::Statement(db, sql); })) {}
  void bindInt(int i, long long v) override { translated([&] { st_.bind(i, static_cast<int64_t>(v)); }); }
  void bindDouble(int i, double v) override { translated([&] { st_.bind(i, v); }); }
  void bindText(int i, const std::string& v) override { translated([&] { st_.bind(i, v); }); }
  void bindNull(int i) override { translated([&] { st_.bind(i); }); }
  void reset() override { translated([&] { st_.reset(); }); }
  int exec() override { return translated([&] { return st_.exec(); }); }
  bool step() override { return translated([&] { return st_.executeStep(); }); }
  bool isNull(int c) const override { return translated([&] { return st_.getColumn(c).isNull(); }); }
  bool isInteger(int c) const override { return translated([&] { return st_.getColumn(c).isInteger(); }); }
  bool isFloat(int c) const override { return translated([&] { return st_.getColumn(c).isFloat(); }); }
  long long getInt(int c) const override { return translated([&] { return st_.getColumn(c).getInt64(); }); }
  double getDouble(int c) const override { return translated([&] { return st_.getColumn(c).getDouble(); }); }
  std::string getText(int c) const override { return translated([&] { return st_.getColumn(c).getString(); }); }
  std::string columnName(int c) const override { return translated([&] { return std::string(st_.getColumnName(c)); }); }

 private:
  mutable SQLite::Statement st_;
};

class SqliteBackend final : public Backend {
 public:
  explicit SqliteBackend(std::unique_ptr<SQLite::Database> db) : db_(std::move(db)) {}
  bool isPostgres() const override { return false; }
  std::unique_ptr<StatementImpl> prepare(const std::string& sql) override {
    return std::make_unique<SqliteStatement>(*db_, sql);
  }
  void exec(const std::string& sql) override { translated([&] { db_->exec(sql); }); }
  // IMMEDIATE takes the write lock now, so a concurrent writer waits here
  // (busy timeout) instead of failing at its first write.
  void beginWrite() override { exec("BEGIN IMMEDIATE"); }
  void beginRead() override { exec("BEGIN"); }
  int schemaVersion() override {
    return translated([&] { return db_->execAndGet("PRAGMA user_version").getInt(); });
  }
  SQLite::Database* sqlite() override { return db_.get(); }

 private:
  std::unique_ptr<SQLite::Database> db_;
};

}  // namespace

std::unique_ptr<Backend> makeSqliteBackend(std::unique_ptr<SQLite::Database> db) {
  return std::make_unique<SqliteBackend>(std::move(db));
}

}  // namespace srp::taskdb::detail
