// The PostgreSQL backend (libpqxx): one connection, statements prepared once
// per SQL text, every value a parameter; transactions are explicit BEGIN /
// COMMIT on a non-transaction, so the DAOs' transaction logic is the same as
// on SQLite.
#include <pqxx/pqxx>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <optional>
#include <vector>

#include "Backend.h"
#include "Schema.h"
#include "srp/core/Error.h"
#include "srp/taskdb/TaskDatabase.h"

namespace srp::taskdb::detail {

namespace {

// pg_advisory_xact_lock key of schema creation and migration ("srp" in ASCII).
constexpr long long kSchemaLockKey = 0x737270;

DbError::Kind kindOf(const std::string& sqlstate) {
  if (sqlstate == "23505") return DbError::Kind::UniqueViolation;
  if (sqlstate.rfind("23", 0) == 0) return DbError::Kind::Constraint;
  if (sqlstate == "25006") return DbError::Kind::ReadOnly;
  if (sqlstate == "42501") return DbError::Kind::Permission;
  if (sqlstate == "40001" || sqlstate == "40P01" || sqlstate == "55P03") return DbError::Kind::Busy;
  if (sqlstate == "53100") return DbError::Kind::Full;
  return DbError::Kind::Other;
}

template <typename F>
auto translated(F&& f) -> decltype(f()) {
  try {
    return f();
  } catch (const pqxx::sql_error& e) {
    throw DbError(e.what(), kindOf(e.sqlstate()));
  } catch (const pqxx::broken_connection& e) {
    throw DbError(std::string("connection to the server lost: ") + e.what(), DbError::Kind::CantOpen);
  } catch (const pqxx::failure& e) {
    throw DbError(e.what(), DbError::Kind::Other);
  }
}

// '?' -> '$n' (in order) and '?N' -> '$N', outside quoted literals and identifiers.
std::string toPostgresPlaceholders(const std::string& sql) {
  std::string out;
  out.reserve(sql.size() + 16);
  int next = 1;
  char quote = 0;
  for (std::size_t i = 0; i < sql.size(); ++i) {
    const char c = sql[i];
    if (quote) {
      if (c == quote) quote = 0;
      out += c;
    } else if (c == '\'' || c == '"') {
      quote = c;
      out += c;
    } else if (c == '?') {
      out += '$';
      if (i + 1 < sql.size() && std::isdigit(static_cast<unsigned char>(sql[i + 1]))) continue;
      out += std::to_string(next++);
    } else {
      out += c;
    }
  }
  return out;
}

std::string doubleText(double v) {
  if (std::isnan(v)) return "NaN";
  if (std::isinf(v)) return v > 0 ? "Infinity" : "-Infinity";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

class PostgresBackend;

class PostgresStatement final : public StatementImpl {
 public:
  PostgresStatement(PostgresBackend& db, std::string name) : db_(db), name_(std::move(name)) {}
  void bindInt(int i, long long v) override { set(i, std::to_string(v)); }
  void bindDouble(int i, double v) override { set(i, doubleText(v)); }
  void bindText(int i, const std::string& v) override { set(i, v); }
  void bindNull(int i) override { slot(i).reset(); }
  void reset() override {
    result_.reset();
    row_ = -1;
  }
  int exec() override;
  bool step() override;
  bool isNull(int c) const override { return field(c).is_null(); }
  // A server's columns are typed: the value is of its column's type (OIDs of
  // int2/int4/int8 and float4/float8/numeric).
  bool isInteger(int c) const override {
    const auto t = type(c);
    return !isNull(c) && (t == 20 || t == 21 || t == 23);
  }
  bool isFloat(int c) const override {
    const auto t = type(c);
    return !isNull(c) && (t == 700 || t == 701 || t == 1700);
  }
  long long getInt(int c) const override {
    const auto f = field(c);
    return f.is_null() ? 0 : std::strtoll(f.c_str(), nullptr, 10);
  }
  double getDouble(int c) const override {
    const auto f = field(c);
    return f.is_null() ? 0.0 : std::strtod(f.c_str(), nullptr);  // also "NaN", "Infinity"
  }
  std::string getText(int c) const override {
    const auto f = field(c);
    return f.is_null() ? std::string() : std::string(f.c_str(), f.size());
  }
  std::string columnName(int c) const override { return result_ ? result_->column_name(static_cast<pqxx::row::size_type>(c)) : ""; }

 private:
  std::optional<std::string>& slot(int i) {
    if (i < 1) throw DbError("parameter index " + std::to_string(i) + " out of range", DbError::Kind::Other);
    if (params_.size() < static_cast<std::size_t>(i)) params_.resize(static_cast<std::size_t>(i));
    return params_[static_cast<std::size_t>(i - 1)];
  }
  void set(int i, std::string v) { slot(i) = std::move(v); }
  pqxx::field field(int c) const {
    if (!result_ || row_ < 0 || row_ >= static_cast<long>(result_->size()))
      throw DbError("no current row", DbError::Kind::Other);
    return (*result_)[static_cast<pqxx::result::size_type>(row_)][static_cast<pqxx::row::size_type>(c)];
  }
  pqxx::result run();
  pqxx::oid type(int c) const {
    if (!result_) throw DbError("no result", DbError::Kind::Other);
    return result_->column_type(static_cast<pqxx::row::size_type>(c));
  }

  PostgresBackend& db_;
  std::string name_;
  std::vector<std::optional<std::string>> params_;
  std::optional<pqxx::result> result_;
  long row_ = -1;
};

class PostgresBackend final : public Backend {
 public:
  PostgresBackend(const std::string& uri, bool readOnly)
      : conn_(uri), tx_(std::make_unique<pqxx::nontransaction>(conn_)), readOnly_(readOnly) {
    if (readOnly_) exec("SET SESSION CHARACTERISTICS AS TRANSACTION READ ONLY");
  }
  bool isPostgres() const override { return true; }
  std::unique_ptr<StatementImpl> prepare(const std::string& sql) override {
    auto it = prepared_.find(sql);
    if (it == prepared_.end()) {
      const std::string name = "s" + std::to_string(prepared_.size());
      translated([&] { conn_.prepare(name, toPostgresPlaceholders(sql)); });
      it = prepared_.emplace(sql, name).first;
    }
    return std::make_unique<PostgresStatement>(*this, it->second);
  }
  void exec(const std::string& sql) override { translated([&] { tx_->exec(sql); }); }
  void beginWrite() override { exec("BEGIN"); }
  void beginRead() override { exec("BEGIN ISOLATION LEVEL REPEATABLE READ"); }
  int schemaVersion() override {
    return translated([&] { return tx_->exec("SELECT Version FROM SrpSchema")[0][0].as<int>(); });
  }
  pqxx::result run(const std::string& name, const std::vector<std::optional<std::string>>& params) {
    std::vector<const char*> values;
    values.reserve(params.size());
    for (const auto& p : params) values.push_back(p ? p->c_str() : nullptr);
    return translated([&] { return tx_->exec_prepared(name, pqxx::prepare::make_dynamic_params(values)); });
  }
  pqxx::nontransaction& tx() { return *tx_; }

 private:
  pqxx::connection conn_;
  std::unique_ptr<pqxx::nontransaction> tx_;
  bool readOnly_;
  std::map<std::string, std::string> prepared_;
};

pqxx::result PostgresStatement::run() { return db_.run(name_, params_); }

int PostgresStatement::exec() {
  const pqxx::result r = run();
  result_.reset();
  row_ = -1;
  return static_cast<int>(r.affected_rows());
}

bool PostgresStatement::step() {
  if (!result_) {
    result_ = run();
    row_ = -1;
  }
  ++row_;
  return row_ < static_cast<long>(result_->size());
}

// Creates the schema on first use or checks and migrates its version, in
// one transaction holding an advisory lock: programs connecting to a new
// database at the same moment take turns.
void prepareSchema(PostgresBackend& db, const std::string& shown, bool readOnly) {
  auto& tx = db.tx();
  if (!readOnly) {
    tx.exec("BEGIN");
    tx.exec("SELECT pg_advisory_xact_lock(" + std::to_string(kSchemaLockKey) + ")");
  }
  try {
    const auto r = tx.exec("SELECT to_regclass('srpschema') IS NOT NULL, to_regclass('taskmodels') IS NOT NULL");
    const bool hasVersion = r[0][0].as<bool>();
    const bool hasTasks = r[0][1].as<bool>();
    if (!hasVersion && hasTasks)
      throw core::FileError(shown, "the database has a TaskModels table but no srp schema version; it belongs to "
                                   "another application. Give another database name in the URI");
    if (!hasVersion) {
      if (readOnly)
        throw core::FileError(shown, "not yet a task database (create it with 'srp db init " + shown + "')");
      tx.exec(createSchemaSql(Dialect::PostgreSQL, kSchemaVersion));
    } else {
      const int version = tx.exec("SELECT Version FROM SrpSchema")[0][0].as<int>();
      if (version > kSchemaVersion)
        throw core::FileError(shown, "task database has schema version " + std::to_string(version) +
                                         ", newer than this build of srp reads (" + std::to_string(kSchemaVersion) +
                                         "); use a newer srp");
      if (version < 1)
        throw core::FileError(shown, "task database has schema version " + std::to_string(version) +
                                         " in table SrpSchema, which srp never writes; the database is damaged");
      if (version < kSchemaVersion && readOnly)
        throw core::FileError(shown, "task database has schema version " + std::to_string(version) +
                                         "; open it once read-write to migrate it to version " +
                                         std::to_string(kSchemaVersion));
      // Migrated in this transaction, under the advisory lock: a program
      // opening it at the same moment waits, then finds the new version.
      for (int v = version; v < kSchemaVersion; ++v) tx.exec(migrationSql(Dialect::PostgreSQL, v));
    }
    if (!readOnly) tx.exec("COMMIT");
  } catch (...) {
    if (!readOnly) {
      try {
        tx.exec("ROLLBACK");
      } catch (...) {
      }
    }
    throw;
  }
}

}  // namespace

bool isServerUri(const std::string& target) {
  return target.rfind("postgresql://", 0) == 0 || target.rfind("postgres://", 0) == 0;
}

std::string redactUri(const std::string& uri) {
  const auto scheme = uri.find("://");
  if (scheme == std::string::npos) return uri;
  std::string out = uri;
  const auto start = scheme + 3;
  const auto hostEnd = out.find_first_of("/?", start);
  const auto at = out.rfind('@', hostEnd == std::string::npos ? std::string::npos : hostEnd);
  if (at != std::string::npos && at >= start) {
    const auto colon = out.find(':', start);
    if (colon != std::string::npos && colon < at) out.erase(colon, at - colon);
  }
  // A password given as a parameter (?password=... or &password=...).
  for (std::size_t p = out.find("password="); p != std::string::npos; p = out.find("password=", p + 1)) {
    if (p == 0 || (out[p - 1] != '?' && out[p - 1] != '&')) continue;
    const auto end = out.find('&', p);
    out.replace(p + 9, (end == std::string::npos ? out.size() : end) - (p + 9), "***");
  }
  return out;
}

std::unique_ptr<Backend> openPostgres(const std::string& uri, const std::string& shown, bool readOnly) {
  std::unique_ptr<PostgresBackend> db;
  try {
    db = std::make_unique<PostgresBackend>(uri, readOnly);
  } catch (const pqxx::broken_connection& e) {
    // libpq's message names host and port, never the password.
    throw core::FileError(shown, std::string("cannot connect to the task database server (") + e.what() +
                                     "); check that the server runs, the URI (postgresql://user@host:port/dbname) "
                                     "and the credentials (PGPASSFILE or PGPASSWORD)");
  } catch (const std::exception& e) {
    throw core::FileError(shown, std::string("cannot connect to the task database server (") + e.what() + ")");
  }
  try {
    prepareSchema(*db, shown, readOnly);
  } catch (const pqxx::sql_error& e) {
    throw core::FileError(shown, std::string("cannot create or check the task schema (") + e.what() +
                                     "); does the user have CREATE permission on the database?");
  }
  return db;
}

}  // namespace srp::taskdb::detail
