#include "srp/taskdb/SkillDao.h"

#include "SqlUtil.h"

namespace srp::taskdb {
using namespace detail;

namespace {
constexpr const char* kSelect =
    "SELECT ClassId, Skill, StartTimeId, EndTimeId, Parameters, InstanceId, TaskModelId FROM Skills";

SkillRow readRow(const Statement& st) {
  const RowRef row = rowRef(st, "Skills", {6, 0, 5, 1});
  SkillRow r;
  r.classId = checkedInt(st, 0, row);
  try {
    r.skill = core::skillTypeFromString(st.getColumn(1).getString());
  } catch (const core::Error& e) {
    badCell(st, 1, row, e.what());
  }
  r.startTimeId = checkedInt(st, 2, row);
  r.endTimeId = checkedInt(st, 3, row);
  if (r.endTimeId < r.startTimeId) badCell(st, 3, row, "the skill ends before it starts (EndTimeId < StartTimeId)");
  r.parameters = checkedJson(st, 4, row);
  r.instanceId = st.getColumn(5).getString();
  return r;
}
}  // namespace

void SkillDao::add(int tm, const SkillRow& r) {
  Statement st(db_,
                       "INSERT INTO Skills (TaskModelId, ClassId, Skill, StartTimeId, EndTimeId, Parameters, InstanceId) "
                       "VALUES (?, ?, ?, ?, ?, ?, ?)");
  st.bind(1, tm);
  st.bind(2, r.classId);
  st.bind(3, core::toString(r.skill));
  st.bind(4, r.startTimeId);
  st.bind(5, r.endTimeId);
  st.bind(6, r.parameters.dump());
  st.bind(7, r.instanceId);
  st.exec();
}

std::optional<SkillRow> SkillDao::get(int tm, int classId, core::SkillType skill, const std::string& instanceId) const {
  Statement st(db_, std::string(kSelect) +
                                             " WHERE TaskModelId = ? AND ClassId = ? AND Skill = ? AND InstanceId = ?");
  st.bind(1, tm);
  st.bind(2, classId);
  st.bind(3, core::toString(skill));
  st.bind(4, instanceId);
  if (!st.executeStep()) return std::nullopt;
  return readRow(st);
}

void SkillDao::update(int tm, const SkillRow& r) {
  Statement st(db_,
                       "UPDATE Skills SET StartTimeId = ?, EndTimeId = ?, Parameters = ? "
                       "WHERE TaskModelId = ? AND ClassId = ? AND Skill = ? AND InstanceId = ?");
  st.bind(1, r.startTimeId);
  st.bind(2, r.endTimeId);
  st.bind(3, r.parameters.dump());
  st.bind(4, tm);
  st.bind(5, r.classId);
  st.bind(6, core::toString(r.skill));
  st.bind(7, r.instanceId);
  execExpectingRow(st, "no " + core::toString(r.skill) + " skill of class " + std::to_string(r.classId) +
                           " in task model " + std::to_string(tm));
}

bool SkillDao::remove(int tm, int classId, core::SkillType skill, const std::string& instanceId) {
  Statement st(db_,
                       "DELETE FROM Skills WHERE TaskModelId = ? AND ClassId = ? AND Skill = ? AND InstanceId = ?");
  st.bind(1, tm);
  st.bind(2, classId);
  st.bind(3, core::toString(skill));
  st.bind(4, instanceId);
  return st.exec() > 0;
}

std::vector<SkillRow> SkillDao::list(int tm) const {
  Statement st(db_,
                       std::string(kSelect) +
                           " WHERE TaskModelId = ? ORDER BY ClassId, InstanceId, CASE Skill WHEN 'Reach' THEN 0 "
                           "WHEN 'Grasp' THEN 1 WHEN 'Move' THEN 2 ELSE 3 END");
  st.bind(1, tm);
  std::vector<SkillRow> rows;
  while (st.executeStep()) rows.push_back(readRow(st));
  return rows;
}

}  // namespace srp::taskdb
