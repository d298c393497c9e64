#include "srp/execution/PlanConversion.h"

#include <gtest/gtest.h>

#include "srp/core/Error.h"
#include "srp/core/Json.h"

using namespace srp::execution;

TEST(PlanConversion, AppendixCBecomesTheFourStepPlan) {
  const auto j = srp::core::readJsonFile(std::string(SRP_DATASETS_DIR) + "/examples/appendix_c_instruction1.json");
  const auto model = srp::taskdb::taskModelFromJson(j, "appendix C");
  const ExecutionPlan plan = planFromTaskModel(model);
  ASSERT_EQ(plan.steps.size(), 4u);
  EXPECT_EQ(plan.steps[0].object.name, "cuboid");
  EXPECT_EQ(plan.steps[1].object.name, "star");
  EXPECT_EQ(plan.steps[2].object.name, "parallelogram");
  EXPECT_EQ(plan.steps[3].object.name, "octagon");
  // cuboid: from the blue box, in the gray box.
  ASSERT_EQ(plan.steps[0].source.size(), 1u);
  EXPECT_EQ(plan.steps[0].source[0].relation, "from");
  EXPECT_EQ(plan.steps[0].source[0].landmark.color.value_or(""), "blue");
  ASSERT_EQ(plan.steps[0].target.size(), 1u);
  EXPECT_EQ(plan.steps[0].target[0].relation, "in");
  EXPECT_EQ(plan.steps[0].target[0].landmark.color.value_or(""), "gray");
  // star: next to the cuboid (stored as a source location) and, via its sentence, in the gray box.
  bool nextToCuboid = false, inGray = false;
  for (const auto& r : plan.steps[1].target) {
    nextToCuboid |= r.relation == "next to" && r.landmark.name == "cuboid";
    inGray |= r.relation == "in" && r.landmark.color.value_or("") == "gray";
  }
  EXPECT_TRUE(nextToCuboid);
  EXPECT_TRUE(inGray);
  EXPECT_EQ(plan.steps[2].target.at(0).relation, "beside");
  EXPECT_EQ(plan.steps[2].target.at(0).landmark.name, "star");
  bool nextToParallelogram = false;
  for (const auto& r : plan.steps[3].target) nextToParallelogram |= r.landmark.name == "parallelogram";
  EXPECT_TRUE(nextToParallelogram);
}

TEST(PlanConversion, DanglingReferenceIsAClearError) {
  const auto j = srp::core::readJsonFile(std::string(SRP_DATASETS_DIR) + "/examples/appendix_c_instruction1.json");
  auto model = srp::taskdb::taskModelFromJson(j, "appendix C");
  model.targetObjectIds.push_back(99);
  EXPECT_THROW(planFromTaskModel(model), srp::core::InvalidInputError);
}
