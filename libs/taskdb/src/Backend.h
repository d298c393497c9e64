#pragma once
// The two storage engines behind TaskDatabase (private to taskdb): SQLite
// (SQLiteCpp, an embedded file) and PostgreSQL (libpqxx, a shared server).
// The DAOs write their SQL once, with '?' / '?N' placeholders; the PostgreSQL
// backend rewrites them to '$N'. Every value is bound, never spliced into SQL.
#include <memory>
#include <stdexcept>
#include <string>

namespace SQLite {
class Database;
}

namespace srp::taskdb::detail {

/// An error from either engine, classified so callers need not know which.
class DbError : public std::runtime_error {
 public:
  enum class Kind { Busy, ReadOnly, Permission, CantOpen, Corrupt, Full, UniqueViolation, Constraint, Other };
  DbError(const std::string& what, Kind kind, int sqliteCode = 0)
      : std::runtime_error(what), kind_(kind), sqliteCode_(sqliteCode) {}
  Kind kind() const { return kind_; }
  int sqliteCode() const { return sqliteCode_; }

 private:
  Kind kind_;
  int sqliteCode_;
};

/// One prepared statement of a backend: 1-based parameters, 0-based columns.
class StatementImpl {
 public:
  virtual ~StatementImpl() = default;
  virtual void bindInt(int index, long long value) = 0;
  virtual void bindDouble(int index, double value) = 0;
  virtual void bindText(int index, const std::string& value) = 0;
  virtual void bindNull(int index) = 0;
  /// Clears the result so the statement can run again with new bindings.
  virtual void reset() = 0;
  /// Runs a statement without rows; returns the number of rows changed.
  virtual int exec() = 0;
  /// Runs the statement on the first call; steps to the next row; false at the end.
  virtual bool step() = 0;
  virtual bool isNull(int column) const = 0;
  virtual bool isInteger(int column) const = 0;
  virtual bool isFloat(int column) const = 0;
  virtual long long getInt(int column) const = 0;
  virtual double getDouble(int column) const = 0;
  virtual std::string getText(int column) const = 0;
  virtual std::string columnName(int column) const = 0;
};

/// A connection of one backend.
class Backend {
 public:
  virtual ~Backend() = default;
  virtual bool isPostgres() const = 0;
  virtual std::unique_ptr<StatementImpl> prepare(const std::string& sql) = 0;
  virtual void exec(const std::string& sql) = 0;
  /// Starts a write transaction (SQLite: takes the write lock now).
  virtual void beginWrite() = 0;
  /// Starts a read transaction that sees one snapshot.
  virtual void beginRead() = 0;
  virtual int schemaVersion() = 0;
  /// The SQLite connection, or nullptr for PostgreSQL.
  virtual SQLite::Database* sqlite() { return nullptr; }
};

std::unique_ptr<Backend> makeSqliteBackend(std::unique_ptr<SQLite::Database> db);

/// Connects to a PostgreSQL server (uri: postgresql://user@host:port/dbname),
/// creates the schema on first use (one transaction under an advisory lock)
/// or checks its version. `shown` is the URI without credentials, for messages.
std::unique_ptr<Backend> openPostgres(const std::string& uri, const std::string& shown, bool readOnly);

/// The URI without a password (in the user part or as a parameter).
std::string redactUri(const std::string& uri);
bool isServerUri(const std::string& target);

}  // namespace srp::taskdb::detail
