#include "srp/execution/TaskExecutor.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "srp/execution/MinimumJerkPathGenerator.h"

using srp::core::Pose3;
using namespace srp::execution;

namespace {
constexpr double kPlacementTol_m = 0.01;  // issue: within 1 cm of the planned pose

CellDescription defaultCell() { return CellDescription::loadScene(); }

Pose3 homeTcp() {
  Pose3 X = Pose3::Identity();
  X.linear() = Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitX()).toRotationMatrix();
  X.translation() = Eigen::Vector3d(0.0, 0.1, 0.3);
  return X;
}

SpatialRelation rel(const std::string& r, const std::string& name, std::optional<std::string> color = {}) {
  return {r, {name, color}};
}

/// Appendix C's plan of instruction 1.
ExecutionPlan instruction1() {
  ExecutionPlan p;
  p.steps.push_back({{"cuboid", {}}, {rel("from", "box", "blue")}, {rel("in", "box", "gray")}, {}, {}});
  p.steps.push_back({{"star", {}}, {}, {rel("next to", "cuboid"), rel("in", "box", "gray")}, {}, {}});
  p.steps.push_back({{"parallelogram", {}}, {}, {rel("beside", "star"), rel("in", "box", "gray")}, {}, {}});
  p.steps.push_back({{"octagon", {}}, {}, {rel("adjacent to", "parallelogram"), rel("in", "box", "gray")}, {}, {}});
  return p;
}

struct Cell {
  RobotModel model = RobotModel::defaultUr5();
  CellDescription cell = defaultCell();
  JointVector home = TaskExecutor::defaultHome(model, cell.X_world_base, homeTcp());
  std::unique_ptr<TaskExecutor> executor() const {
    return std::make_unique<TaskExecutor>(model, cell, home, std::make_shared<MinimumJerkPathGenerator>());
  }
};
}  // namespace

TEST(TaskExecutor, InstructionOneOnTheDefaultScene) {
  Cell c;
  auto ex = c.executor();
  const ExecutionReport report = ex->run(instruction1());
  std::cout << report.toText();
  ASSERT_EQ(report.steps.size(), 4u);
  for (const auto& s : report.steps) {
    EXPECT_EQ(s.status, StepStatus::Done) << s.object << ": " << s.reason;
    EXPECT_TRUE(s.relationsHold) << s.object;
    EXPECT_TRUE(s.insideContainer) << s.object;
    EXPECT_LT(s.placementError_m, kPlacementTol_m) << s.object;
  }
  EXPECT_GT(report.minTableClearance_m, 0.0);
  EXPECT_TRUE(report.allSucceeded());
  const auto j = report.toJson();
  EXPECT_EQ(j["steps"].size(), 4u);
  EXPECT_EQ(j["steps"][0]["status"], "done");
}

TEST(TaskExecutor, MissingPartIsSkippedAndTheOthersAreDone) {
  Cell c;
  auto& objs = c.cell.objects;
  objs.erase(std::remove_if(objs.begin(), objs.end(), [](const CellObject& o) { return o.name == "star"; }),
             objs.end());
  ExecutionPlan plan = instruction1();
  plan.steps.erase(plan.steps.begin() + 2, plan.steps.end());  // cuboid, star
  auto ex = c.executor();
  const ExecutionReport report = ex->run(plan);
  ASSERT_EQ(report.steps.size(), 2u);
  EXPECT_EQ(report.steps[0].status, StepStatus::Done);
  EXPECT_EQ(report.steps[1].status, StepStatus::Skipped);
  EXPECT_NE(report.steps[1].reason.find("no star"), std::string::npos) << report.steps[1].reason;
}

TEST(TaskExecutor, UnreachableTargetIsRefusedAndTheArmStaysPut) {
  Cell c;
  // Move the gray box out of reach (far corner of a large table).
  c.cell.tableHalfExtents_m = Eigen::Vector2d(2.0, 2.0);
  for (auto& o : c.cell.objects)
    if (o.name == "gray box") o.X_world_object.translation() = Eigen::Vector3d(1.3, 1.2, 0.0);
  ExecutionPlan plan = instruction1();
  plan.steps.resize(1);
  auto ex = c.executor();
  const JointVector q0 = ex->simulator().jointPositions();
  const ExecutionReport report = ex->run(plan);
  ASSERT_EQ(report.steps.size(), 1u);
  EXPECT_EQ(report.steps[0].status, StepStatus::Refused);
  EXPECT_NE(report.steps[0].reason.find("out of the arm's reach"), std::string::npos) << report.steps[0].reason;
  EXPECT_LT((ex->simulator().jointPositions() - q0).norm(), 1e-9);
}

// A path too fast for the joints (here: a generator three times faster than the
// default; in practice a learned DMP near a wrist singularity) is followed more
// slowly, not refused; with no slow-down allowed it is refused.
TEST(TaskExecutor, TooFastPathIsSlowedDownToTheJointSpeedLimits) {
  Cell c;
  MinimumJerkOptions fast;
  fast.meanSpeed_mps = 0.75;
  fast.meanAngularSpeed_radps = 2.4;
  fast.minSegmentDuration_s = 0.1;
  ExecutionPlan plan;
  plan.steps.push_back(instruction1().steps[0]);

  TaskExecutor slowed(c.model, c.cell, c.home, std::make_shared<MinimumJerkPathGenerator>(fast));
  const ExecutionReport done = slowed.run(plan);
  ASSERT_EQ(done.steps.size(), 1u);
  EXPECT_EQ(done.steps[0].status, StepStatus::Done) << done.steps[0].reason;
  EXPECT_GT(done.steps[0].slowDown, 1.0);
  EXPECT_LT(done.steps[0].placementError_m, kPlacementTol_m);

  ExecutionOptions noSlowDown;
  noSlowDown.maxSlowDown = 1.0;
  TaskExecutor strict(c.model, c.cell, c.home, std::make_shared<MinimumJerkPathGenerator>(fast), noSlowDown);
  const ExecutionReport refused = strict.run(plan);
  ASSERT_EQ(refused.steps.size(), 1u);
  EXPECT_EQ(refused.steps[0].status, StepStatus::Refused);
  EXPECT_NE(refused.steps[0].reason.find("above its limit"), std::string::npos) << refused.steps[0].reason;
}
