#include "srp/taskdb/HandPositionDao.h"

#include "SqlUtil.h"

namespace srp::taskdb {
using namespace detail;

namespace {
constexpr const char* kSelect = "SELECT TimeId, X, Y, Z, Detected, TaskModelId FROM HandPositions";

HandPositionRow readRow(const Statement& st) {
  const RowRef row = rowRef(st, "HandPositions", {5, 0});
  return {checkedInt(st, 0, row),
          {checkedReal(st, 1, row, -kMaxCoordinate_m, kMaxCoordinate_m),
           checkedReal(st, 2, row, -kMaxCoordinate_m, kMaxCoordinate_m),
           checkedReal(st, 3, row, -kMaxCoordinate_m, kMaxCoordinate_m)},
          checkedInt(st, 4, row, 0, 1) != 0};
}

void checkFinite(const HandPositionRow& r) {
  if (!r.p_m.allFinite())
    throw core::InvalidInputError("hand position at TimeId " + std::to_string(r.timeId) +
                                  " has a non-finite value (NaN/inf)");
}
}  // namespace

void HandPositionDao::add(int tm, const HandPositionRow& r) { addMany(tm, {r}); }

void HandPositionDao::addMany(int tm, const std::vector<HandPositionRow>& rows) {
  for (const auto& r : rows) checkFinite(r);
  insertRows(db_, "HandPositions", "TimeId, TaskModelId, X, Y, Z, Detected", 6, rows.size(),
             [&](Statement& st, int p, std::size_t i) {
               const auto& r = rows[i];
               st.bind(p, r.timeId);
               st.bind(p + 1, tm);
               st.bind(p + 2, r.p_m.x());
               st.bind(p + 3, r.p_m.y());
               st.bind(p + 4, r.p_m.z());
               st.bind(p + 5, r.detected ? 1 : 0);
             });
}

std::optional<HandPositionRow> HandPositionDao::get(int tm, int timeId) const {
  Statement st(db_, std::string(kSelect) + " WHERE TaskModelId = ? AND TimeId = ?");
  st.bind(1, tm);
  st.bind(2, timeId);
  if (!st.executeStep()) return std::nullopt;
  return readRow(st);
}

void HandPositionDao::update(int tm, const HandPositionRow& r) {
  checkFinite(r);
  Statement st(db_,
                       "UPDATE HandPositions SET X = ?, Y = ?, Z = ?, Detected = ? WHERE TaskModelId = ? AND TimeId = ?");
  st.bind(1, r.p_m.x());
  st.bind(2, r.p_m.y());
  st.bind(3, r.p_m.z());
  st.bind(4, r.detected ? 1 : 0);
  st.bind(5, tm);
  st.bind(6, r.timeId);
  execExpectingRow(st, "no hand position at TimeId " + std::to_string(r.timeId) + " in task model " + std::to_string(tm));
}

bool HandPositionDao::remove(int tm, int timeId) {
  Statement st(db_, "DELETE FROM HandPositions WHERE TaskModelId = ? AND TimeId = ?");
  st.bind(1, tm);
  st.bind(2, timeId);
  return st.exec() > 0;
}

std::vector<HandPositionRow> HandPositionDao::inFrameRange(int tm, int first, int last) const {
  Statement st(db_,
                       std::string(kSelect) + " WHERE TaskModelId = ? AND TimeId BETWEEN ? AND ? ORDER BY TimeId");
  st.bind(1, tm);
  st.bind(2, first);
  st.bind(3, last);
  std::vector<HandPositionRow> rows;
  while (st.executeStep()) rows.push_back(readRow(st));
  return rows;
}

std::vector<HandPositionRow> HandPositionDao::list(int tm) const {
  Statement st(db_, std::string(kSelect) + " WHERE TaskModelId = ? ORDER BY TimeId");
  st.bind(1, tm);
  std::vector<HandPositionRow> rows;
  while (st.executeStep()) rows.push_back(readRow(st));
  return rows;
}

}  // namespace srp::taskdb
