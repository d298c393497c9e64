// The duplicate-parts scene: two parts of one class, different colours, the
// other one on the moved one's way to the container; the plan grounds to the
// moved instance (PickPlacePlan's colour rule), and the demo plans.
#include <gtest/gtest.h>

#include "srp/core/Error.h"
#include "srp/kb/KnowledgeBase.h"
#include "srp/synth/DemoTimeline.h"
#include "srp/synth/DuplicatePartsDemo.h"
#include "srp/synth/HandModel.h"
#include "srp/synth/PickPlacePlan.h"

namespace srp::synth {
namespace {

struct Base {
  core::Scene scene = core::Scene::load(std::string(SRP_SIM_DIR) + "/scenes/default.json");
  core::ObjectCatalogue catalogue = kb::loadCatalogue(scene.cataloguePath);
};

TEST(DuplicatePartsDemo, TwoColouredInstancesOnTheWayAndThePlanMovesTheNamedOne) {
  constexpr double kMinGap_m = 0.045;   // the parts' centres at least this far apart (a 5 cm cuboid each)
  constexpr double kMaxOffWay_m = 0.04 + 1e-9;  // DuplicatePartsOptions::sideMax_m
  const Base b;
  int movedRed = 0;
  for (std::uint32_t seed = 1; seed <= 10; ++seed) {
    const DuplicatePartsDemo d = makeDuplicatePartsDemo(b.scene, b.catalogue, seed);
    const auto* moved = d.scene.findObject(d.movedId);
    const auto* other = d.scene.findObject(d.otherId);
    ASSERT_TRUE(moved && other);
    EXPECT_EQ(moved->className, "cuboid");
    EXPECT_EQ(other->className, "cuboid");
    EXPECT_NE(moved->colour, other->colour);
    movedRed += moved->colour == "red";
    const Eigen::Vector2d a = moved->X_world_object.translation().head<2>();
    const Eigen::Vector2d g = d.scene.findObject("gray box")->X_world_object.translation().head<2>();
    const Eigen::Vector2d p = other->X_world_object.translation().head<2>();
    EXPECT_GT((p - a).norm(), kMinGap_m) << "seed " << seed;
    const Eigen::Vector2d u = (g - a).normalized();
    EXPECT_LE(std::abs(u.x() * (p - a).y() - u.y() * (p - a).x()), kMaxOffWay_m) << "seed " << seed;
    // The plan's colour word picks the moved instance, and the demo can be planned.
    const auto steps = groundPlan(d.plan, d.scene, b.catalogue);
    ASSERT_EQ(steps.size(), 1u);
    EXPECT_EQ(steps[0].objectId, d.movedId);
    EXPECT_EQ(steps[0].targetId, "gray box");
    EXPECT_NO_THROW(planDemonstration(d.scene, b.catalogue, steps, HandModel(HandModel::Options{}), DemoOptions{}))
        << "seed " << seed;
    // Deterministic in the seed.
    EXPECT_EQ(makeDuplicatePartsDemo(b.scene, b.catalogue, seed).scene.toJson(), d.scene.toJson());
  }
  EXPECT_EQ(movedRed, 5) << "even seeds move the red cuboid, odd ones the blue";
}

TEST(DuplicatePartsDemo, UnknownTargetIsAClearError) {
  const Base b;
  DuplicatePartsOptions o;
  o.targetId = "no such box";
  EXPECT_THROW(makeDuplicatePartsDemo(b.scene, b.catalogue, 1, o), core::InvalidInputError);
}

}  // namespace
}  // namespace srp::synth
