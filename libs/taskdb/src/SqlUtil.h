#pragma once
// The statement the DAOs use on either backend, and binding/reading helpers
// (private to taskdb). Mirrors the part of SQLiteCpp's Statement they use.
#include <memory>
#include <optional>
#include <string>

#include "Backend.h"
#include "srp/core/Error.h"
#include "srp/taskdb/TaskDatabase.h"

namespace srp::taskdb::detail {

class Statement;

/// One column of the current row.
class Column {
 public:
  Column(const StatementImpl& st, int index) : st_(st), index_(index) {}
  bool isNull() const { return st_.isNull(index_); }
  int getInt() const { return static_cast<int>(st_.getInt(index_)); }
  long long getInt64() const { return st_.getInt(index_); }
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

/// Runs a write statement; throws InvalidInputError(missing) when it changed no row.
inline void execExpectingRow(Statement& st, const std::string& missing) {
  if (st.exec() == 0) throw core::InvalidInputError(missing);
}

}  // namespace srp::taskdb::detail
