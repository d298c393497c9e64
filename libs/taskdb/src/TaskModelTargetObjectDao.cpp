#include "srp/taskdb/TaskModelTargetObjectDao.h"

#include "SqlUtil.h"
#include "srp/taskdb/ProductDao.h"

namespace srp::taskdb {
using namespace detail;

void TaskModelTargetObjectDao::add(int tm, int step, int objectId) {
  Statement st(db_,
                       "INSERT INTO TaskModelTargetObjects (TaskModelId, StepIndex, TargetObjectId) VALUES (?, ?, ?)");
  st.bind(1, tm);
  st.bind(2, step);
  st.bind(3, objectId);
  st.exec();
}

void TaskModelTargetObjectDao::update(int tm, int step, int objectId) {
  Statement st(db_,
                       "UPDATE TaskModelTargetObjects SET TargetObjectId = ? WHERE TaskModelId = ? AND StepIndex = ?");
  st.bind(1, objectId);
  st.bind(2, tm);
  st.bind(3, step);
  execExpectingRow(st, "no step " + std::to_string(step) + " in task model " + std::to_string(tm));
}

bool TaskModelTargetObjectDao::remove(int tm, int step) {
  Statement st(db_, "DELETE FROM TaskModelTargetObjects WHERE TaskModelId = ? AND StepIndex = ?");
  st.bind(1, tm);
  st.bind(2, step);
  return st.exec() > 0;
}

std::vector<int> TaskModelTargetObjectDao::list(int tm) const {
  Statement st(db_,
                       "SELECT TargetObjectId, TaskModelId, StepIndex FROM TaskModelTargetObjects "
                       "WHERE TaskModelId = ? ORDER BY StepIndex");
  st.bind(1, tm);
  std::vector<int> ids;
  while (st.executeStep()) ids.push_back(checkedInt(st, 0, rowRef(st, "TaskModelTargetObjects", {1, 2})));
  return ids;
}

std::vector<ProductRow> TaskModelTargetObjectDao::orderedTargetObjects(int tm) const {
  ProductDao products(db_);
  std::vector<ProductRow> rows;
  for (int id : list(tm))
    if (auto p = products.get(tm, id)) rows.push_back(*p);
  return rows;
}

}  // namespace srp::taskdb
