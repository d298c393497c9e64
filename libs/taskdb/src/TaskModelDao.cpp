#include "srp/taskdb/TaskModelDao.h"

#include <chrono>
#include <ctime>

#include "SqlUtil.h"
#include "srp/core/Json.h"

namespace srp::taskdb {
using namespace detail;

namespace {
constexpr const char* kSelect =
    "SELECT TaskModelId, Name, Version, CreatedUtc, Instruction, Frame, FrameRate_Hz, Intrinsics, X_base_camera "
    "FROM TaskModels";

std::string nowUtc() {
  const std::time_t t = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

std::optional<std::string> intrinsicsText(const TaskModelInfo& i) {
  if (!i.intrinsics) return std::nullopt;
  return nlohmann::json(*i.intrinsics).dump();
}
std::optional<std::string> poseText(const TaskModelInfo& i) {
  if (!i.X_base_camera) return std::nullopt;
  return core::poseToJson(*i.X_base_camera).dump();
}

void bindValues(Statement& st, int first, const TaskModelInfo& i) {
  st.bind(first, i.name);
  st.bind(first + 1, i.version);
  st.bind(first + 2, i.createdUtc.empty() ? nowUtc() : i.createdUtc);
  st.bind(first + 3, i.instruction);
  st.bind(first + 4, i.frame);
  st.bind(first + 5, i.frameRate_hz);
  bindOptional(st, first + 6, intrinsicsText(i));
  bindOptional(st, first + 7, poseText(i));
}

TaskModelInfo readRow(const Statement& st) {
  const RowRef row = rowRef(st, "TaskModels", {0});
  TaskModelInfo i;
  i.id = checkedInt(st, 0, row, 1);
  i.name = st.getColumn(1).getString();
  i.version = checkedInt(st, 2, row, 1);
  i.createdUtc = st.getColumn(3).getString();
  i.instruction = st.getColumn(4).getString();
  i.frame = st.getColumn(5).getString();
  constexpr double kMaxFrameRate_hz = 10000.0;
  i.frameRate_hz = checkedReal(st, 6, row, 1e-3, kMaxFrameRate_hz);
  try {
    if (!st.getColumn(7).isNull()) {
      i.intrinsics = checkedJson(st, 7, row).get<core::CameraIntrinsics>();
      i.intrinsics->validate("the camera");
    }
  } catch (const core::Error& e) {
    badCell(st, 7, row, e.what());
  } catch (const nlohmann::json::exception& e) {
    badCell(st, 7, row, e.what());
  }
  try {
    if (!st.getColumn(8).isNull()) {
      i.X_base_camera = core::poseFromJson(checkedJson(st, 8, row), "the camera pose");
      if (!i.X_base_camera->matrix().allFinite() ||
          i.X_base_camera->translation().cwiseAbs().maxCoeff() > kMaxCoordinate_m)
        badCell(st, 8, row, "the camera pose is not finite or is more than 1 km away");
    }
  } catch (const core::Error& e) {
    badCell(st, 8, row, e.what());
  } catch (const nlohmann::json::exception& e) {
    badCell(st, 8, row, e.what());
  }
  return i;
}
}  // namespace

int TaskModelDao::add(const TaskModelInfo& info) {
  if (info.name.empty()) throw core::InvalidInputError("a task model needs a name");
  Statement st(db_,
                       "INSERT INTO TaskModels (Name, Version, CreatedUtc, Instruction, Frame, FrameRate_Hz, "
                       "Intrinsics, X_base_camera) VALUES (?, ?, ?, ?, ?, ?, ?, ?) RETURNING TaskModelId");
  bindValues(st, 1, info);
  st.executeStep();
  const int id = st.getColumn(0).getInt();
  st.reset();  // SQLite finishes the INSERT on the step after its RETURNING row
  return id;
}

std::optional<TaskModelInfo> TaskModelDao::get(int id) const {
  Statement st(db_, std::string(kSelect) + " WHERE TaskModelId = ?");
  st.bind(1, id);
  if (!st.executeStep()) return std::nullopt;
  return readRow(st);
}

void TaskModelDao::update(const TaskModelInfo& info) {
  Statement st(db_,
                       "UPDATE TaskModels SET Name = ?, Version = ?, CreatedUtc = ?, Instruction = ?, Frame = ?, "
                       "FrameRate_Hz = ?, Intrinsics = ?, X_base_camera = ? WHERE TaskModelId = ?");
  bindValues(st, 1, info);
  st.bind(9, info.id);
  execExpectingRow(st, "no task model " + std::to_string(info.id));
}

bool TaskModelDao::remove(int id) {
  Statement st(db_, "DELETE FROM TaskModels WHERE TaskModelId = ?");
  st.bind(1, id);
  return st.exec() > 0;
}

std::vector<TaskModelInfo> TaskModelDao::list() const {
  Statement st(db_, std::string(kSelect) + " ORDER BY TaskModelId");
  std::vector<TaskModelInfo> rows;
  while (st.executeStep()) rows.push_back(readRow(st));
  return rows;
}

int TaskModelDao::nextVersion(const std::string& name) const {
  Statement st(db_, "SELECT COALESCE(MAX(Version), 0) + 1 FROM TaskModels WHERE Name = ?");
  st.bind(1, name);
  st.executeStep();
  return st.getColumn(0).getInt();
}

std::optional<TaskModelInfo> TaskModelDao::latestByName(const std::string& name) const {
  Statement st(db_, std::string(kSelect) + " WHERE Name = ? ORDER BY Version DESC LIMIT 1");
  st.bind(1, name);
  if (!st.executeStep()) return std::nullopt;
  return readRow(st);
}

}  // namespace srp::taskdb
