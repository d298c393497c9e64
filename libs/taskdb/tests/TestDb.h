#pragma once
// Helpers shared by the taskdb tests.
#include <cmath>
#include <filesystem>
#include <string>
#include <unistd.h>

#include "srp/taskdb/TaskModel.h"

namespace srp::taskdb::test {

/// A fresh database path in the temp folder, removed (with -wal/-shm) on destruction.
class TempDbPath {
 public:
  explicit TempDbPath(const std::string& name)
      : path_((std::filesystem::temp_directory_path() /
               ("srp_taskdb_" + name + "_" + std::to_string(::getpid()) + ".db")).string()) {
    clean();
  }
  ~TempDbPath() { clean(); }
  const std::string& str() const { return path_; }

 private:
  void clean() {
    for (const char* suffix : {"", "-wal", "-shm", "-journal"}) std::filesystem::remove(path_ + suffix);
  }
  std::string path_;
};

inline Eigen::Quaterniond yawQuaternion(double yaw_rad) {
  return Eigen::Quaterniond(std::cos(yaw_rad / 2), 0.0, 0.0, std::sin(yaw_rad / 2));
}

/// A synthetic task model with `frames` hand rows and `objects` x `frames` pose rows.
inline TaskModel bulkModel(const std::string& name, int frames, int objects) {
  TaskModel m;
  m.info.name = name;
  m.info.instruction = "bulk";
  for (int c = 0; c < objects; ++c) m.groundedProducts.push_back({c, "object" + std::to_string(c), {}, {}, {}});
  m.handPositions.reserve(static_cast<std::size_t>(frames));
  for (int t = 0; t < frames; ++t) m.handPositions.push_back({t, {0.001 * t, 0.2, 0.5}, t % 7 != 0});
  m.productPoses.reserve(static_cast<std::size_t>(frames) * static_cast<std::size_t>(objects));
  for (int c = 0; c < objects; ++c)
    for (int t = 0; t < frames; ++t) {
      ProductPoseRow r;
      r.classId = c;
      r.timeId = t;
      r.p_m = {0.01 * c, 0.0001 * t, 0.55};
      r.q = yawQuaternion(0.001 * t);
      r.grasp = t == 100;
      r.release = t == 200;
      r.confidence = 0.9;
      m.productPoses.push_back(r);
    }
  return m;
}

}  // namespace srp::taskdb::test
