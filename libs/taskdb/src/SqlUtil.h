#pragma once
// Binding and reading helpers shared by the DAOs (private to taskdb).
#include <SQLiteCpp/SQLiteCpp.h>

#include <climits>
#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <string>

#include "srp/core/Error.h"
#include "srp/core/SafeText.h"

namespace srp::taskdb::detail {

template <typename T>
void bindOptional(SQLite::Statement& st, int index, const std::optional<T>& value) {
  if (value) st.bind(index, *value);
  else st.bind(index);
}

inline std::optional<int> optionalInt(const SQLite::Column& c) {
  return c.isNull() ? std::nullopt : std::optional<int>(c.getInt());
}
inline std::optional<std::string> optionalText(const SQLite::Column& c) {
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
inline RowRef rowRef(const SQLite::Statement& st, const char* table, std::initializer_list<int> indices) {
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
[[noreturn]] inline void badCell(const SQLite::Statement& st, int index, const RowRef& row, const std::string& problem) {
  throw BadCellError("table " + std::string(row.table) + ", row (" + row.key + "), column " +
                     st.getColumnName(index) + ": " + problem +
                     "; the row was not written by srp, or the file is damaged");
}

/// An INTEGER column: stored as an integer, within [lo, hi].
inline int checkedInt(const SQLite::Statement& st, int index, const RowRef& row, std::int64_t lo = INT32_MIN,
                      std::int64_t hi = INT32_MAX) {
  const SQLite::Column c = st.getColumn(index);
  if (!c.isInteger())
    badCell(st, index, row, "not an integer ('" + core::exportSafeText(c.getString(), 40) + "')");
  const std::int64_t v = c.getInt64();
  if (v < lo || v > hi)
    badCell(st, index, row, std::to_string(v) + " is outside [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
  return static_cast<int>(v);
}

/// checkedInt(), or nullopt for NULL.
inline std::optional<int> checkedOptionalInt(const SQLite::Statement& st, int index, const RowRef& row) {
  if (st.getColumn(index).isNull()) return std::nullopt;
  return checkedInt(st, index, row);
}

/// A REAL column: stored as a number (not text, not NULL), finite, within [lo, hi].
inline double checkedReal(const SQLite::Statement& st, int index, const RowRef& row, double lo, double hi) {
  const SQLite::Column c = st.getColumn(index);
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
inline std::optional<double> checkedOptionalReal(const SQLite::Statement& st, int index, const RowRef& row, double lo,
                                                 double hi) {
  if (st.getColumn(index).isNull()) return std::nullopt;
  return checkedReal(st, index, row, lo, hi);
}

/// A JSON text column, parsed; a parse error names the table, row and column.
inline nlohmann::json checkedJson(const SQLite::Statement& st, int index, const RowRef& row) {
  try {
    return nlohmann::json::parse(st.getColumn(index).getString());
  } catch (const nlohmann::json::exception& e) {
    badCell(st, index, row, std::string("not valid JSON (") + e.what() + ")");
  }
}

/// Largest |coordinate| [m] a task model's positions may have.
constexpr double kMaxCoordinate_m = 1000.0;

/// Runs a write statement; throws InvalidInputError(missing) when it changed no row.
inline void execExpectingRow(SQLite::Statement& st, const std::string& missing) {
  if (st.exec() == 0) throw core::InvalidInputError(missing);
}

}  // namespace srp::taskdb::detail
