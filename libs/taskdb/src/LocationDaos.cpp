// SourceLocations and TargetLocations have the same shape (location, landmark
// object, description); one implementation serves both DAOs.
#include "SqlUtil.h"
#include "srp/taskdb/SourceLocationDao.h"
#include "srp/taskdb/TargetLocationDao.h"

namespace srp::taskdb {
using namespace detail;

namespace {

int& landmarkOf(SourceLocationRow& r) { return r.trajectorObjectId; }
int& landmarkOf(TargetLocationRow& r) { return r.indicatorObjectId; }
int landmarkOf(const SourceLocationRow& r) { return r.trajectorObjectId; }
int landmarkOf(const TargetLocationRow& r) { return r.indicatorObjectId; }

template <typename Row>
class LocationTable {
 public:
  LocationTable(TaskDatabase& db, std::string table, std::string landmarkColumn)
      : db_(db), table_(std::move(table)), col_(std::move(landmarkColumn)) {}

  void add(int tm, const Row& r) {
    Statement st(db_, "INSERT INTO " + table_ + " (TaskModelId, LocationId, " + col_ +
                                               ", Description) VALUES (?, ?, ?, ?)");
    st.bind(1, tm);
    st.bind(2, r.locationId);
    st.bind(3, landmarkOf(r));
    st.bind(4, r.description);
    st.exec();
  }
  std::optional<Row> get(int tm, int id) const {
    Statement st(db_, select() + " WHERE TaskModelId = ? AND LocationId = ?");
    st.bind(1, tm);
    st.bind(2, id);
    if (!st.executeStep()) return std::nullopt;
    return read(st);
  }
  void update(int tm, const Row& r) {
    Statement st(db_, "UPDATE " + table_ + " SET " + col_ +
                                               " = ?, Description = ? WHERE TaskModelId = ? AND LocationId = ?");
    st.bind(1, landmarkOf(r));
    st.bind(2, r.description);
    st.bind(3, tm);
    st.bind(4, r.locationId);
    execExpectingRow(st, "no " + table_ + " row " + std::to_string(r.locationId) + " in task model " +
                             std::to_string(tm));
  }
  bool remove(int tm, int id) {
    Statement st(db_, "DELETE FROM " + table_ + " WHERE TaskModelId = ? AND LocationId = ?");
    st.bind(1, tm);
    st.bind(2, id);
    return st.exec() > 0;
  }
  std::vector<Row> list(int tm) const {
    Statement st(db_, select() + " WHERE TaskModelId = ? ORDER BY LocationId");
    st.bind(1, tm);
    std::vector<Row> rows;
    while (st.executeStep()) rows.push_back(read(st));
    return rows;
  }

 private:
  std::string select() const { return "SELECT LocationId, " + col_ + ", Description FROM " + table_; }
  Row read(const Statement& st) const {
    const RowRef row = rowRef(st, table_.c_str(), {0});
    Row r;
    r.locationId = checkedInt(st, 0, row);
    landmarkOf(r) = checkedInt(st, 1, row);
    r.description = st.getColumn(2).getString();
    return r;
  }
  TaskDatabase& db_;
  std::string table_, col_;
};

LocationTable<SourceLocationRow> sources(TaskDatabase& db) { return {db, "SourceLocations", "TrajectorObjectId"}; }
LocationTable<TargetLocationRow> targets(TaskDatabase& db) { return {db, "TargetLocations", "IndicatorObjectId"}; }

}  // namespace

void SourceLocationDao::add(int tm, const SourceLocationRow& r) { sources(db_).add(tm, r); }
std::optional<SourceLocationRow> SourceLocationDao::get(int tm, int id) const { return sources(db_).get(tm, id); }
void SourceLocationDao::update(int tm, const SourceLocationRow& r) { sources(db_).update(tm, r); }
bool SourceLocationDao::remove(int tm, int id) { return sources(db_).remove(tm, id); }
std::vector<SourceLocationRow> SourceLocationDao::list(int tm) const { return sources(db_).list(tm); }

void TargetLocationDao::add(int tm, const TargetLocationRow& r) { targets(db_).add(tm, r); }
std::optional<TargetLocationRow> TargetLocationDao::get(int tm, int id) const { return targets(db_).get(tm, id); }
void TargetLocationDao::update(int tm, const TargetLocationRow& r) { targets(db_).update(tm, r); }
bool TargetLocationDao::remove(int tm, int id) { return targets(db_).remove(tm, id); }
std::vector<TargetLocationRow> TargetLocationDao::list(int tm) const { return targets(db_).list(tm); }

}  // namespace srp::taskdb
