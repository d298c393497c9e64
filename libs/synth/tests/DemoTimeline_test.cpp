#include "srp/kb/KnowledgeBase.h"
#include "srp/synth/DemoTimeline.h"

#include <gtest/gtest.h>

#include "srp/core/Error.h"
#include "srp/synth/PickPlacePlan.h"

namespace {

constexpr double kRigidTranslationTol_m = 1e-9;   // carried object vs hand: exactly rigid
constexpr double kRigidRotationTol_rad = 1e-9;
constexpr double kFlatTol_rad = 1e-6;             // placed objects stand upright

struct Fixture {
  srp::core::Scene scene = srp::core::Scene::load(std::string(SRP_SIM_DIR) + "/scenes/default.json");
  srp::core::ObjectCatalogue catalogue = srp::kb::loadCatalogue(scene.cataloguePath);
  srp::synth::HandModel hand;
};

TEST(PickPlacePlan, DefaultPlanGroundsInstructionOne) {
  Fixture f;
  const auto steps = srp::synth::groundPlan(srp::synth::defaultPlanJson(), f.scene, f.catalogue);
  ASSERT_EQ(steps.size(), 4u);
  const std::vector<std::string> objects = {"cuboid", "star", "parallelogram", "octagon"};
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(steps[i].objectId, objects[i]);
    EXPECT_EQ(steps[i].sourceId, "blue box");
    EXPECT_EQ(steps[i].targetId, "gray box");
    EXPECT_EQ(steps[i].referenceId, i == 0 ? "" : objects[i - 1]);
  }
}

// Appendix A words every neighbour relation differently ("near", "alongside", ...).
TEST(PickPlacePlan, EveryNeighbourWordingOfAppendixAPlacesBesideTheLandmark) {
  Fixture f;
  for (const char* relation : {"near", "alongside", "beside", "adjacent to"}) {
    auto plan = srp::synth::defaultPlanJson();
    plan["steps"][1]["target"][0]["relation"] = relation;
    const auto steps = srp::synth::groundPlan(plan, f.scene, f.catalogue);
    EXPECT_EQ(steps[1].referenceId, "cuboid") << relation;
    EXPECT_EQ(steps[1].targetId, "gray box") << relation;
  }
}

TEST(PickPlacePlan, ErrorsNameTheStepAndField) {
  Fixture f;
  auto plan = srp::synth::defaultPlanJson();
  plan["steps"][1]["object"]["name"] = "teapot";
  try {
    srp::synth::groundPlan(plan, f.scene, f.catalogue);
    FAIL();
  } catch (const srp::core::InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("step 2: object"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("teapot"), std::string::npos) << e.what();
  }
  plan = srp::synth::defaultPlanJson();
  plan["steps"][0].erase("target");
  try {
    srp::synth::groundPlan(plan, f.scene, f.catalogue);
    FAIL();
  } catch (const srp::core::InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("'target'"), std::string::npos) << e.what();
  }
}

TEST(DemoTimeline, MinimumJerkProfile) {
  EXPECT_DOUBLE_EQ(srp::synth::minimumJerk(0.0), 0.0);
  EXPECT_DOUBLE_EQ(srp::synth::minimumJerk(0.5), 0.5);
  EXPECT_DOUBLE_EQ(srp::synth::minimumJerk(1.0), 1.0);
  constexpr double h = 1e-4;  // zero velocity at both ends
  EXPECT_NEAR(srp::synth::minimumJerk(h) / h, 0.0, 1e-6);
  EXPECT_NEAR((1.0 - srp::synth::minimumJerk(1.0 - h)) / h, 0.0, 1e-6);
}

// The default demonstration: carried objects are rigid in the hand between
// grasp and release, land upright in the gray box without overlapping, and the
// hand is out of view for the first and last second.
TEST(DemoTimeline, DefaultDemoIsPhysicallyConsistent) {
  Fixture f;
  const auto steps = srp::synth::groundPlan(srp::synth::defaultPlanJson(), f.scene, f.catalogue);
  srp::synth::DemoOptions options;
  options.seed = 7;
  const auto timeline = srp::synth::planDemonstration(f.scene, f.catalogue, steps, f.hand, options);
  ASSERT_EQ(timeline.events.size(), 4u);
  const double fps = f.scene.fps;
  EXPECT_GT(timeline.duration_s(), 12.0);
  EXPECT_LT(timeline.duration_s(), 45.0);

  for (const auto& e : timeline.events) {
    SCOPED_TRACE(e.objectId);
    ASSERT_LT(e.graspFrame, e.releaseFrame);
    int oi = 0;
    while (timeline.scene.objects[oi].id != e.objectId) ++oi;
    for (int k = e.graspFrame; k <= e.releaseFrame; ++k) {
      const auto& fr = timeline.frames[k];
      const srp::core::Pose3 X_hand_object = fr.X_world_hand.inverse() * fr.X_world_objects[oi];
      ASSERT_LT((X_hand_object.translation() - e.X_hand_object.translation()).norm(), kRigidTranslationTol_m);
      ASSERT_LT(srp::core::rotationAngleBetween(X_hand_object.linear(), e.X_hand_object.linear()), kRigidRotationTol_rad);
      ASSERT_EQ(fr.carriedObject, oi);
    }
    // Still before the grasp and after the release.
    const auto& before = timeline.frames[e.graspFrame - 1].X_world_objects[oi];
    EXPECT_LT((before.translation() - e.X_world_object_start.translation()).norm(), 1e-12);
    const auto& last = timeline.frames.back().X_world_objects[oi];
    EXPECT_LT((last.translation() - e.X_world_object_end.translation()).norm(), 1e-12);
    // Upright in the gray box, on its floor.
    EXPECT_LT(std::acos(std::clamp(last.linear()(2, 2), -1.0, 1.0)), kFlatTol_rad + 1e-3);
    const auto& box = *timeline.scene.findObject("gray box");
    const Eigen::Vector3d p_box = box.X_world_object.inverse() * last.translation();
    EXPECT_LT(std::abs(p_box.x()), 0.11);
    EXPECT_LT(std::abs(p_box.y()), 0.085);
    EXPECT_NEAR(p_box.z(), 0.006, 2e-3);
  }
  // Placed parts do not overlap (footprint circles may touch: check centres).
  for (std::size_t a = 0; a < timeline.events.size(); ++a)
    for (std::size_t b = a + 1; b < timeline.events.size(); ++b)
      EXPECT_GT((timeline.events[a].X_world_object_end.translation() - timeline.events[b].X_world_object_end.translation())
                    .head<2>().norm(), 0.03);
  // "next to": each part lands within a hand's width of its reference.
  for (std::size_t i = 1; i < timeline.events.size(); ++i)
    EXPECT_LT((timeline.events[i].X_world_object_end.translation() -
               timeline.events[i - 1].X_world_object_end.translation()).head<2>().norm(), 0.09)
        << timeline.events[i].objectId << " next to " << timeline.events[i - 1].objectId;
  // Hand out of view at the start and the end (palm centre outside the image).
  const auto X_camera_world = timeline.scene.X_world_camera.inverse();
  for (int k : {0, static_cast<int>(fps) - 1, static_cast<int>(timeline.frames.size()) - 1,
                static_cast<int>(timeline.frames.size() - fps)}) {
    const auto uv = timeline.scene.intrinsics.project(X_camera_world * timeline.frames[k].X_world_hand.translation());
    EXPECT_TRUE(!uv || !timeline.scene.intrinsics.contains(uv->x(), uv->y())) << "frame " << k;
    EXPECT_EQ(timeline.frames[k].phase, "idle");
  }
}

// "Move the cuboid to the gray box, then back to the blue box": the second
// step starts where the first ended.
TEST(DemoTimeline, ObjectMovedTwiceStartsWhereItWasPut) {
  Fixture f;
  auto plan = srp::synth::defaultPlanJson();
  auto back = plan["steps"][0];
  back["source"][0]["landmark"]["color"] = "gray";
  back["target"] = nlohmann::json::array({{{"relation", "in"}, {"landmark", {{"name", "box"}, {"color", "blue"}}}}});
  plan["steps"] = nlohmann::json::array({plan["steps"][0], back});
  const auto steps = srp::synth::groundPlan(plan, f.scene, f.catalogue);
  ASSERT_EQ(steps.size(), 2u);
  EXPECT_EQ(steps[1].sourceId, "gray box");
  EXPECT_EQ(steps[1].targetId, "blue box");
  const auto timeline = srp::synth::planDemonstration(f.scene, f.catalogue, steps, f.hand, {});
  ASSERT_EQ(timeline.events.size(), 2u);
  EXPECT_LT((timeline.events[1].X_world_object_start.translation() - timeline.events[0].X_world_object_end.translation())
                .norm(), 1e-9);
}

TEST(DemoTimeline, SeedRandomisesPlacementsAndRepeats) {
  Fixture f;
  const auto steps = srp::synth::groundPlan(srp::synth::defaultPlanJson(), f.scene, f.catalogue);
  srp::synth::DemoOptions a, b;
  a.seed = 1;
  b.seed = 2;
  const auto t1 = srp::synth::planDemonstration(f.scene, f.catalogue, steps, f.hand, a);
  const auto t1again = srp::synth::planDemonstration(f.scene, f.catalogue, steps, f.hand, a);
  const auto t2 = srp::synth::planDemonstration(f.scene, f.catalogue, steps, f.hand, b);
  ASSERT_EQ(t1.frames.size(), t1again.frames.size());
  EXPECT_TRUE(t1.frames[200].X_world_hand.isApprox(t1again.frames[200].X_world_hand));
  EXPECT_GT((t1.events[0].X_world_object_start.translation() - t2.events[0].X_world_object_start.translation()).norm(),
            1e-3);
  srp::synth::DemoOptions fixed;
  fixed.randomise = false;
  const auto t0 = srp::synth::planDemonstration(f.scene, f.catalogue, steps, f.hand, fixed);
  EXPECT_LT((t0.events[0].X_world_object_start.translation() - f.scene.findObject("cuboid")->X_world_object.translation())
                .norm(), 1e-12);
}

}  // namespace
