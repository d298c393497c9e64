#include "srp/taskdb/TaskModelStore.h"

#include "Backend.h"
#include "SqlUtil.h"
#include "srp/core/Json.h"

#include "SqlUtil.h"
#include "srp/core/Error.h"
#include "srp/taskdb/GroundedProductDao.h"
#include "srp/taskdb/HandPositionDao.h"
#include "srp/taskdb/PerceivedSceneDao.h"
#include "srp/taskdb/ProductDao.h"
#include "srp/taskdb/ProductPoseDao.h"
#include "srp/taskdb/SkillDao.h"
#include "srp/taskdb/SourceLocationDao.h"
#include "srp/taskdb/TargetLocationDao.h"
#include "srp/taskdb/TaskModelDao.h"
#include "srp/taskdb/TaskModelTargetObjectDao.h"

namespace srp::taskdb {

namespace {
// Bulk rows are written in chunks so the progress callback (and a kill) can
// land in the middle of a task model.
constexpr std::size_t kChunkRows = 2000;
// Writers storing the same name at once: the loser of the unique (Name,
// Version) race takes the next version; bounded so a bug cannot spin forever.
constexpr int kMaxVersionAttempts = 100;

template <typename Row, typename Dao>
void writeChunked(Dao& dao, int id, const std::vector<Row>& rows, std::size_t& done, std::size_t total,
                  const TaskModelStore::Progress& progress) {
  for (std::size_t i = 0; i < rows.size(); i += kChunkRows) {
    const auto end = rows.begin() + static_cast<std::ptrdiff_t>(std::min(rows.size(), i + kChunkRows));
    dao.addMany(id, std::vector<Row>(rows.begin() + static_cast<std::ptrdiff_t>(i), end));
    done += static_cast<std::size_t>(end - (rows.begin() + static_cast<std::ptrdiff_t>(i)));
    if (progress) progress(done, total);
  }
}
}  // namespace

int TaskModelStore::write(const TaskModel& m, const Progress& progress, const BeforeCommit& beforeCommit) {
  ScopedTransaction tx(db_);
  try {
    const auto [id, version] = writeRows(m, false, progress);
    if (beforeCommit) beforeCommit(id, version);
    tx.commit();  // deferred foreign keys are checked here
    return id;
  } catch (const detail::DbError& e) {
    throw core::InvalidInputError("task model '" + m.info.name + "' not written (database unchanged): " + e.what());
  }
}

std::pair<int, int> TaskModelStore::writeRows(const TaskModel& m, bool keepVersion, const Progress& progress) {
  TaskModelDao models(db_);
  TaskModelInfo info = m.info;
  int id = 0;
  if (keepVersion) {
    try {
      id = models.add(info);
    } catch (const detail::DbError& e) {
      if (e.kind() != detail::DbError::Kind::UniqueViolation) throw;
      throw core::InvalidInputError("task model '" + info.name + "' version " + std::to_string(info.version) +
                                    " is already in '" + db_.path() +
                                    "'; nothing copied (copy into a database without it, or delete it there)");
    }
    return {writeChildren(m, id, progress), info.version};
  }
  // Race-free versioning: insert under the UNIQUE (Name, Version)
  // constraint; a concurrent writer that took the version first makes the
  // insert fail, the savepoint undoes it and the next version is tried (on a
  // server each statement sees the other's committed row; SQLite's write
  // lock already serialises writers).
  for (int attempt = 1;; ++attempt) {
    info.version = models.nextVersion(info.name);
    db_.backend().exec("SAVEPOINT srp_version");
    try {
      id = models.add(info);
      db_.backend().exec("RELEASE SAVEPOINT srp_version");
      break;
    } catch (const detail::DbError& e) {
      if (e.kind() != detail::DbError::Kind::UniqueViolation || attempt >= kMaxVersionAttempts) throw;
      db_.backend().exec("ROLLBACK TO SAVEPOINT srp_version");
    }
  }
  return {writeChildren(m, id, progress), info.version};
}

int TaskModelStore::writeChildren(const TaskModel& m, int id, const Progress& progress) {
  ProductDao products(db_);
  for (const auto& r : m.products) products.add(id, r);
  SourceLocationDao sources(db_);
  for (const auto& r : m.sourceLocations) sources.add(id, r);
  TargetLocationDao targets(db_);
  for (const auto& r : m.targetLocations) targets.add(id, r);
  TaskModelTargetObjectDao plan(db_);
  for (std::size_t i = 0; i < m.targetObjectIds.size(); ++i) plan.add(id, static_cast<int>(i), m.targetObjectIds[i]);
  GroundedProductDao grounded(db_);
  for (const auto& r : m.groundedProducts) grounded.add(id, r);
  SkillDao skills(db_);
  for (const auto& r : m.skills) skills.add(id, r);
  if (m.scene) PerceivedSceneDao(db_).add(id, *m.scene);

  const std::size_t total = m.handPositions.size() + m.productPoses.size();
  std::size_t done = 0;
  HandPositionDao hands(db_);
  writeChunked(hands, id, m.handPositions, done, total, progress);
  ProductPoseDao poses(db_);
  writeChunked(poses, id, m.productPoses, done, total, progress);
  return id;
}

namespace {
// Columns the task model holds as a Pose3 (a rotation matrix): going through
// it changes a quaternion's last bit, so a copy takes them from the source's
// row as they are. JSON text is re-serialised by the same writer (jsonb on a
// server keeps the numbers' digits).
void copyExactColumns(TaskDatabase& from, int id, TaskDatabase& to, int newId) {
  using detail::Statement;
  Statement info(from, "SELECT Intrinsics, X_base_camera FROM TaskModels WHERE TaskModelId = ?");
  info.bind(1, id);
  if (info.executeStep()) {
    Statement set(to, "UPDATE TaskModels SET Intrinsics = ?, X_base_camera = ? WHERE TaskModelId = ?");
    for (int c = 0; c < 2; ++c) {
      if (info.getColumn(c).isNull()) set.bind(c + 1);
      else set.bind(c + 1, nlohmann::json::parse(info.getColumn(c).getString()).dump());
    }
    set.bind(3, newId);
    set.exec();
  }
  Statement camera(from, "SELECT CameraX, CameraY, CameraZ, CameraQW, CameraQX, CameraQY, CameraQZ FROM "
                         "PerceivedScenes WHERE TaskModelId = ?");
  camera.bind(1, id);
  if (camera.executeStep()) {
    Statement set(to, "UPDATE PerceivedScenes SET CameraX = ?, CameraY = ?, CameraZ = ?, CameraQW = ?, CameraQX = ?, "
                      "CameraQY = ?, CameraQZ = ? WHERE TaskModelId = ?");
    for (int c = 0; c < 7; ++c) set.bind(c + 1, camera.getColumn(c).getDouble());
    set.bind(8, newId);
    set.exec();
  }
  Statement objects(from, "SELECT ObjectId, X, Y, Z, QW, QX, QY, QZ FROM SceneObjects WHERE TaskModelId = ?");
  objects.bind(1, id);
  Statement set(to, "UPDATE SceneObjects SET X = ?, Y = ?, Z = ?, QW = ?, QX = ?, QY = ?, QZ = ? "
                    "WHERE TaskModelId = ? AND ObjectId = ?");
  while (objects.executeStep()) {
    set.reset();
    for (int c = 0; c < 7; ++c) set.bind(c + 1, objects.getColumn(c + 1).getDouble());
    set.bind(8, newId);
    set.bind(9, objects.getColumn(0).getString());
    set.exec();
  }
}
}  // namespace

std::vector<std::pair<int, int>> copyTaskModels(TaskDatabase& from, TaskDatabase& to, const std::vector<int>& ids) {
  const TaskModelStore source(from);
  std::vector<int> which = ids;
  if (which.empty())
    for (const auto& info : source.list()) which.push_back(info.id);
  TaskModelStore target(to);
  std::vector<std::pair<int, int>> copied;
  ScopedTransaction tx(to);
  try {
    for (const int id : which) {
      copied.emplace_back(id, target.writeRows(source.read(id), true, {}).first);
      copyExactColumns(from, id, to, copied.back().second);
    }
    tx.commit();
  } catch (const detail::DbError& e) {
    throw core::InvalidInputError("task models not copied from '" + from.path() + "' to '" + to.path() +
                                  "' (destination unchanged): " + e.what());
  }
  return copied;
}

namespace {
// A page SQLite cannot read mid-query: say which file and what to do.
[[noreturn]] void rethrowUnreadable(const std::string& path, const detail::DbError& e) {
  throw core::FileError(path, std::string("cannot read the task database (") + e.what() +
                                  "); if it is corrupt, restore it from a backup");
}
}  // namespace

TaskModel TaskModelStore::read(int id) const {
  try {
    return readUnchecked(id);
  } catch (const detail::DbError& e) {
    rethrowUnreadable(db_.path(), e);
  } catch (const detail::BadCellError& e) {
    throw core::InvalidInputError("task database '" + db_.path() + "', task model " + std::to_string(id) + ": " +
                                  e.what());
  }
}

TaskModel TaskModelStore::readUnchecked(int id) const {
  TaskModel m;
  auto info = TaskModelDao(db_).get(id);
  if (!info)
    throw core::InvalidInputError("no task model with id " + std::to_string(id) + " in '" + db_.path() +
                                  "' (list them with 'srp db list')");
  // One read transaction: a consistent snapshot even while a writer commits.
  db_.backend().beginRead();
  try {
    m.info = *info;
    m.products = ProductDao(db_).list(id);
    m.sourceLocations = SourceLocationDao(db_).list(id);
    m.targetLocations = TargetLocationDao(db_).list(id);
    m.targetObjectIds = TaskModelTargetObjectDao(db_).list(id);
    m.groundedProducts = GroundedProductDao(db_).list(id);
    m.productPoses = ProductPoseDao(db_).list(id);
    m.handPositions = HandPositionDao(db_).list(id);
    m.skills = SkillDao(db_).list(id);
    m.scene = PerceivedSceneDao(db_).get(id);
  } catch (...) {
    try {
      db_.backend().exec("ROLLBACK");
    } catch (...) {
    }
    throw;
  }
  db_.backend().exec("COMMIT");
  return m;
}

std::vector<TaskModelInfo> TaskModelStore::list() const {
  try {
    return TaskModelDao(db_).list();
  } catch (const detail::DbError& e) {
    rethrowUnreadable(db_.path(), e);
  } catch (const detail::BadCellError& e) {
    throw core::InvalidInputError("task database '" + db_.path() + "': " + e.what());
  }
}

void TaskModelStore::remove(int id) {
  ScopedTransaction tx(db_);
  if (!TaskModelDao(db_).remove(id))
    throw core::InvalidInputError("no task model with id " + std::to_string(id) + " in '" + db_.path() + "'");
  tx.commit();
}

void TaskModelStore::replaceSkills(int id, const std::vector<SkillRow>& rows) {
  ScopedTransaction tx(db_);
  if (!TaskModelDao(db_).get(id))
    throw core::InvalidInputError("no task model with id " + std::to_string(id) + " in '" + db_.path() + "'");
  SkillDao skills(db_);
  for (const auto& old : skills.list(id)) skills.remove(id, old.classId, old.skill, old.instanceId);
  try {
    for (const auto& r : rows) skills.add(id, r);
    tx.commit();
  } catch (const detail::DbError& e) {
    throw core::InvalidInputError("skills of task model " + std::to_string(id) + " not written (unchanged): " + e.what());
  }
}

}  // namespace srp::taskdb
