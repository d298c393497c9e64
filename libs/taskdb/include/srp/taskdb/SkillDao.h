#pragma once
/// \file SkillDao.h
/// \brief DAO of table Skills: learned skills (DMPs, grasp/release poses) per object.

#include <optional>
#include <vector>

#include "srp/taskdb/Rows.h"
#include "srp/taskdb/TaskDatabase.h"

namespace srp::taskdb {

/// Data access object of table Skills, rows keyed by (TaskModelId, ClassId, InstanceId, Skill);
/// `instanceId` "" is the one instance of a class (schema 1 rows); get and remove
/// take it explicitly, so that no caller keys a row by its class alone.
class SkillDao {
 public:
  explicit SkillDao(TaskDatabase& db) : db_(db) {}
  void add(int taskModelId, const SkillRow& row);
  std::optional<SkillRow> get(int taskModelId, int classId, core::SkillType skill, const std::string& instanceId) const;
  void update(int taskModelId, const SkillRow& row);
  bool remove(int taskModelId, int classId, core::SkillType skill, const std::string& instanceId);
  /// All skills of a task model, by class then Reach, Grasp, Move, Release.
  std::vector<SkillRow> list(int taskModelId) const;

 private:
  TaskDatabase& db_;
};

}  // namespace srp::taskdb
