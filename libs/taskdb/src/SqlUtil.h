#pragma once
// Binding and reading helpers shared by the DAOs (private to taskdb).
#include <SQLiteCpp/SQLiteCpp.h>

#include <optional>
#include <string>

#include "srp/core/Error.h"

namespace srp::taskdb::detail {

template <typename T>
void bindOptional(SQLite::Statement& st, int index, const std::optional<T>& value) {
  if (value) st.bind(index, *value);
  else st.bind(index);
}

inline std::optional<int> optionalInt(const SQLite::Column& c) {
  return c.isNull() ? std::nullopt : std::optional<int>(c.getInt());
}
inline std::optional<double> optionalDouble(const SQLite::Column& c) {
  return c.isNull() ? std::nullopt : std::optional<double>(c.getDouble());
}
inline std::optional<std::string> optionalText(const SQLite::Column& c) {
  return c.isNull() ? std::nullopt : std::optional<std::string>(c.getString());
}

/// Runs a write statement; throws InvalidInputError(missing) when it changed no row.
inline void execExpectingRow(SQLite::Statement& st, const std::string& missing) {
  if (st.exec() == 0) throw core::InvalidInputError(missing);
}

}  // namespace srp::taskdb::detail
