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
  EXPECT_EQ(plan.steps[0].source[0].landmark.colour.value_or(""), "blue");
  ASSERT_EQ(plan.steps[0].target.size(), 1u);
  EXPECT_EQ(plan.steps[0].target[0].relation, "in");
  EXPECT_EQ(plan.steps[0].target[0].landmark.colour.value_or(""), "gray");
  // star: next to the cuboid (stored as a source location) and, via its sentence, in the gray box.
  bool nextToCuboid = false, inGray = false;
  for (const auto& r : plan.steps[1].target) {
    nextToCuboid |= r.relation == "next to" && r.landmark.name == "cuboid";
    inGray |= r.relation == "in" && r.landmark.colour.value_or("") == "gray";
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

#include "srp/language/InstructionParser.h"

namespace {
std::string show(const ExecutionPlan& p) {
  std::string s;
  for (const auto& st : p.steps) {
    s += st.object.describe() + " ->";
    for (const auto& r : st.target)
      s += " [" + r.relation + (r.corner.empty() ? "" : " " + r.corner) + " " + r.landmark.describe() +
           (r.secondLandmark ? " & " + r.secondLandmark->describe() : "") + "]";
    s += "; ";
  }
  return s;
}
}  // namespace

// The language model reads these spatial phrases only in part; planFromLanguage re-reads
// the relation from the sentence's tokens (the object phrases are left as parsed).
TEST(PlanConversion, PlacementRelationsOfNewInstructions) {
  const srp::language::InstructionParser parser;
  const std::pair<const char*, const char*> cases[] = {
      {"Put the star to the left of the cuboid.", "star -> [left of cuboid]; "},
      {"Place the star to the right of the octagon.", "star -> [right of octagon]; "},
      {"Stack the cuboid on the octagon.", "cuboid -> [on octagon]; "},
      {"Put the star on top of the cuboid.", "star -> [on top of cuboid]; "},
      {"Place the star between the cuboid and the octagon.", "star -> [between cuboid & octagon]; "},
      {"Put the star in front of the octagon.", "star -> [in front of octagon]; "},
      {"Put the star behind the octagon.", "star -> [behind octagon]; "},
      {"Put the star right of the cuboid.", "star -> [right of cuboid]; "},
      {"Put the cuboid in the front left corner of the gray box.", "cuboid -> [corner front left gray box]; "},
  };
  for (const auto& [text, expected] : cases) {
    const ExecutionPlan plan = planFromLanguage(parser.parse(text));
    EXPECT_EQ(show(plan), expected) << text;
  }
}
