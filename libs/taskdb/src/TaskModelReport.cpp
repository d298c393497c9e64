#include "srp/taskdb/TaskModelReport.h"

#include <algorithm>
#include <iomanip>
#include <map>
#include <sstream>

#include "srp/core/Text.h"

namespace srp::taskdb {

namespace {

std::string describe(const TaskModel& m, int objectId) {
  const ProductRow* p = m.findProduct(objectId);
  if (!p) return "?" + std::to_string(objectId);
  return p->colour ? *p->colour + " " + p->objectName : p->objectName;
}

template <typename Rows, typename LandmarkOf>
std::optional<std::string> location(const TaskModel& m, const Rows& rows, std::optional<int> id, LandmarkOf landmarkOf) {
  if (!id) return std::nullopt;
  for (const auto& r : rows)
    if (r.locationId == *id) return r.description + " " + describe(m, landmarkOf(r));
  return "location " + std::to_string(*id) + " (missing)";
}

std::string opt(const std::optional<int>& v) { return v ? std::to_string(*v) : ""; }
std::string opt(const std::optional<std::string>& v) { return v ? *v : ""; }

std::string num(double v) {
  std::ostringstream s;
  s << std::setprecision(6) << v;
  return s.str();
}

std::string camel(const std::string& name) {
  std::string out;
  bool up = true;
  for (char c : name) {
    if (c == ' ' || c == '_') { up = true; continue; }
    out += up ? static_cast<char>(std::toupper(static_cast<unsigned char>(c))) : c;
    up = false;
  }
  return out;
}

// Prints rows [0, n) or, with maxRows, the first maxRows and a "..." line.
template <typename F>
void rows(std::ostream& out, std::size_t n, int maxRows, int columns, F printRow) {
  const std::size_t shown = maxRows > 0 ? std::min<std::size_t>(n, static_cast<std::size_t>(maxRows)) : n;
  for (std::size_t i = 0; i < shown; ++i) printRow(i);
  if (shown < n) {
    for (int c = 0; c < columns; ++c) out << (c ? "\t" : "") << "...";
    out << "\n";
  }
}

}  // namespace

std::vector<PlanStepView> planSteps(const TaskModel& m) {
  std::vector<PlanStepView> steps;
  const auto sourceLandmark = [](const SourceLocationRow& r) { return r.trajectorObjectId; };
  const auto targetLandmark = [](const TargetLocationRow& r) { return r.indicatorObjectId; };
  for (int id : m.targetObjectIds) {
    const ProductRow* p = m.findProduct(id);
    const std::string name = p ? p->objectName : "?";
    if (steps.empty() || core::toLowerAscii(steps.back().objectName) != core::toLowerAscii(name)) {
      steps.push_back({});
      steps.back().objectName = name;
    }
    PlanStepView& s = steps.back();
    s.objectIds.push_back(id);
    if (!p) continue;
    if (p->colour && !s.colour) s.colour = p->colour;
    if (auto src = location(m, m.sourceLocations, p->sourceLocationId, sourceLandmark)) s.sources.push_back(*src);
    if (auto dst = location(m, m.targetLocations, p->targetLocationId, targetLandmark)) s.targets.push_back(*dst);
  }
  return steps;
}

void printTaskModel(const TaskModel& m, std::ostream& out) {
  const auto& i = m.info;
  out << "Task model " << i.id << ": '" << i.name << "' version " << i.version << " (created " << i.createdUtc
      << ")\n";
  if (!i.instruction.empty()) out << "Instruction: " << i.instruction << "\n";
  out << "Frame: " << i.frame << ", " << num(i.frameRate_hz) << " FPS";
  if (i.intrinsics)
    out << ", camera " << i.intrinsics->width_px << "x" << i.intrinsics->height_px << " fx " << num(i.intrinsics->fx_px);
  out << "\n\nPlan (" << planSteps(m).size() << " steps):\n";
  out << "  #  object                 source                        target\n";
  int n = 0;
  for (const auto& s : planSteps(m)) {
    const auto join = [](const std::vector<std::string>& v) {
      std::string r;
      for (const auto& x : v) r += (r.empty() ? "" : "; ") + x;
      return r.empty() ? std::string("-") : r;
    };
    const std::string object = s.colour ? *s.colour + " " + s.objectName : s.objectName;
    out << "  " << std::left << std::setw(3) << ++n << std::setw(23) << object << std::setw(30) << join(s.sources)
        << join(s.targets) << "\n";
  }
  if (!m.groundedProducts.empty()) {
    out << "\nGrounded objects:\n";
    for (const auto& g : m.groundedProducts) {
      std::size_t count = 0;
      std::optional<int> grasp, release;
      for (const auto& p : m.productPoses) {
        if (p.classId != g.classId || p.instanceId != g.instanceId) continue;
        ++count;
        if (p.grasp && !grasp) grasp = p.timeId;
        if (p.release && !release) release = p.timeId;
      }
      out << "  class " << g.classId << " " << g.objectName;
      if (!g.instanceId.empty()) out << " (instance " << g.instanceId << ")";
      out << ": " << count << " poses";
      if (grasp) out << ", grasp at frame " << *grasp;
      if (release) out << ", release at frame " << *release;
      out << "\n";
    }
  }
  if (!m.skills.empty()) {
    out << "\nSkills:\n";
    for (const auto& s : m.skills) {
      const GroundedProductRow* g = m.findGrounded(s.classId);
      out << "  " << (g ? g->objectName : std::to_string(s.classId)) << (s.instanceId.empty() ? "" : " " + s.instanceId)
          << " " << core::toString(s.skill) << ": frames "
          << s.startTimeId << "-" << s.endTimeId;
      if (s.parameters.contains("class")) out << " (" << s.parameters.at("class").get<std::string>() << ")";
      out << "\n";
    }
  }
  if (m.scene) {
    const auto& sc = *m.scene;
    const Eigen::Vector3d camera = sc.X_table_camera.translation();
    out << "\nPerceived scene (table frame, metres): table " << num(sc.tableSize_m.x()) << " x " << num(sc.tableSize_m.y())
        << ", camera at (" << num(camera.x()) << ", " << num(camera.y()) << ", " << num(camera.z()) << ")\n";
    for (const auto& o : sc.objects) {
      const bool observed = std::any_of(sc.observedClasses.begin(), sc.observedClasses.end(),
                                        [&](const auto& c) { return c.name == o.className; });
      const Eigen::Vector3d p = o.X_table_object.translation();
      out << "  " << o.objectId << " (" << o.className << (observed ? ", observed, no CAD" : "") << ") at ("
          << num(p.x()) << ", " << num(p.y()) << ", " << num(p.z()) << ")\n";
    }
  }
  out << "\nRows: " << m.products.size() << " products, " << m.handPositions.size() << " hand positions, "
      << m.productPoses.size() << " object poses, " << m.skills.size() << " skills\n";
}

void writeAppendixC(const TaskModel& m, std::ostream& out, int maxRows) {
  out << "Table C.1: Products\n\nObjectId\tObjectName\tSourceLocation\tTargetLocation\tColor\tTokenId\tSentenceId\tClassId\n";
  for (const auto& p : m.products)
    out << p.objectId << "\t" << p.objectName << "\t" << opt(p.sourceLocationId) << "\t" << opt(p.targetLocationId)
        << "\t" << opt(p.colour) << "\t" << opt(p.tokenId) << "\t" << opt(p.sentenceId) << "\t" << opt(p.classId) << "\n";
  out << "\nTable C.2: SourceLocations\n\nLocationId\tTrajectorObjectId\tDescription\n";
  for (const auto& s : m.sourceLocations) out << s.locationId << "\t" << s.trajectorObjectId << "\t" << s.description << "\n";
  out << "\nTable C.3: TargetLocations\n\nLocationId\tIndicatorObjectId\tDescription\n";
  for (const auto& t : m.targetLocations) out << t.locationId << "\t" << t.indicatorObjectId << "\t" << t.description << "\n";
  out << "\nTable C.4: TaskModelTargetObjects\n\nTaskModelId\tTargetObjectId\n";
  for (int id : m.targetObjectIds) out << m.info.id << "\t" << id << "\n";
  out << "\nTable C.5: HandPositions\n\nTimeId\tTaskModelId\tX\tY\tZ\n";
  rows(out, m.handPositions.size(), maxRows, 5, [&](std::size_t i) {
    const auto& h = m.handPositions[i];
    out << h.timeId << "\t" << m.info.id << "\t" << num(h.p_m.x()) << "\t" << num(h.p_m.y()) << "\t" << num(h.p_m.z()) << "\n";
  });
  out << "\nTable C.6: GroundedProducts\n\nClassId\tObjectName\tSourceLocation\tTargetLocation\tColor\n";
  for (const auto& g : m.groundedProducts)
    out << g.classId << "\t" << g.objectName << "\t" << opt(g.sourceLocationId) << "\t" << opt(g.targetLocationId)
        << "\t" << opt(g.colour) << "\n";
  int table = 7;
  for (const auto& g : m.groundedProducts) {
    std::vector<const ProductPoseRow*> poses;
    for (const auto& p : m.productPoses)
      if (p.classId == g.classId) poses.push_back(&p);
    if (poses.empty()) continue;
    out << "\nTable C." << table++ << ": ProductPose" << camel(g.objectName)
        << "\n\nTimeId\tTaskModelId\tX\tY\tZ\tRz\tReach\tGrasp\tMove\tRelease\n";
    rows(out, poses.size(), maxRows, 10, [&](std::size_t i) {
      const auto& p = *poses[i];
      const auto flag = [](bool b) { return b ? "1" : ""; };
      out << p.timeId << "\t" << m.info.id << "\t" << num(p.p_m.x()) << "\t" << num(p.p_m.y()) << "\t" << num(p.p_m.z())
          << "\t" << num(p.yaw_rad()) << "\t" << flag(p.reach) << "\t" << flag(p.grasp) << "\t" << flag(p.move) << "\t"
          << flag(p.release) << "\n";
    });
  }
}

}  // namespace srp::taskdb
