#include "srp/taskdb/ProductPoseDao.h"

#include "SqlUtil.h"

namespace srp::taskdb {
using namespace detail;

namespace {
constexpr const char* kSelect =
    "SELECT ClassId, TimeId, X, Y, Z, QW, QX, QY, QZ, Reach, Grasp, Move, Release, Detected, Confidence, InstanceId, "
    "TaskModelId FROM ProductPose";
constexpr const char* kInsertColumns =
    "TaskModelId, ClassId, TimeId, X, Y, Z, QW, QX, QY, QZ, Reach, Grasp, Move, Release, Detected, Confidence, "
    "InstanceId";

// Binds the value columns X..Confidence starting at `first`.
void bindValues(Statement& st, int first, const ProductPoseRow& r) {
  const double v[] = {r.p_m.x(), r.p_m.y(), r.p_m.z(), r.q.w(), r.q.x(), r.q.y(), r.q.z()};
  for (int i = 0; i < 7; ++i) st.bind(first + i, v[i]);
  const bool flags[] = {r.reach, r.grasp, r.move, r.release, r.detected};
  for (int i = 0; i < 5; ++i) st.bind(first + 7 + i, flags[i] ? 1 : 0);
  bindOptional(st, first + 12, r.confidence);
}

ProductPoseRow readRow(const Statement& st) {
  const RowRef row = rowRef(st, "ProductPose", {16, 0, 15, 1});
  ProductPoseRow r;
  r.classId = checkedInt(st, 0, row);
  r.timeId = checkedInt(st, 1, row);
  r.p_m = {checkedReal(st, 2, row, -kMaxCoordinate_m, kMaxCoordinate_m),
           checkedReal(st, 3, row, -kMaxCoordinate_m, kMaxCoordinate_m),
           checkedReal(st, 4, row, -kMaxCoordinate_m, kMaxCoordinate_m)};
  double q[4];
  for (int i = 0; i < 4; ++i) q[i] = checkedReal(st, 5 + i, row, -1.0 - 1e-6, 1.0 + 1e-6);
  r.q = Eigen::Quaterniond(q[0], q[1], q[2], q[3]);
  if (std::abs(r.q.norm() - 1.0) > 0.01) badCell(st, 5, row, "the quaternion QW, QX, QY, QZ is not of unit length");
  r.reach = checkedInt(st, 9, row, 0, 1) != 0;
  r.grasp = checkedInt(st, 10, row, 0, 1) != 0;
  r.move = checkedInt(st, 11, row, 0, 1) != 0;
  r.release = checkedInt(st, 12, row, 0, 1) != 0;
  r.detected = checkedInt(st, 13, row, 0, 1) != 0;
  r.confidence = checkedOptionalReal(st, 14, row, 0.0, 1.0);
  r.instanceId = st.getColumn(15).getString();
  return r;
}

void checkFinite(const ProductPoseRow& r) {
  if (!r.p_m.allFinite() || !r.q.coeffs().allFinite())
    throw core::InvalidInputError("object pose of class " + std::to_string(r.classId) + " at TimeId " +
                                  std::to_string(r.timeId) + " has a non-finite value (NaN/inf)");
}
}  // namespace

void ProductPoseDao::add(int tm, const ProductPoseRow& r) { addMany(tm, {r}); }

void ProductPoseDao::addMany(int tm, const std::vector<ProductPoseRow>& rows) {
  for (const auto& r : rows) checkFinite(r);
  insertRows(db_, "ProductPose", kInsertColumns, 17, rows.size(), [&](Statement& st, int p, std::size_t i) {
    const auto& r = rows[i];
    st.bind(p, tm);
    st.bind(p + 1, r.classId);
    st.bind(p + 2, r.timeId);
    bindValues(st, p + 3, r);
    st.bind(p + 16, r.instanceId);
  });
}

std::optional<ProductPoseRow> ProductPoseDao::get(int tm, int classId, int timeId, const std::string& instanceId) const {
  Statement st(db_, std::string(kSelect) +
                                             " WHERE TaskModelId = ? AND ClassId = ? AND TimeId = ? AND InstanceId = ?");
  st.bind(1, tm);
  st.bind(2, classId);
  st.bind(3, timeId);
  st.bind(4, instanceId);
  if (!st.executeStep()) return std::nullopt;
  return readRow(st);
}

void ProductPoseDao::update(int tm, const ProductPoseRow& r) {
  checkFinite(r);
  Statement st(db_,
                       "UPDATE ProductPose SET X = ?, Y = ?, Z = ?, QW = ?, QX = ?, QY = ?, QZ = ?, Reach = ?, "
                       "Grasp = ?, Move = ?, Release = ?, Detected = ?, Confidence = ? "
                       "WHERE TaskModelId = ? AND ClassId = ? AND TimeId = ? AND InstanceId = ?");
  bindValues(st, 1, r);
  st.bind(14, tm);
  st.bind(15, r.classId);
  st.bind(16, r.timeId);
  st.bind(17, r.instanceId);
  execExpectingRow(st, "no pose of class " + std::to_string(r.classId) + " at TimeId " + std::to_string(r.timeId) +
                           " in task model " + std::to_string(tm));
}

bool ProductPoseDao::remove(int tm, int classId, int timeId, const std::string& instanceId) {
  Statement st(db_,
                       "DELETE FROM ProductPose WHERE TaskModelId = ? AND ClassId = ? AND TimeId = ? AND InstanceId = ?");
  st.bind(1, tm);
  st.bind(2, classId);
  st.bind(3, timeId);
  st.bind(4, instanceId);
  return st.exec() > 0;
}

std::vector<ProductPoseRow> ProductPoseDao::inFrameRange(int tm, int classId, int first, int last,
                                                        const std::string& instanceId) const {
  Statement st(db_, std::string(kSelect) +
                                             " WHERE TaskModelId = ? AND ClassId = ? AND InstanceId = ? AND TimeId "
                                             "BETWEEN ? AND ? ORDER BY TimeId");
  st.bind(1, tm);
  st.bind(2, classId);
  st.bind(3, instanceId);
  st.bind(4, first);
  st.bind(5, last);
  std::vector<ProductPoseRow> rows;
  while (st.executeStep()) rows.push_back(readRow(st));
  return rows;
}

std::vector<ProductPoseRow> ProductPoseDao::list(int tm) const {
  Statement st(db_, std::string(kSelect) + " WHERE TaskModelId = ? ORDER BY ClassId, InstanceId, TimeId");
  st.bind(1, tm);
  std::vector<ProductPoseRow> rows;
  while (st.executeStep()) rows.push_back(readRow(st));
  return rows;
}

GraspReleaseFrames ProductPoseDao::graspReleaseFrames(int tm, int classId, const std::string& instanceId) const {
  Statement st(db_,
                       "SELECT (SELECT MIN(TimeId) FROM ProductPose WHERE TaskModelId = ?1 AND ClassId = ?2 AND "
                       "InstanceId = ?3 AND Grasp = 1), "
                       "(SELECT MIN(TimeId) FROM ProductPose WHERE TaskModelId = ?1 AND ClassId = ?2 AND "
                       "InstanceId = ?3 AND Release = 1)");
  st.bind(1, tm);
  st.bind(2, classId);
  st.bind(3, instanceId);
  st.executeStep();
  return {optionalInt(st.getColumn(0)), optionalInt(st.getColumn(1))};
}

}  // namespace srp::taskdb
