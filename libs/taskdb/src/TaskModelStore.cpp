#include "srp/taskdb/TaskModelStore.h"

#include "Backend.h"

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
    TaskModelDao models(db_);
    TaskModelInfo info = m.info;
    // Race-free versioning: insert under the UNIQUE (Name, Version)
    // constraint; a concurrent writer that took the version first makes the
    // insert fail, the savepoint undoes it and the next version is tried (on a
    // server each statement sees the other's committed row; SQLite's write
    // lock already serialises writers).
    int id = 0;
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
    if (beforeCommit) beforeCommit(id, info.version);
    tx.commit();  // deferred foreign keys are checked here
    return id;
  } catch (const detail::DbError& e) {
    throw core::InvalidInputError("task model '" + m.info.name + "' not written (database unchanged): " + e.what());
  }
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
