#include "srp/programming/MotionRows.h"

#include <set>

#include "srp/core/Error.h"
#include "srp/programming/PerceptionRows.h"
#include "srp/taskdb/ProductPoseDao.h"
#include "srp/taskdb/SkillDao.h"
#include "srp/taskdb/TaskModelDao.h"

namespace srp::programming {

Eigen::Vector3d p_object_tracked(const std::string& className, const std::vector<core::ObjectClass>& observed) {
  for (const auto& c : observed)
    if (c.name == className && c.observed) return Eigen::Vector3d(0, 0, 0.5 * c.dimensions_m.z());
  return Eigen::Vector3d::Zero();
}

namespace {

bool rowOf(const MotionInputs::RowKey& key, int classId, const std::string& instanceId) {
  return key.classId == classId && key.instanceId == instanceId;
}

const MotionInputs::RowKey& rowKeyOf(const MotionInputs& inputs, const std::string& name) {
  const auto it = inputs.rowKeyByName.find(name);
  if (it == inputs.rowKeyByName.end())
    throw core::InvalidInputError("skill object '" + name + "' is not a grounded product");
  return it->second;
}

}  // namespace

MotionInputs motionInputsFromTaskModel(const taskdb::TaskModel& model) {
  using core::InvalidInputError;
  MotionInputs in;
  core::require(model.info.frameRate_hz > 0, "task model " + std::to_string(model.info.id) + ": frame rate must be positive");
  core::require(!model.handPositions.empty(), "task model " + std::to_string(model.info.id) +
                                                  " has no hand positions; program it from a demo first");
  core::require(!model.targetObjectIds.empty(), "task model " + std::to_string(model.info.id) + " has an empty plan");
  for (const auto& g : model.groundedProducts) in.rowKeyByName[perceptionKey(g)] = {g.classId, g.instanceId};
  std::set<std::pair<int, std::string>> planObjects;  // (ClassId, InstanceId)
  for (int objectId : model.targetObjectIds) {
    const auto* p = model.findProduct(objectId);
    if (!p) throw InvalidInputError("plan object id " + std::to_string(objectId) + " is not in Products");
    if (!p->classId) throw InvalidInputError("plan object '" + p->objectName + "' (ObjectId " + std::to_string(objectId) +
                                             ") is not grounded to a class; it has no trajectory");
    // The grounded row of the product's instance; a product grounded to its class only: the class's first.
    const taskdb::GroundedProductRow* g = nullptr;
    for (const auto& row : model.groundedProducts)
      if (row.classId == *p->classId && row.instanceId == p->instanceId) g = &row;
    if (!g) g = model.findGrounded(*p->classId);
    in.planOrder.push_back(g ? perceptionKey(*g) : p->objectName);
    const MotionInputs::RowKey key{*p->classId, g ? g->instanceId : p->instanceId};
    in.rowKeyByName[in.planOrder.back()] = key;
    planObjects.insert({key.classId, key.instanceId});
  }
  std::set<int> times;
  for (const auto& h : model.handPositions) times.insert(h.timeId);
  for (const auto& r : model.productPoses)
    if (planObjects.count({r.classId, r.instanceId})) times.insert(r.timeId);
  std::map<int, const taskdb::HandPositionRow*> handAt;
  for (const auto& h : model.handPositions) handAt[h.timeId] = &h;
  const std::string frame = model.info.frame;
  in.hand = core::PositionTrajectory(frame);
  for (int t : times) {
    const auto it = handAt.find(t);
    const bool ok = it != handAt.end() && it->second->detected;
    in.hand.append({t, t / model.info.frameRate_hz, ok ? it->second->p_m : Eigen::Vector3d::Zero(), ok});
  }
  for (const auto& [name, key] : in.rowKeyByName) {
    if (!planObjects.count({key.classId, key.instanceId})) continue;
    std::map<int, const taskdb::ProductPoseRow*> at;
    for (const auto& r : model.productPoses)
      if (rowOf(key, r.classId, r.instanceId)) at[r.timeId] = &r;
    if (at.empty()) continue;
    // The same point demoTracks handed to motion when the model was programmed.
    std::string className;
    for (const auto& o : model.scene ? model.scene->objects : std::vector<taskdb::SceneObjectRow>{})
      if (o.classId == key.classId) className = o.className;
    const Eigen::Vector3d p_object =
        model.scene ? p_object_tracked(className, model.scene->observedClasses) : Eigen::Vector3d::Zero();
    motion::ObjectTrack track;
    track.name = name;
    track.positions = core::PositionTrajectory(frame);
    for (int t : times) {
      const auto it = at.find(t);
      const bool ok = it != at.end() && it->second->detected;
      track.positions.append({t, t / model.info.frameRate_hz,
                              ok ? Eigen::Vector3d(it->second->p_m + it->second->q.normalized() * p_object)
                                 : Eigen::Vector3d::Zero(),
                              ok});
      track.yaw_rad.push_back(it != at.end() ? it->second->yaw_rad() : (track.yaw_rad.empty() ? 0.0 : track.yaw_rad.back()));
    }
    in.objects.push_back(std::move(track));
  }
  return in;
}

std::vector<taskdb::SkillRow> skillRows(const std::vector<motion::SkillSet>& skills, const MotionInputs& inputs) {
  std::vector<taskdb::SkillRow> rows;
  for (const auto& s : skills) {
    const MotionInputs::RowKey& key = rowKeyOf(inputs, s.objectName);
    for (const auto& r : motion::skillRecords(s)) {
      taskdb::SkillRow row;
      row.classId = key.classId;
      row.instanceId = key.instanceId;
      row.skill = r.skill;
      row.startTimeId = inputs.hand[static_cast<std::size_t>(r.startIndex)].frame;
      row.endTimeId = inputs.hand[static_cast<std::size_t>(r.endIndex)].frame;
      row.parameters = r.parameters;
      rows.push_back(std::move(row));
    }
  }
  return rows;
}

motion::LearnedSkills learnSkills(taskdb::TaskModel& model) {
  const MotionInputs inputs = motionInputsFromTaskModel(model);
  motion::LearnedSkills learned = motion::learnSkills(inputs);
  model.skills = skillRows(learned.skills, inputs);
  return learned;
}

void setSkillFlags(std::vector<taskdb::ProductPoseRow>& rows, const std::vector<motion::SkillSet>& skills,
                   const MotionInputs& inputs) {
  for (const auto& s : skills) {
    const MotionInputs::RowKey& key = rowKeyOf(inputs, s.objectName);
    for (auto& row : rows) {
      if (!rowOf(key, row.classId, row.instanceId)) continue;
      row.reach = row.timeId >= s.reachStartFrame && row.timeId < s.graspFrame;
      row.grasp = row.timeId == s.graspFrame;
      row.move = row.timeId > s.graspFrame && row.timeId < s.releaseFrame;
      row.release = row.timeId == s.releaseFrame;
    }
  }
}

void storeSkills(taskdb::TaskDatabase& db, int taskModelId, const std::vector<motion::SkillSet>& skills,
                 const MotionInputs& inputs) {
  const std::vector<taskdb::SkillRow> rows = skillRows(skills, inputs);
  taskdb::ScopedTransaction tx(db);
  if (!taskdb::TaskModelDao(db).get(taskModelId))
    throw core::InvalidInputError("no task model with id " + std::to_string(taskModelId) + " in '" + db.path() + "'");
  taskdb::SkillDao skillDao(db);
  for (const auto& old : skillDao.list(taskModelId)) skillDao.remove(taskModelId, old.classId, old.skill, old.instanceId);
  for (const auto& r : rows) skillDao.add(taskModelId, r);
  taskdb::ProductPoseDao poses(db);
  const std::vector<taskdb::ProductPoseRow> before = poses.list(taskModelId);
  std::vector<taskdb::ProductPoseRow> flagged = before;
  setSkillFlags(flagged, skills, inputs);
  for (std::size_t i = 0; i < flagged.size(); ++i)
    if (!(flagged[i] == before[i])) poses.update(taskModelId, flagged[i]);
  tx.commit();
}

taskdb::TaskModel taskModelFromTracks(const motion::DemoTracks& demo, const std::string& name,
                                      const std::string& instruction) {
  taskdb::TaskModel m;
  m.info.name = name;
  m.info.instruction = instruction;
  m.info.frame = demo.hand.frame();
  m.info.frameRate_hz = demo.hand.size() > 1 ? 1.0 / (demo.hand[1].t_s - demo.hand[0].t_s) : 30.0;
  for (std::size_t k = 0; k < demo.objects.size(); ++k) {
    const int id = static_cast<int>(k);
    taskdb::ProductRow p;
    p.objectId = id;
    p.objectName = demo.objects[k].name;
    p.classId = id;
    m.products.push_back(p);
    taskdb::GroundedProductRow g;  // no locations, colour or instance
    g.classId = id;
    g.objectName = demo.objects[k].name;
    m.groundedProducts.push_back(g);
    for (std::size_t i = 0; i < demo.objects[k].positions.size(); ++i) {
      const auto& s = demo.objects[k].positions[i];
      taskdb::ProductPoseRow r;
      r.classId = id;
      r.timeId = s.frame;
      r.p_m = s.valid ? s.p_m : Eigen::Vector3d::Zero();
      r.detected = s.valid;
      r.q = Eigen::Quaterniond(Eigen::AngleAxisd(demo.objects[k].yaw_rad[i], Eigen::Vector3d::UnitZ()));
      m.productPoses.push_back(r);
    }
  }
  for (const auto& planName : demo.planOrder)
    for (const auto& p : m.products)
      if (p.objectName == planName) m.targetObjectIds.push_back(p.objectId);
  for (const auto& s : demo.hand.samples())
    m.handPositions.push_back({s.frame, s.valid ? s.p_m : Eigen::Vector3d::Zero(), s.valid});
  return m;
}

}  // namespace srp::programming
