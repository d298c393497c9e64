#include "srp/taskdb/ProductDao.h"

#include "SqlUtil.h"

namespace srp::taskdb {
using namespace detail;

namespace {
constexpr const char* kColumns =
    "ObjectId, ObjectName, SourceLocationId, TargetLocationId, Color, TokenId, SentenceId, ClassId, InstanceId";

void bindRow(Statement& st, int first, const ProductRow& r) {
  st.bind(first, r.objectName);
  bindOptional(st, first + 1, r.sourceLocationId);
  bindOptional(st, first + 2, r.targetLocationId);
  bindOptional(st, first + 3, r.colour);
  bindOptional(st, first + 4, r.tokenId);
  bindOptional(st, first + 5, r.sentenceId);
  bindOptional(st, first + 6, r.classId);
  st.bind(first + 7, r.instanceId);
}

ProductRow readRow(const Statement& st) {
  const RowRef row = rowRef(st, "Products", {0});
  ProductRow r;
  r.objectId = checkedInt(st, 0, row);
  r.objectName = st.getColumn(1).getString();
  r.sourceLocationId = checkedOptionalInt(st, 2, row);
  r.targetLocationId = checkedOptionalInt(st, 3, row);
  r.colour = optionalText(st.getColumn(4));
  r.tokenId = checkedOptionalInt(st, 5, row);
  r.sentenceId = checkedOptionalInt(st, 6, row);
  r.classId = checkedOptionalInt(st, 7, row);
  r.instanceId = st.getColumn(8).getString();
  return r;
}
}  // namespace

void ProductDao::add(int tm, const ProductRow& r) {
  Statement st(db_, std::string("INSERT INTO Products (TaskModelId, ") + kColumns +
                                             ") VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?)");
  st.bind(1, tm);
  st.bind(2, r.objectId);
  bindRow(st, 3, r);
  st.exec();
}

std::optional<ProductRow> ProductDao::get(int tm, int objectId) const {
  Statement st(db_, std::string("SELECT ") + kColumns +
                                             " FROM Products WHERE TaskModelId = ? AND ObjectId = ?");
  st.bind(1, tm);
  st.bind(2, objectId);
  if (!st.executeStep()) return std::nullopt;
  return readRow(st);
}

void ProductDao::update(int tm, const ProductRow& r) {
  Statement st(db_,
                       "UPDATE Products SET ObjectName = ?, SourceLocationId = ?, TargetLocationId = ?, Color = ?, "
                       "TokenId = ?, SentenceId = ?, ClassId = ?, InstanceId = ? WHERE TaskModelId = ? AND ObjectId = ?");
  bindRow(st, 1, r);
  st.bind(9, tm);
  st.bind(10, r.objectId);
  execExpectingRow(st, "no product " + std::to_string(r.objectId) + " in task model " + std::to_string(tm));
}

bool ProductDao::remove(int tm, int objectId) {
  Statement st(db_, "DELETE FROM Products WHERE TaskModelId = ? AND ObjectId = ?");
  st.bind(1, tm);
  st.bind(2, objectId);
  return st.exec() > 0;
}

std::vector<ProductRow> ProductDao::list(int tm) const {
  Statement st(db_, std::string("SELECT ") + kColumns +
                                             " FROM Products WHERE TaskModelId = ? ORDER BY ObjectId");
  st.bind(1, tm);
  std::vector<ProductRow> rows;
  while (st.executeStep()) rows.push_back(readRow(st));
  return rows;
}

}  // namespace srp::taskdb
