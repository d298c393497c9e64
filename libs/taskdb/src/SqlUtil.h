#pragma once
// The statement the DAOs use on either backend (mirrors the part of
// SQLiteCpp's Statement they use), and binding/reading helpers (private to
// taskdb).
#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <string>

#include "Backend.h"
#include "srp/core/Error.h"
#include "srp/core/SafeText.h"
#include "srp/taskdb/TaskDatabase.h"

namespace srp::taskdb::detail {

/// One column of the current row.
class Column {
 public:
  Column(const StatementImpl& st, int index) : st_(st), index_(index) {}
  bool isNull() const { return st_.isNull(index_); }
  /// Stored as an integer (SQLite's type of the value; a server's column type).
  bool isInteger() const { return st_.isInteger(index_); }
  bool isFloat() const { return st_.isFloat(index_); }
  int getInt() const { return static_cast<int>(st_.getInt(index_)); }
  std::int64_t getInt64() const { return st_.getInt(index_); }
  double getDouble() const { return st_.getDouble(index_); }
  std::string getString() const { return st_.getText(index_); }
  std::string getName() const { return st_.columnName(index_); }

 private:
  const StatementImpl& st_;
  int index_;
};

/// A statement with '?' placeholders on the database's backend.
class Statement {
 public:
  Statement(TaskDatabase& db, const std::string& sql) : impl_(db.backend().prepare(sql)) {}
  void bind(int i, int v) { impl_->bindInt(i, v); }
  void bind(int i, long long v) { impl_->bindInt(i, v); }
  void bind(int i, bool v) = delete;  // say 0/1
  void bind(int i, double v) { impl_->bindDouble(i, v); }
  void bind(int i, const std::string& v) { impl_->bindText(i, v); }
  void bind(int i, const char* v) { impl_->bindText(i, v); }
  void bind(int i) { impl_->bindNull(i); }
  void reset() { impl_->reset(); }
  int exec() { return impl_->exec(); }
  bool executeStep() { return impl_->step(); }
  Column getColumn(int i) const { return Column(*impl_, i); }
  std::string getColumnName(int i) const { return impl_->columnName(i); }

 private:
  std::unique_ptr<StatementImpl> impl_;
};

template <typename T>
void bindOptional(Statement& st, int index, const std::optional<T>& value) {
  if (value) st.bind(index, *value);
  else st.bind(index);
}

inline std::optional<int> optionalInt(const Column& c) {
  return c.isNull() ? std::nullopt : std::optional<int>(c.getInt());
}
inline std::optional<double> optionalDouble(const Column& c) {
  return c.isNull() ? std::nullopt : std::optional<double>(c.getDouble());
}
inline std::optional<std::string> optionalText(const Column& c) {
  return c.isNull() ? std::nullopt : std::optional<std::string>(c.getString());
}

/// One row of a table, for error messages: the table and the row's key columns
/// ("ClassId 2, TimeId 17"), read as text.
struct RowRef {
  const char* table;
  std::string key;
};

/// "ClassId 2, TimeId 17" from the statement's columns `indices` (their names
/// and values as text, made printable).
inline RowRef rowRef(const Statement& st, const char* table, std::initializer_list<int> indices) {
  RowRef r{table, {}};
  for (int i : indices)
    r.key += (r.key.empty() ? "" : ", ") + std::string(st.getColumnName(i)) + " " +
             core::exportSafeText(st.getColumn(i).getString(), 40);
  return r;
}

/// A value read from a row that srp cannot use; TaskModelStore adds the file's name.
class BadCellError : public core::InvalidInputError {
 public:
  using core::InvalidInputError::InvalidInputError;
};

/// Throws BadCellError naming the table, the row, the column and `problem`.
[[noreturn]] inline void badCell(const Statement& st, int index, const RowRef& row, const std::string& problem) {
  throw BadCellError("table " + std::string(row.table) + ", row (" + row.key + "), column " +
                     st.getColumnName(index) + ": " + problem +
                     "; the row was not written by srp, or the file is damaged");
}

/// An INTEGER column: stored as an integer, within [lo, hi].
inline int checkedInt(const Statement& st, int index, const RowRef& row, std::int64_t lo = INT32_MIN,
                      std::int64_t hi = INT32_MAX) {
  const Column c = st.getColumn(index);
  if (!c.isInteger())
    badCell(st, index, row, "not an integer ('" + core::exportSafeText(c.getString(), 40) + "')");
  const std::int64_t v = c.getInt64();
  if (v < lo || v > hi)
    badCell(st, index, row, std::to_string(v) + " is outside [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
  return static_cast<int>(v);
}

/// checkedInt(), or nullopt for NULL.
inline std::optional<int> checkedOptionalInt(const Statement& st, int index, const RowRef& row) {
  if (st.getColumn(index).isNull()) return std::nullopt;
  return checkedInt(st, index, row);
}

/// A REAL column: stored as a number (not text, not NULL), finite, within [lo, hi].
inline double checkedReal(const Statement& st, int index, const RowRef& row, double lo, double hi) {
  const Column c = st.getColumn(index);
  if (!c.isFloat() && !c.isInteger())
    badCell(st, index, row, "not a number ('" + core::exportSafeText(c.getString(), 40) + "')");
  const double v = c.getDouble();
  if (!std::isfinite(v) || v < lo || v > hi) {
    std::ostringstream o;
    o << v << " is outside [" << lo << ", " << hi << "]";
    badCell(st, index, row, o.str());
  }
  return v;
}

/// checkedReal(), or nullopt for NULL.
inline std::optional<double> checkedOptionalReal(const Statement& st, int index, const RowRef& row, double lo,
                                                 double hi) {
  if (st.getColumn(index).isNull()) return std::nullopt;
  return checkedReal(st, index, row, lo, hi);
}

/// A JSON text column, parsed; a parse error names the table, row and column.
inline nlohmann::json checkedJson(const Statement& st, int index, const RowRef& row) {
  try {
    return nlohmann::json::parse(st.getColumn(index).getString());
  } catch (const nlohmann::json::exception& e) {
    badCell(st, index, row, std::string("not valid JSON (") + e.what() + ")");
  }
}

/// Largest |coordinate| [m] a task model's positions may have.
constexpr double kMaxCoordinate_m = 1000.0;

/// Rows per INSERT statement on a server (17 columns x 1000 rows stays far
/// below PostgreSQL's 65535 parameters of one statement).
constexpr std::size_t kServerBatchRows = 1000;

/// Inserts `count` rows into `table`: `columns` names the `columnCount`
/// columns ("TimeId, X, Y"), bindRow(statement, first, i) binds row i's values
/// at parameters first .. first + columnCount - 1. SQLite runs one prepared
/// statement per row (no round trip to save); a server gets multi-row INSERTs
/// of up to kServerBatchRows rows, one round trip each.
template <typename BindRow>
void insertRows(TaskDatabase& db, const std::string& table, const std::string& columns, int columnCount,
                std::size_t count, BindRow&& bindRow) {
  std::string tuple = "(";
  for (int c = 0; c < columnCount; ++c) tuple += c ? ", ?" : "?";
  tuple += ")";
  const std::string head = "INSERT INTO " + table + " (" + columns + ") VALUES ";
  const std::size_t batch = db.isPostgres() ? kServerBatchRows : 1;
  std::string sql;
  std::size_t sqlRows = 0;
  std::unique_ptr<Statement> st;
  for (std::size_t first = 0; first < count; first += batch) {
    const std::size_t rows = std::min(batch, count - first);
    if (!st || rows != sqlRows) {
      sql = head;
      for (std::size_t r = 0; r < rows; ++r) sql += (r ? ", " : "") + tuple;
      st = std::make_unique<Statement>(db, sql);
      sqlRows = rows;
    }
    st->reset();
    for (std::size_t r = 0; r < rows; ++r) bindRow(*st, 1 + static_cast<int>(r) * columnCount, first + r);
    st->exec();
  }
}

/// Runs a write statement; throws InvalidInputError(missing) when it changed no row.
inline void execExpectingRow(Statement& st, const std::string& missing) {
  if (st.exec() == 0) throw core::InvalidInputError(missing);
}

}  // namespace srp::taskdb::detail
