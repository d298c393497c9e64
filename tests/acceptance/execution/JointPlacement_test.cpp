// Acceptance (label `slow`): two- and three-step instructions where placing each step on
// its own (the one-step planner, in plan order) blocks a later relation, executed on the
// simulated UR5 with the joint placement planning of TaskExecutor::run.
//
// GreedyBlockedInstructions: seeded scenes (randomizeCell: the boxes shifted +-3 cm and
// turned +-0.2 rad, the parts anywhere in the blue box at any yaw) and seeded instructions
// of three kinds, all into the gray box:
//   A  "X in the box; Y <left of | right of | in front of | behind> X in the box"
//   B  "X in the box; Y in the box; Z between X and Y in the box"
//   C  "X in the box; Y <d> X in the box; Z <opposite of d> X in the box"
// An instance counts only when the greedy planner is blocked on it (asserted: at least
// kMinInstances such instances among the seeds). Each must end with every step done and
// its relations holding in the simulated scene, or with steps refused and the independent
// check below confirming that no placement of the steps together exists.
//
// ImpossibleStepsAreRefusedAndConfirmed: a narrow tray (the gray box 0.072 x 0.17 m, or
// turned by 90 degrees) where "Y left of / right of / in front of / behind X, both in the
// tray" cannot hold: refused before it moves, with the reason, confirmed by the same
// check, the first step done.
//
// The independent check (no planner code): both footprints inside the container's inner
// walls project onto the relation's direction d within the inner walls' projection; "left
// of" etc. need them disjoint along d (gap >= -1 mm, the after-placement check), "between"
// needs X, Z, Y one after the other along the line X-Y (any direction: the inner
// diagonal bounds it). A rectangle's projection is never narrower than its narrower side.
// So: narrower sides summed (less the checks' 1 mm per gap) > the inner projection
// (diagonal for "between") proves that no joint placement exists.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <iomanip>
#include <iostream>
#include <random>
#include <sstream>

#include "srp/execution/ExecutionSession.h"
#include "srp/execution/MinimumJerkPathGenerator.h"
#include "srp/execution/RandomScene.h"
#include "srp/execution/TaskExecutor.h"

using namespace srp::execution;
using srp::core::Pose3;

namespace {

/// Development seeds; a fresh block is given by SRP_JOINT_FIRST_SEED / SRP_JOINT_SEEDS (run once, reported apart).
constexpr int kFirstDevSeed = 1;
constexpr int kDevSeeds = 40;
constexpr int kMinInstances = 20;
constexpr double kCheckSlack_m = 0.001;  // the after-placement checks allow footprints 1 mm into each other
constexpr double kMovedTol_m = 1e-4;     // "nothing moved": every part within 0.1 mm

const char* const kDirections[] = {"left of", "right of", "in front of", "behind"};

std::string opposite(const std::string& d) {
  if (d == "left of") return "right of";
  if (d == "right of") return "left of";
  if (d == "in front of") return "behind";
  return "in front of";
}

SpatialRelation rel(const std::string& r, const std::string& landmark, std::optional<std::string> colour = {}) {
  return {r, {landmark, colour}, {}, ""};
}

ExecutionStep step(const std::string& object, std::vector<SpatialRelation> target) {
  ExecutionStep s;
  s.object = {object, {}};
  s.target = std::move(target);
  return s;
}

struct Instance {
  int seed = 0;
  char kind = 'A';
  std::string text;
  CellDescription cell;
  ExecutionPlan plan;
  std::string direction;  ///< A, C: the first relation's view direction
};

Instance makeInstance(int seed) {
  Instance in;
  in.seed = seed;
  std::mt19937 rng(static_cast<std::uint32_t>(seed));
  in.cell = randomizeCell(CellDescription::loadScene(), "blue box", static_cast<std::uint32_t>(seed));
  std::vector<std::string> parts = {"cuboid", "star", "parallelogram", "octagon"};
  std::shuffle(parts.begin(), parts.end(), rng);
  const int kind = std::uniform_int_distribution<int>(0, 2)(rng);
  in.direction = kDirections[std::uniform_int_distribution<int>(0, 3)(rng)];
  const SpatialRelation box = rel("in", "box", "gray");
  in.plan.steps.push_back(step(parts[0], {box}));
  in.kind = "ABC"[kind];
  std::ostringstream text;
  text << parts[0] << " in the gray box; ";
  if (kind == 0) {
    in.plan.steps.push_back(step(parts[1], {rel(in.direction, parts[0]), box}));
    text << parts[1] << " " << in.direction << " the " << parts[0] << " in the gray box";
  } else if (kind == 1) {
    in.plan.steps.push_back(step(parts[1], {box}));
    SpatialRelation between = rel("between", parts[0]);
    between.secondLandmark = ObjectReference{parts[1], {}};
    in.plan.steps.push_back(step(parts[2], {between, box}));
    text << parts[1] << " in the gray box; " << parts[2] << " between the " << parts[0] << " and the " << parts[1]
         << " in the gray box";
  } else {
    in.plan.steps.push_back(step(parts[1], {rel(in.direction, parts[0]), box}));
    in.plan.steps.push_back(step(parts[2], {rel(opposite(in.direction), parts[0]), box}));
    text << parts[1] << " " << in.direction << " the " << parts[0] << ", " << parts[2] << " "
         << opposite(in.direction) << " it, in the gray box";
  }
  in.text = text.str();
  return in;
}

/// The first step the greedy planner (each step alone, in plan order) cannot place, or -1.
int greedyFailure(const Instance& in) {
  const PlacementPlanner planner;
  CellDescription scene = in.cell;
  for (std::size_t i = 0; i < in.plan.steps.size(); ++i) {
    const CellObject& part = *scene.find(in.plan.steps[i].object.name);
    const Placement p = planner.place(scene, part, in.plan.steps[i]);
    if (!p.X_world_object) return static_cast<int>(i);
    for (auto& o : scene.objects)
      if (o.name == part.name) o.X_world_object = *p.X_world_object;
  }
  return -1;
}

double narrowerSide(const CellObject& o) { return std::min(o.size_m.x(), o.size_m.y()); }

/// Width of `box`'s inner footprint (inside its walls) along the unit direction d.
double innerProjection(const CellObject& box, const Eigen::Vector2d& d) {
  const Eigen::Vector2d ax = box.X_world_object.linear().col(0).head<2>(), ay = box.X_world_object.linear().col(1).head<2>();
  return std::abs(d.dot(ax)) * (box.size_m.x() - 2 * box.wallThickness_m) +
         std::abs(d.dot(ay)) * (box.size_m.y() - 2 * box.wallThickness_m);
}

/// The view direction of a relation phrase in the demonstrator's view of `cell` (camera x
/// on the table = right, image down = front), computed here from the camera pose.
Eigen::Vector2d viewDirection(const CellDescription& cell, const std::string& relation) {
  const Eigen::Vector2d right = cell.X_world_camera->linear().col(0).head<2>().normalized();
  Eigen::Vector2d front = cell.X_world_camera->linear().col(1).head<2>();
  front = (front - front.dot(right) * right).normalized();
  if (relation == "left of") return -right;
  if (relation == "right of") return right;
  if (relation == "in front of") return front;
  return -front;
}

/// True when the independent check proves that no placement of the steps together exists.
bool provablyImpossible(const Instance& in) {
  const CellObject& box = *in.cell.find("gray box");
  auto part = [&](std::size_t i) -> const CellObject& { return *in.cell.find(in.plan.steps[i].object.name); };
  if (in.kind == 'B') {
    const double diagonal = std::hypot(box.size_m.x() - 2 * box.wallThickness_m, box.size_m.y() - 2 * box.wallThickness_m);
    return narrowerSide(part(0)) + narrowerSide(part(1)) + narrowerSide(part(2)) - 2 * kCheckSlack_m > diagonal;
  }
  const double extent = innerProjection(box, viewDirection(in.cell, in.direction));
  double widths = narrowerSide(part(0)) + narrowerSide(part(1)) - kCheckSlack_m;
  if (in.kind == 'C') widths += narrowerSide(part(2)) - kCheckSlack_m;
  return widths > extent;
}

struct Outcome {
  bool correct = false;
  std::string line;
};

/// Executes the instance; correct when every step is done with its relations holding, or
/// when the refused steps are confirmed impossible and moved nothing.
Outcome execute(const Instance& in, const RobotModel& model) {
  const JointVector home = TaskExecutor::defaultHome(model, in.cell.X_world_base, defaultHomeTcp(in.cell));
  TaskExecutor ex(model, in.cell, home, std::make_shared<MinimumJerkPathGenerator>());
  std::vector<CellDescription> scenes{ex.perceive()};  // before the run, then after each step
  const ExecutionReport r = ex.run(in.plan, [&](const StepReport&) { scenes.push_back(ex.perceive()); });
  bool allDone = true, refusedConfirmed = true;
  std::ostringstream line;
  line << "seed " << in.seed << " [" << in.kind << "] " << in.text << ":";
  for (std::size_t k = 0; k < r.steps.size(); ++k) {
    const StepReport& s = r.steps[k];
    const bool done = s.status == StepStatus::Done && s.relationsHold;
    allDone = allDone && done;
    line << " " << toString(s.status) << (s.status == StepStatus::Done ? (s.relationsHold ? "" : " (RELATION NOT MET)") : "");
    if (s.status == StepStatus::Skipped || s.status == StepStatus::Refused) {
      double moved = 0.0;  // a refused step moves nothing
      for (const auto& o : scenes[k].objects)
        moved = std::max(moved, (scenes[k + 1].find(o.name)->X_world_object.translation() - o.X_world_object.translation()).norm());
      const bool confirmed = provablyImpossible(in) && !s.reason.empty() && moved < kMovedTol_m;
      refusedConfirmed = refusedConfirmed && confirmed;
      line << " (" << s.reason << (confirmed ? "; confirmed impossible" : "; NOT confirmed") << ")";
    } else if (!done) {
      refusedConfirmed = false;
    }
  }
  double planning = 0.0;
  for (const auto& s : r.steps) planning += s.planning_s;
  line << std::fixed << std::setprecision(1) << " [planning " << 1000 * planning / r.steps.size() << " ms/step]";
  return {allDone || refusedConfirmed, line.str()};
}

std::pair<int, int> seedBlock() {
  const char* first = std::getenv("SRP_JOINT_FIRST_SEED");
  const char* count = std::getenv("SRP_JOINT_SEEDS");
  return {first ? std::atoi(first) : kFirstDevSeed, count ? std::atoi(count) : kDevSeeds};
}

}  // namespace

TEST(JointPlacement, GreedyBlockedInstructions) {
  const RobotModel model = RobotModel::defaultUr5();
  const auto [first, seeds] = seedBlock();
  int instances = 0, correct = 0;
  std::vector<std::string> failures;
  for (int seed = first; seed < first + seeds; ++seed) {
    const Instance in = makeInstance(seed);
    const int blocked = greedyFailure(in);
    if (blocked < 0) continue;  // the greedy planner manages: not an instance of this family
    ++instances;
    const Outcome o = execute(in, model);
    correct += o.correct;
    std::cout << (o.correct ? "  ok     " : "  FAILED ") << o.line << " (greedy blocked at step " << blocked + 1 << ")\n";
    if (!o.correct) failures.push_back(o.line);
  }
  std::cout << "greedy-blocked instructions, seeds " << first << "-" << first + seeds - 1
            << (first == kFirstDevSeed && seeds == kDevSeeds ? " (development seeds)" : " (not the development seeds)")
            << ": " << correct << "/" << instances << " correct\n";
  EXPECT_GE(instances, kMinInstances) << "too few seeds where the greedy planner is blocked";
  EXPECT_EQ(correct, instances);
  for (const auto& f : failures) ADD_FAILURE() << f;
}

TEST(JointPlacement, ImpossibleStepsAreRefusedAndConfirmed) {
  const RobotModel model = RobotModel::defaultUr5();
  int n = 0;
  for (const char* direction : kDirections) {
    Instance in;
    in.seed = ++n;
    in.kind = 'A';
    in.direction = direction;
    in.cell = CellDescription::loadScene();
    const bool across = std::string(direction) == "left of" || std::string(direction) == "right of";
    for (auto& o : in.cell.objects)
      if (o.name == "gray box") o.size_m = across ? Eigen::Vector3d(0.072, 0.17, 0.06) : Eigen::Vector3d(0.22, 0.072, 0.06);
    const SpatialRelation box = rel("in", "box", "gray");
    in.plan.steps.push_back(step("octagon", {box}));
    in.plan.steps.push_back(step("cuboid", {rel(direction, "octagon"), box}));
    in.text = std::string("octagon in the narrow gray box; cuboid ") + direction + " the octagon in it";
    ASSERT_TRUE(provablyImpossible(in)) << in.text;
    const Outcome o = execute(in, model);
    std::cout << (o.correct ? "  ok     " : "  FAILED ") << o.line << "\n";
    EXPECT_TRUE(o.correct) << o.line;
    EXPECT_NE(o.line.find("done skipped"), std::string::npos) << "the octagon done, the cuboid refused: " << o.line;
  }
}
