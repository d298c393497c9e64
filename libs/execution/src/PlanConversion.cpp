#include "srp/execution/PlanConversion.h"

#include <algorithm>
#include <map>

#include "srp/core/Error.h"

namespace srp::execution {
namespace {

bool isSourceWord(const std::string& d) { return d == "from" || d == "out of" || d == "off" || d == "from inside"; }

ObjectReference refOf(const srp::taskdb::ProductRow& p) { return {p.objectName, p.color}; }

bool sameRelation(const SpatialRelation& a, const SpatialRelation& b) {
  return a.relation == b.relation && a.landmark.name == b.landmark.name && a.landmark.color == b.landmark.color;
}

void addUnique(std::vector<SpatialRelation>& list, const SpatialRelation& r) {
  if (std::none_of(list.begin(), list.end(), [&](const auto& x) { return sameRelation(x, r); })) list.push_back(r);
}

}  // namespace

ExecutionPlan planFromTaskModel(const srp::taskdb::TaskModel& model, const std::optional<srp::core::Pose3>& X_world_camera) {
  const std::string context = "task model " + std::to_string(model.info.id) + " ('" + model.info.name + "')";
  auto product = [&](int id) -> const srp::taskdb::ProductRow& {
    const auto* p = model.findProduct(id);
    if (!p) throw srp::core::InvalidInputError(context + ": no product with ObjectId " + std::to_string(id));
    return *p;
  };
  std::map<int, const srp::taskdb::SourceLocationRow*> sources;
  std::map<int, const srp::taskdb::TargetLocationRow*> targets;
  for (const auto& s : model.sourceLocations) sources[s.locationId] = &s;
  for (const auto& t : model.targetLocations) targets[t.locationId] = &t;

  ExecutionPlan plan;
  std::vector<std::vector<int>> sentencesOfStep;
  std::map<std::string, std::size_t> stepOfName;
  std::vector<bool> sourceUsed(0), targetUsed(0);
  std::map<int, bool> usedSource, usedTarget;
  auto addRelation = [&](ExecutionStep& step, const std::string& description, int landmarkId) {
    const SpatialRelation r{description, refOf(product(landmarkId))};
    addUnique(isSourceWord(description) ? step.source : step.target, r);
  };
  for (int objectId : model.targetObjectIds) {
    const auto& p = product(objectId);
    auto it = stepOfName.find(p.objectName);
    if (it == stepOfName.end()) {
      it = stepOfName.emplace(p.objectName, plan.steps.size()).first;
      plan.steps.push_back({refOf(p), {}, {}, {}, {}});
      sentencesOfStep.emplace_back();
    }
    ExecutionStep& step = plan.steps[it->second];
    if (p.sentenceId) sentencesOfStep[it->second].push_back(*p.sentenceId);
    if (p.sourceLocationId) {
      const auto s = sources.find(*p.sourceLocationId);
      if (s == sources.end())
        throw srp::core::InvalidInputError(context + ": product " + std::to_string(objectId) +
                                           " refers to a missing SourceLocation " + std::to_string(*p.sourceLocationId));
      addRelation(step, s->second->description, s->second->trajectorObjectId);
      usedSource[s->first] = true;
    }
    if (p.targetLocationId) {
      const auto t = targets.find(*p.targetLocationId);
      if (t == targets.end())
        throw srp::core::InvalidInputError(context + ": product " + std::to_string(objectId) +
                                           " refers to a missing TargetLocation " + std::to_string(*p.targetLocationId));
      addRelation(step, t->second->description, t->second->indicatorObjectId);
      usedTarget[t->first] = true;
    }
  }
  // Locations no target object refers to join the step of their landmark's sentence.
  auto attachOrphan = [&](const std::string& description, int landmarkId) {
    const auto& lm = product(landmarkId);
    if (!lm.sentenceId) return;
    for (std::size_t i = 0; i < plan.steps.size(); ++i)
      if (std::count(sentencesOfStep[i].begin(), sentencesOfStep[i].end(), *lm.sentenceId) &&
          lm.objectName != plan.steps[i].object.name) {
        addRelation(plan.steps[i], description, landmarkId);
        return;
      }
  };
  for (const auto& s : model.sourceLocations)
    if (!usedSource.count(s.locationId)) attachOrphan(s.description, s.trajectorObjectId);
  for (const auto& t : model.targetLocations)
    if (!usedTarget.count(t.locationId)) attachOrphan(t.description, t.indicatorObjectId);

  if (X_world_camera) attachDemoOffsets(plan, model, *X_world_camera);
  return plan;
}

void attachDemoOffsets(ExecutionPlan& plan, const srp::taskdb::TaskModel& model, const srp::core::Pose3& X_world_camera) {
  if (model.productPoses.empty()) return;
  {
    auto classOf = [&](const ObjectReference& ref) -> std::optional<int> {
      for (const auto& g : model.groundedProducts)
        if (g.objectName == ref.name || g.objectName == (ref.color ? *ref.color + ref.name : ref.name) ||
            g.objectName == (ref.color ? *ref.color + " " + ref.name : ref.name))
          return g.classId;
      for (const auto& p : model.products)
        if (p.objectName == ref.name && p.classId && (!ref.color || p.color == ref.color)) return p.classId;
      return std::nullopt;
    };
    auto finalPosition = [&](int classId) -> std::optional<Eigen::Vector3d> {
      const srp::taskdb::ProductPoseRow* last = nullptr;
      for (const auto& r : model.productPoses)
        if (r.classId == classId && (!last || r.timeId > last->timeId)) last = &r;
      if (!last) return std::nullopt;
      return last->p_m;
    };
    for (auto& step : plan.steps) {
      for (const auto& r : step.target) {
        if (!isNeighbourRelation(r.relation)) continue;
        const auto a = classOf(step.object), b = classOf(r.landmark);
        if (!a || !b) continue;
        const auto pa = finalPosition(*a), pb = finalPosition(*b);
        if (!pa || !pb) continue;
        const Eigen::Vector3d d_world = X_world_camera.linear() * (*pa - *pb);
        if (d_world.head<2>().norm() > 1e-3) step.demoOffsetFromNeighbour_m = d_world.head<2>();
      }
    }
  }
}

ExecutionPlan planFromLanguage(const srp::language::TaskPlan& plan) {
  ExecutionPlan out;
  for (const auto& s : plan.steps) {
    ExecutionStep step;
    // One type (language::ObjectRef): colour, ordinal, superlative and the
    // noun phrase's own relations reach SceneGrounder unchanged.
    step.object = s.object;
    for (const auto& l : s.source) step.source.push_back(l);
    for (const auto& l : s.target) step.target.push_back(l);
    out.steps.push_back(step);
  }
  return out;
}

}  // namespace srp::execution
