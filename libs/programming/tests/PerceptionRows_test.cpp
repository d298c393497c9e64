// The perception result as task-database rows (the store stage's mapping).
#include "srp/kb/KnowledgeBase.h"
#include "srp/programming/PerceptionRows.h"

#include <gtest/gtest.h>

#include "srp/core/Error.h"
#include "srp/core/Pose.h"

namespace srp::programming {
namespace {

using perception::ObjectTrajectory;
using perception::PerceptionResult;

const core::ObjectCatalogue& catalogue() {
  static const auto c = kb::loadCatalogue(core::ObjectCatalogue::defaultPath());
  return c;
}


TEST(TaskDbMapping, HandCarriedForwardAndObjectRows) {
  PerceptionResult r;
  for (int i = 0; i < 4; ++i) r.hand.append({i, i / 30.0, Eigen::Vector3d(0.1 * i, 0, 0.8), i == 1 || i == 2});
  ObjectTrajectory box;
  box.className = "gray box";
  box.classId = 0;
  box.isStatic = true;
  for (int i = 0; i < 4; ++i) box.samples.push_back({i, i / 30.0, core::makePoseYPR({0.1, 0.2, 0.85}, 0.5, 0, 0), i == 0, 0.9});
  r.objects.push_back(box);
  r.objects.push_back(ObjectTrajectory{"star", 5, false, {}});  // never seen: no rows
  const PerceptionRows rows = toTaskDbRows(r, catalogue());
  ASSERT_EQ(rows.handPositions.size(), 4u);
  EXPECT_FALSE(rows.handPositions[0].detected);
  EXPECT_NEAR(rows.handPositions[0].p_m.x(), 0.1, 1e-12);  // before the first: the first
  EXPECT_NEAR(rows.handPositions[3].p_m.x(), 0.2, 1e-12);  // after the last: the last
  EXPECT_TRUE(rows.handPositions[2].detected);
  ASSERT_EQ(rows.groundedProducts.size(), 1u);
  EXPECT_EQ(rows.groundedProducts[0].objectName, "gray box");
  EXPECT_EQ(rows.groundedProducts[0].colour.value_or(""), "gray");
  ASSERT_EQ(rows.productPoses.size(), 4u);
  EXPECT_NEAR(rows.productPoses[2].yaw_rad(), 0.5, 1e-9);
  EXPECT_FALSE(rows.productPoses[2].detected);
  PerceptionResult none;
  none.hand.append({0, 0.0, Eigen::Vector3d::Zero(), false});
  EXPECT_THROW(toTaskDbRows(none, catalogue()), core::InvalidInputError);
}

// Two cuboid instances: one GroundedProducts row each with its InstanceId and
// the colour word the scene gives it; every ProductPose row carries the id.
TEST(TaskDbMapping, InstancesKeepTheirIdAndColour) {
  PerceptionResult r;
  r.hand.append({0, 0.0, Eigen::Vector3d(0, 0, 0.8), true});
  for (const char* id : {"cuboid_red", "cuboid_blue"}) {
    ObjectTrajectory t{"cuboid", 3, false, {}};
    t.instanceId = id;
    t.samples.push_back({0, 0.0, core::makePoseYPR({0.1, 0.2, 0.85}, 0.5, 0, 0), true, 0.9});
    r.objects.push_back(t);
  }
  const PerceptionRows rows = toTaskDbRows(r, catalogue(), {{"cuboid_red", "red"}, {"cuboid_blue", "blue"}});
  ASSERT_EQ(rows.groundedProducts.size(), 2u);
  EXPECT_EQ(rows.groundedProducts[0].instanceId, "cuboid_red");
  EXPECT_EQ(rows.groundedProducts[0].colour.value_or(""), "red");
  EXPECT_EQ(rows.groundedProducts[1].instanceId, "cuboid_blue");
  EXPECT_EQ(rows.groundedProducts[1].colour.value_or(""), "blue");
  ASSERT_EQ(rows.productPoses.size(), 2u);
  EXPECT_EQ(rows.productPoses[0].instanceId, "cuboid_red");
  EXPECT_EQ(rows.productPoses[1].instanceId, "cuboid_blue");
}

}  // namespace
}  // namespace srp::programming
