#include "srp/language/PlanTables.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>

#include "srp/core/Error.h"
#include "srp/language/InstructionParser.h"
#include "srp/taskdb/TaskDatabase.h"
#include "srp/taskdb/TaskModelStore.h"

using namespace srp::language;

namespace {
const std::string kInstruction1 =
    "Begin by picking up the cuboid from the blue box and placing it in the gray box. Next, carefully lift the star "
    "and position it next to the cuboid in the gray box. Then, move the parallelogram, placing it beside the star in "
    "the gray box. Finally, pick up the octagon and place it adjacent to the parallelogram in the gray box.";

const InstructionParser& parser() {
  static const InstructionParser p;
  return p;
}

std::string tempDbPath(const std::string& tag) {
  const auto path = std::filesystem::temp_directory_path() /
                    ("srp_language_" + tag + "_" + std::to_string(::getpid()) + ".db");
  std::filesystem::remove(path);
  return path.string();
}
}  // namespace

TEST(PlanTables, AppendixAInstructionGivesLinkedRows) {
  const TaskPlan plan = parser().parse(kInstruction1);
  ASSERT_EQ(plan.steps.size(), 4u) << describe(plan);
  const auto m = planToTaskModel(plan, "thesis-1", kInstruction1);
  ASSERT_EQ(m.targetObjectIds.size(), 4u);
  const std::vector<std::string> order{"cuboid", "star", "parallelogram", "octagon"};
  for (size_t i = 0; i < 4; ++i) EXPECT_EQ(m.findProduct(m.targetObjectIds[i])->objectName, order[i]);
  // cuboid: from the blue box (SourceLocation), in the gray box (TargetLocation), as Appendix C.
  const auto* cuboid = m.findProduct(m.targetObjectIds[0]);
  ASSERT_TRUE(cuboid->sourceLocationId && cuboid->targetLocationId);
  const auto& from = m.sourceLocations.at(*cuboid->sourceLocationId);
  EXPECT_EQ(from.description, "from");
  EXPECT_EQ(m.findProduct(from.trajectorObjectId)->objectName, "box");
  EXPECT_EQ(m.findProduct(from.trajectorObjectId)->colour, std::optional<std::string>("blue"));
  const auto& into = m.targetLocations.at(*cuboid->targetLocationId);
  EXPECT_EQ(into.description, "in");
  EXPECT_EQ(m.findProduct(into.indicatorObjectId)->colour, std::optional<std::string>("gray"));
  EXPECT_EQ(cuboid->sentenceId, std::optional<int>(0));
  EXPECT_EQ(cuboid->tokenId, std::optional<int>(5));  // "Begin by picking up the cuboid": token 5
  // star: next to the cuboid, which is in the gray box.
  const auto* star = m.findProduct(m.targetObjectIds[1]);
  ASSERT_TRUE(star->targetLocationId);
  EXPECT_FALSE(star->sourceLocationId);
  const auto& nextTo = m.targetLocations.at(*star->targetLocationId);
  EXPECT_EQ(nextTo.description, "next to");
  const auto* cuboidLandmark = m.findProduct(nextTo.indicatorObjectId);
  EXPECT_EQ(cuboidLandmark->objectName, "cuboid");
  ASSERT_TRUE(cuboidLandmark->sourceLocationId);
  EXPECT_EQ(m.sourceLocations.at(*cuboidLandmark->sourceLocationId).description, "in");
}

TEST(PlanTables, StoreAndReadBackGivesTheSameSteps) {
  const std::string dbPath = tempDbPath("roundtrip");
  for (const std::string text : {kInstruction1, std::string("Pick item A and item B from the conveyor belt, place them at Location 2")}) {
    const TaskPlan plan = parser().parse(text);
    const int id = storePlan(plan, dbPath, "demo", text);
    auto db = srp::taskdb::TaskDatabase::open(dbPath);
    const auto model = srp::taskdb::TaskModelStore(db).read(id);
    EXPECT_EQ(model.info.instruction, text);
    const auto steps = planStepsFromTaskModel(model);
    ASSERT_EQ(steps.size(), plan.steps.size());
    for (size_t s = 0; s < steps.size(); ++s) {
      EXPECT_EQ(steps[s].object, plan.steps[s].object);
      EXPECT_EQ(steps[s].source, plan.steps[s].source);
      EXPECT_EQ(steps[s].target, plan.steps[s].target);
    }
  }
  std::filesystem::remove(dbPath);
}

TEST(PlanTables, EmptyPlanWritesNothing) {
  const std::string dbPath = tempDbPath("empty");
  {
    auto db = srp::taskdb::TaskDatabase::open(dbPath);  // an existing, empty database
  }
  for (const std::string text : {"", "The cuboid is in the blue box.", "12 34"}) {
    const TaskPlan plan = parser().parse(text);
    ASSERT_TRUE(plan.steps.empty());
    EXPECT_THROW(storePlan(plan, dbPath, "bad", text), srp::core::InvalidInputError);
  }
  auto db = srp::taskdb::TaskDatabase::open(dbPath);
  EXPECT_TRUE(srp::taskdb::TaskModelStore(db).list().empty());
  std::filesystem::remove(dbPath);
}
