#include "srp/language/PlanTables.h"

#include <set>

#include "srp/core/Error.h"
#include "srp/core/SafeText.h"
#include "srp/taskdb/TaskDatabase.h"
#include "srp/taskdb/TaskModelStore.h"

namespace srp::language {

namespace {
std::optional<int> idOrNone(int id) { return id >= 0 ? std::optional<int>(id) : std::nullopt; }

struct RowWriter {
  taskdb::TaskModel& m;

  int addProduct(const ObjectRef& o, const TokenAnchor& a) {
    taskdb::ProductRow row;
    row.objectId = static_cast<int>(m.products.size());
    row.objectName = o.name;
    row.colour = o.colour;
    row.tokenId = idOrNone(a.tokenId);
    row.sentenceId = idOrNone(a.sentenceId);
    m.products.push_back(row);
    return row.objectId;
  }
  int addSource(int landmarkId, const std::string& relation) {
    const int id = static_cast<int>(m.sourceLocations.size());
    m.sourceLocations.push_back({id, landmarkId, relation});
    return id;
  }
  int addTarget(int landmarkId, const std::string& relation) {
    const int id = static_cast<int>(m.targetLocations.size());
    m.targetLocations.push_back({id, landmarkId, relation});
    return id;
  }
  /// Landmark products for locations[1..], each the SourceLocation of the previous landmark.
  void chain(int firstLandmark, const std::vector<LocationRef>& locations, const std::vector<TokenAnchor>& anchors) {
    int previous = firstLandmark;
    for (size_t i = 1; i < locations.size(); ++i) {
      const int landmark = addProduct(locations[i].landmark, i < anchors.size() ? anchors[i] : TokenAnchor{});
      m.products[previous].sourceLocationId = addSource(landmark, locations[i].relation);
      previous = landmark;
    }
  }
};
}  // namespace

taskdb::TaskModel planToTaskModel(const TaskPlan& plan, const std::string& name, const std::string& instruction) {
  core::require(!plan.steps.empty(), "task plan for '" + name + "' has no steps; nothing to store");
  taskdb::TaskModel m;
  m.info.name = name;
  m.info.instruction = instruction;
  RowWriter w{m};
  for (const auto& step : plan.steps) {
    const int object = w.addProduct(step.object, step.objectAnchor);
    m.targetObjectIds.push_back(object);
    auto anchor = [](const std::vector<TokenAnchor>& a, size_t i) { return i < a.size() ? a[i] : TokenAnchor{}; };
    if (!step.source.empty()) {
      const int landmark = w.addProduct(step.source[0].landmark, anchor(step.sourceAnchors, 0));
      m.products[object].sourceLocationId = w.addSource(landmark, step.source[0].relation);
      w.chain(landmark, step.source, step.sourceAnchors);
    }
    if (!step.target.empty()) {
      const int landmark = w.addProduct(step.target[0].landmark, anchor(step.targetAnchors, 0));
      m.products[object].targetLocationId = w.addTarget(landmark, step.target[0].relation);
      w.chain(landmark, step.target, step.targetAnchors);
    }
  }
  return m;
}

std::vector<PlanStep> planStepsFromTaskModel(const taskdb::TaskModel& model) {
  auto product = [&](int id) -> const taskdb::ProductRow& {
    const auto* p = model.findProduct(id);
    if (!p) throw core::InvalidInputError("task model '" + model.info.name + "': Products has no ObjectId " + std::to_string(id));
    return *p;
  };
  auto sourceLocation = [&](int id) -> const taskdb::SourceLocationRow& {
    for (const auto& l : model.sourceLocations)
      if (l.locationId == id) return l;
    throw core::InvalidInputError("task model '" + model.info.name + "': SourceLocations has no LocationId " + std::to_string(id));
  };
  auto follow = [&](int landmarkId, std::vector<LocationRef>& out) {
    std::set<int> seen;
    for (std::optional<int> next = product(landmarkId).sourceLocationId; next && seen.insert(*next).second;) {
      const auto& l = sourceLocation(*next);
      const auto& p = product(l.trajectorObjectId);
      out.push_back({l.description, {p.objectName, p.colour, std::nullopt, {}, {}}, std::nullopt, {}});
      next = p.sourceLocationId;
    }
  };
  std::vector<PlanStep> steps;
  for (int id : model.targetObjectIds) {
    const auto& p = product(id);
    PlanStep step;
    step.object = {p.objectName, p.colour, std::nullopt, {}, {}};
    follow(id, step.source);
    if (p.targetLocationId) {
      const taskdb::TargetLocationRow* t = nullptr;
      for (const auto& l : model.targetLocations)
        if (l.locationId == *p.targetLocationId) t = &l;
      if (!t)
        throw core::InvalidInputError("task model '" + model.info.name + "': TargetLocations has no LocationId " +
                                      std::to_string(*p.targetLocationId));
      const auto& landmark = product(t->indicatorObjectId);
      step.target.push_back(
          {t->description, {landmark.objectName, landmark.colour, std::nullopt, {}, {}}, std::nullopt, {}});
      follow(t->indicatorObjectId, step.target);
    }
    steps.push_back(step);
  }
  return steps;
}

int storePlan(const TaskPlan& plan, const std::string& dbPath, const std::string& name, const std::string& instruction) {
  core::requireSafeName(name, "task model name (--name)");
  if (plan.steps.empty()) {
    std::string why;
    for (const auto& w : plan.warnings) why += (why.empty() ? "" : "; ") + w;
    throw core::InvalidInputError("nothing written to '" + taskdb::TaskDatabase::displayName(dbPath) + "': the plan has no steps" +
                                  (why.empty() ? std::string() : " (" + why + ")"));
  }
  const taskdb::TaskModel model = planToTaskModel(plan, name, instruction);
  auto db = taskdb::TaskDatabase::open(dbPath);
  taskdb::TaskModelStore store(db);
  return store.write(model);
}

}  // namespace srp::language
