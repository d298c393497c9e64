#include "srp/taskdb/GroundedProductDao.h"

#include "SqlUtil.h"

namespace srp::taskdb {
using namespace detail;

namespace {
constexpr const char* kSelect =
    "SELECT ClassId, ObjectName, SourceLocationId, TargetLocationId, Color, InstanceId FROM GroundedProducts";

GroundedProductRow readRow(const Statement& st) {
  const RowRef row = rowRef(st, "GroundedProducts", {0, 5});
  GroundedProductRow r;
  r.classId = checkedInt(st, 0, row);
  r.objectName = st.getColumn(1).getString();
  r.sourceLocationId = checkedOptionalInt(st, 2, row);
  r.targetLocationId = checkedOptionalInt(st, 3, row);
  r.colour = optionalText(st.getColumn(4));
  r.instanceId = st.getColumn(5).getString();
  return r;
}
}  // namespace

void GroundedProductDao::add(int tm, const GroundedProductRow& r) {
  Statement st(db_,
                       "INSERT INTO GroundedProducts (TaskModelId, ClassId, ObjectName, SourceLocationId, "
                       "TargetLocationId, Color, InstanceId) VALUES (?, ?, ?, ?, ?, ?, ?)");
  st.bind(1, tm);
  st.bind(2, r.classId);
  st.bind(3, r.objectName);
  bindOptional(st, 4, r.sourceLocationId);
  bindOptional(st, 5, r.targetLocationId);
  bindOptional(st, 6, r.colour);
  st.bind(7, r.instanceId);
  st.exec();
}

std::optional<GroundedProductRow> GroundedProductDao::get(int tm, int classId, const std::string& instanceId) const {
  Statement st(db_,
                       std::string(kSelect) + " WHERE TaskModelId = ? AND ClassId = ? AND InstanceId = ?");
  st.bind(1, tm);
  st.bind(2, classId);
  st.bind(3, instanceId);
  if (!st.executeStep()) return std::nullopt;
  return readRow(st);
}

void GroundedProductDao::update(int tm, const GroundedProductRow& r) {
  Statement st(db_,
                       "UPDATE GroundedProducts SET ObjectName = ?, SourceLocationId = ?, TargetLocationId = ?, "
                       "Color = ? WHERE TaskModelId = ? AND ClassId = ? AND InstanceId = ?");
  st.bind(1, r.objectName);
  bindOptional(st, 2, r.sourceLocationId);
  bindOptional(st, 3, r.targetLocationId);
  bindOptional(st, 4, r.colour);
  st.bind(5, tm);
  st.bind(6, r.classId);
  st.bind(7, r.instanceId);
  execExpectingRow(st, "no grounded product " + std::to_string(r.classId) + " in task model " + std::to_string(tm));
}

bool GroundedProductDao::remove(int tm, int classId, const std::string& instanceId) {
  Statement st(db_,
                       "DELETE FROM GroundedProducts WHERE TaskModelId = ? AND ClassId = ? AND InstanceId = ?");
  st.bind(1, tm);
  st.bind(2, classId);
  st.bind(3, instanceId);
  return st.exec() > 0;
}

std::vector<GroundedProductRow> GroundedProductDao::list(int tm) const {
  Statement st(db_, std::string(kSelect) + " WHERE TaskModelId = ? ORDER BY ClassId, InstanceId");
  st.bind(1, tm);
  std::vector<GroundedProductRow> rows;
  while (st.executeStep()) rows.push_back(readRow(st));
  return rows;
}

}  // namespace srp::taskdb
