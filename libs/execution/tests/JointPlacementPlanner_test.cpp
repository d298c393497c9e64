#include "srp/execution/JointPlacementPlanner.h"

#include <gtest/gtest.h>


#include "srp/execution/PlacementContext.h"

using srp::core::Pose3;
using namespace srp::execution;

namespace {

constexpr double kClearanceTol_m = 1e-6;  // a kept clearance, up to rounding

SpatialRelation rel(const std::string& r, const std::string& landmark, std::optional<std::string> colour = {}) {
  return {r, {landmark, colour}, {}, ""};
}
SpatialRelation inGrayBox() { return rel("in", "box", "gray"); }

ExecutionStep step(const std::string& object, std::vector<SpatialRelation> target) {
  ExecutionStep s;
  s.object = {object, {}};
  s.target = std::move(target);
  return s;
}

SpatialRelation between(const std::string& a, const std::string& b) {
  SpatialRelation r = rel("between", a);
  r.secondLandmark = ObjectReference{b, {}};
  return r;
}

/// The default cell: parts in the blue box (left), the gray box at (0.16, 0.12).
CellDescription defaultCell() { return CellDescription::loadScene(); }

CellDescription moved(CellDescription c, const std::string& name, const Pose3& X) {
  for (auto& o : c.objects)
    if (o.name == name) o.X_world_object = X;
  return c;
}

/// Each step placed on its own, in plan order (the greedy planner): the index of the
/// first step it cannot place, or -1.
int greedyFailure(const PlacementPlanner& planner, CellDescription scene, const ExecutionPlan& plan) {
  for (std::size_t i = 0; i < plan.steps.size(); ++i) {
    const CellObject& part = *scene.find(plan.steps[i].object.name);
    const Placement p = planner.place(scene, part, plan.steps[i]);
    if (!p.X_world_object) return static_cast<int>(i);
    scene = moved(scene, part.name, *p.X_world_object);
  }
  return -1;
}

/// Every placed step's relations hold in the scene right after it (the parts of the
/// earlier steps at their planned poses).
void expectEveryRelationHolds(const JointPlacementPlanner& joint, const CellDescription& scene,
                              const ExecutionPlan& plan, const std::vector<PlannedPlacement>& planned) {
  CellDescription now = scene;
  for (std::size_t i = 0; i < planned.size(); ++i) {
    ASSERT_TRUE(planned[i].placement.X_world_object) << "step " << i + 1 << ": " << planned[i].placement.reason;
    now = moved(now, planned[i].part, *planned[i].placement.X_world_object);
    for (const auto& c : joint.planner().check(now, *now.find(planned[i].part), plan.steps[i],
                                               planned[i].placement.landmarkIds))
      EXPECT_TRUE(c.holds) << "step " << i + 1 << ": " << c.relation << " " << c.landmarks << ": " << c.detail;
    // And the rules: clear of the other parts by clearance_m (a tight place: minClearance_m).
    const CellObject& part = *now.find(planned[i].part);
    PlacementContext::Options rules =
        planned[i].placement.tight ? joint.planner().options().tight() : joint.planner().options();
    rules.clearance_m -= kClearanceTol_m;
    EXPECT_TRUE(PlacementContext(now, part, rules).isFree(part.X_world_object)) << "step " << i + 1;
  }
}

}  // namespace

// The first case: the cuboid in the gray box, then the star left of it in the gray
// box. Alone, the cuboid goes to the box's inner corner nearest to where it comes from (the
// left), leaving no room to its left; planned together it leaves room.
TEST(JointPlacementPlanner, AFirstPartLeavesRoomLeftOfItInTheBox) {
  const CellDescription cell = defaultCell();
  ExecutionPlan plan;
  plan.steps.push_back(step("cuboid", {inGrayBox()}));
  plan.steps.push_back(step("star", {rel("left of", "cuboid"), inGrayBox()}));
  const JointPlacementPlanner joint;
  ASSERT_EQ(greedyFailure(joint.planner(), cell, plan), 1) << "the greedy planner must be blocked here";
  const auto planned = joint.plan(cell, plan);
  ASSERT_EQ(planned.size(), 2u);
  expectEveryRelationHolds(joint, cell, plan, planned);
  EXPECT_EQ(planned[0].placement.container, "gray box");
  EXPECT_EQ(planned[1].placement.container, "gray box");
}

// The second case: two parts in the gray box, then a third between them. Alone,
// the cuboid and the star (both from the blue box's back left) go to the gray box's back
// left corner, side by side 8 mm apart: no room for the octagon between them.
TEST(JointPlacementPlanner, TwoPartsInTheBoxLeaveRoomForAThirdBetweenThem) {
  const CellDescription cell = defaultCell();
  ExecutionPlan plan;
  plan.steps.push_back(step("cuboid", {inGrayBox()}));
  plan.steps.push_back(step("star", {inGrayBox()}));
  plan.steps.push_back(step("octagon", {between("cuboid", "star"), inGrayBox()}));
  const JointPlacementPlanner joint;
  ASSERT_EQ(greedyFailure(joint.planner(), cell, plan), 2) << "the greedy planner must be blocked here";
  const auto planned = joint.plan(cell, plan);
  expectEveryRelationHolds(joint, cell, plan, planned);
  // Room enough to keep the full clearance: the first search (margins first) found it.
  EXPECT_FALSE(planned[2].placement.tight);
}

// One step: the joint plan is what the one-step planner chooses (before the refinement,
// which moves only tight places).
TEST(JointPlacementPlanner, OneStepIsPlacedAsThePlacementPlannerPlacesIt) {
  const CellDescription cell = defaultCell();
  JointPlacementPlanner::Options discrete;
  discrete.refine = false;
  const JointPlacementPlanner joint(PlacementContext::Options{}, discrete);
  for (const auto& target : {std::vector<SpatialRelation>{inGrayBox()},
                             {rel("right of", "star")},
                             {rel("next to", "octagon"), inGrayBox()},
                             {between("star", "octagon")}}) {
    ExecutionPlan plan;
    plan.steps.push_back(step("cuboid", target));
    const auto planned = joint.plan(cell, plan);
    const Placement alone = joint.planner().place(cell, *cell.find("cuboid"), plan.steps[0]);
    ASSERT_EQ(planned.size(), 1u);
    ASSERT_EQ(planned[0].placement.X_world_object.has_value(), alone.X_world_object.has_value())
        << target[0].relation << ": alone: " << alone.reason << "; joint: " << planned[0].placement.reason;
    if (!alone.X_world_object) continue;
    EXPECT_NEAR((planned[0].placement.X_world_object->translation() - alone.X_world_object->translation()).norm(), 0.0,
                1e-12);
  }
}

// A step no plan can satisfy (its landmarks stay where they are, 2 cm apart) is refused
// with the reason; the other steps are planned as if it were not there.
TEST(JointPlacementPlanner, AnImpossibleStepIsRefusedWithTheReasonAndTheOthersArePlaced) {
  CellDescription cell = defaultCell();
  const Pose3 star = cell.find("star")->X_world_object;
  Pose3 nearStar = star;
  nearStar.translation().x() = star.translation().x() - 0.025 - 0.02 - 0.02;  // octagon 2 cm left of the star
  cell = moved(cell, "octagon", nearStar);
  ExecutionPlan plan;
  plan.steps.push_back(step("cuboid", {between("star", "octagon")}));
  plan.steps.push_back(step("parallelogram", {inGrayBox()}));
  const JointPlacementPlanner joint;
  const auto planned = joint.plan(cell, plan);
  ASSERT_EQ(planned.size(), 2u);
  EXPECT_TRUE(planned[0].refused);
  EXPECT_FALSE(planned[0].placement.X_world_object);
  EXPECT_NE(planned[0].placement.reason.find("not enough room between the star and the octagon"), std::string::npos)
      << planned[0].placement.reason;
  ASSERT_TRUE(planned[1].placement.X_world_object) << planned[1].placement.reason;
  EXPECT_FALSE(planned[1].refused);
}

// A part that is not in the scene is not refused by the planner: the executor skips it
// saying it is missing; the other steps are planned.
TEST(JointPlacementPlanner, AMissingPartIsLeftToTheExecutor) {
  const CellDescription cell = defaultCell();
  ExecutionPlan plan;
  plan.steps.push_back(step("hexagon", {inGrayBox()}));
  plan.steps.push_back(step("cuboid", {inGrayBox()}));
  const auto planned = JointPlacementPlanner().plan(cell, plan);
  EXPECT_EQ(planned[0].part, "");
  EXPECT_FALSE(planned[0].refused);
  EXPECT_NE(planned[0].placement.reason.find("hexagon"), std::string::npos) << planned[0].placement.reason;
  EXPECT_TRUE(planned[1].placement.X_world_object);
}

// Left of and right of the same part in the box: the first part must go to the middle.
TEST(JointPlacementPlanner, PartsOnBothSidesOfTheFirstOne) {
  const CellDescription cell = defaultCell();
  ExecutionPlan plan;
  plan.steps.push_back(step("octagon", {inGrayBox()}));
  plan.steps.push_back(step("cuboid", {rel("left of", "octagon"), inGrayBox()}));
  plan.steps.push_back(step("star", {rel("right of", "octagon"), inGrayBox()}));
  const JointPlacementPlanner joint;
  ASSERT_GE(greedyFailure(joint.planner(), cell, plan), 1);
  const auto planned = joint.plan(cell, plan);
  expectEveryRelationHolds(joint, cell, plan, planned);
}

// The continuous refinement. A gray box shortened to 165 x 80 mm holds the star and the
// octagon with room for the cuboid (30 mm across) between them at the full clearance only
// when both touch their end walls' margins; the 5 mm candidate grid ends up to 5 mm short
// of a wall, so the discrete search finds only the tight place (3-8 mm gaps). The
// refinement moves the star and the octagon apart, towards their walls, until the gaps
// reach clearance_m, every relation still holding.
TEST(JointPlacementPlanner, RefinementWidensATightGap) {
  CellDescription cell = defaultCell();
  for (auto& o : cell.objects)
    if (o.name == "gray box") o.size_m = Eigen::Vector3d(0.165, 0.080, 0.06);
  ExecutionPlan plan;
  plan.steps.push_back(step("star", {inGrayBox()}));
  plan.steps.push_back(step("octagon", {inGrayBox()}));
  plan.steps.push_back(step("cuboid", {between("star", "octagon"), inGrayBox()}));
  JointPlacementPlanner::Options discrete;
  discrete.refine = false;
  const JointPlacementPlanner unrefined(PlacementContext::Options{}, discrete);
  const auto before = unrefined.plan(cell, plan);
  expectEveryRelationHolds(unrefined, cell, plan, before);
  ASSERT_TRUE(before[2].placement.tight) << "the construction must leave only a tight place on the grid";
  const JointPlacementPlanner refined;
  const auto after = refined.plan(cell, plan);
  expectEveryRelationHolds(refined, cell, plan, after);
  EXPECT_FALSE(after[2].placement.tight) << "the refinement should reach clearance_m here";
  for (std::size_t i = 0; i < 3; ++i)
    EXPECT_LE((after[i].placement.X_world_object->translation() - before[i].placement.X_world_object->translation()).norm(),
              0.02 * std::sqrt(2.0) + 1e-9)
        << "step " << i + 1 << " moved further than the refinement's 2 cm per coordinate";
}
