#include "srp/language/InstructionParser.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

using namespace srp::language;

namespace {

const InstructionParser& parser() {
  static const InstructionParser p;  // the shipped model, loaded once for the suite
  return p;
}

ObjectRef obj(const std::string& name, std::optional<std::string> colour = std::nullopt) { return {name, colour}; }
LocationRef at(const std::string& relation, const ObjectRef& landmark) { return {relation, landmark}; }

std::string show(const TaskPlan& plan) { return describe(plan); }

// The five test instructions of the thesis, Appendix A (copied verbatim).
const std::vector<std::string> kAppendixA{
    "Begin by picking up the cuboid from the blue box and placing it in the gray box. Next, carefully lift the star and position it next to the cuboid in the gray box. Then, move the parallelogram, placing it beside the star in the gray box. Finally, pick up the octagon and place it adjacent to the parallelogram in the gray box.",
    "Start by gently lifting the cuboid from the blue box and placing it precisely in the gray box. Then, grasp the star and carefully set it near the cuboid in the gray box. Afterwards, pick up the parallelogram and position it beside the star in the gray box. Conclude by placing the octagon next to the parallelogram in the gray box.",
    "First, remove the cuboid from the blue box and place it in the gray box with precision. Following that, take the star and gently place it alongside the cuboid in the gray box. Continue by moving the parallelogram, placing it next to the star in the gray box. Finish by setting the octagon beside the parallelogram in the gray box.",
    "Initially, pick up the cuboid from the blue box and carefully place it in the gray box. Next, take the star and delicately place it next to the cuboid in the gray box. Then, transfer the parallelogram, positioning it beside the star in the gray box. Finally, place the octagon adjacent to the parallelogram in the gray box.",
    "Begin by lifting the cuboid from the blue box and placing it neatly in the gray box. Then, pick up the star and position it carefully next to the cuboid in the gray box. Next, move the parallelogram and place it beside the star in the gray box. Lastly, place the octagon next to the parallelogram, completing the sequence in the gray box.",
};

}  // namespace

// SPEC.md section 4: cuboid (from blue box, into gray box), star (next to cuboid, in gray
// box), parallelogram (beside star, in gray box), octagon (adjacent to parallelogram, in gray box).
TEST(InstructionParser, AppendixAInstructionsGiveTheExpectedFourStepPlan) {
  const ObjectRef grayBox = obj("box", "gray");
  for (size_t i = 0; i < kAppendixA.size(); ++i) {
    SCOPED_TRACE("Appendix A instruction " + std::to_string(i + 1));
    const TaskPlan plan = parser().parse(kAppendixA[i]);
    ASSERT_EQ(plan.steps.size(), 4u) << show(plan);
    const std::vector<std::string> order{"cuboid", "star", "parallelogram", "octagon"};
    for (size_t s = 0; s < 4; ++s) {
      EXPECT_EQ(plan.steps[s].object, obj(order[s])) << show(plan);
      ASSERT_FALSE(plan.steps[s].target.empty()) << show(plan);
      EXPECT_EQ(plan.steps[s].target.back(), at("in", grayBox)) << show(plan);
    }
    ASSERT_EQ(plan.steps[0].source.size(), 1u) << show(plan);
    EXPECT_EQ(plan.steps[0].source[0], at("from", obj("box", "blue")));
    EXPECT_EQ(plan.steps[0].target.size(), 1u) << show(plan);
    // Steps 2-4: placed relative to the previous object, then inside the gray box.
    for (size_t s = 1; s < 4; ++s) {
      ASSERT_EQ(plan.steps[s].target.size(), 2u) << show(plan);
      EXPECT_EQ(plan.steps[s].target[0].landmark, obj(order[s - 1])) << show(plan);
      EXPECT_TRUE(plan.steps[s].source.empty()) << show(plan);
    }
    EXPECT_TRUE(plan.warnings.empty()) << show(plan);
  }
  const TaskPlan first = parser().parse(kAppendixA[0]);
  EXPECT_EQ(first.steps[1].target[0].relation, "next to");
  EXPECT_EQ(first.steps[2].target[0].relation, "beside");
  EXPECT_EQ(first.steps[3].target[0].relation, "adjacent to");
}

TEST(InstructionParser, SubsetInstruction) {
  const TaskPlan plan = parser().parse("Pick up the cuboid from the blue box and place it in the gray box");
  ASSERT_EQ(plan.steps.size(), 1u) << show(plan);
  EXPECT_EQ(plan.steps[0].object, obj("cuboid"));
  EXPECT_EQ(plan.steps[0].source, (std::vector<LocationRef>{at("from", obj("box", "blue"))}));
  EXPECT_EQ(plan.steps[0].target, (std::vector<LocationRef>{at("in", obj("box", "gray"))}));
}

TEST(InstructionParser, ReversalNamesBothBoxesAndIsMarkedAsReturn) {
  const TaskPlan plan = parser().parse("Move the cuboid from the gray box back to the blue box");
  ASSERT_EQ(plan.steps.size(), 1u) << show(plan);
  EXPECT_EQ(plan.steps[0].object, obj("cuboid"));
  EXPECT_EQ(plan.steps[0].source, (std::vector<LocationRef>{at("from", obj("box", "gray"))}));
  EXPECT_EQ(plan.steps[0].target, (std::vector<LocationRef>{at("to", obj("box", "blue"))}));
  EXPECT_TRUE(plan.steps[0].isReturn);
}

TEST(InstructionParser, BackToWithoutSourceReversesTheKnownMove) {
  const TaskPlan demo = parser().parse("Pick up the cuboid from the blue box and place it in the gray box");
  const TaskPlan plan = parser().parse("Move the cuboid back to the blue box", demo.steps);
  ASSERT_EQ(plan.steps.size(), 1u) << show(plan);
  EXPECT_EQ(plan.steps[0].source, (std::vector<LocationRef>{at("in", obj("box", "gray"))})) << show(plan);
  EXPECT_EQ(plan.steps[0].target, (std::vector<LocationRef>{at("to", obj("box", "blue"))})) << show(plan);
}

TEST(InstructionParser, GroupingGivesOneStepPerObjectWithNamedLocations) {
  const TaskPlan plan = parser().parse("Pick item A and item B from the conveyor belt, place them at Location 2");
  ASSERT_EQ(plan.steps.size(), 2u) << show(plan);
  EXPECT_EQ(plan.steps[0].object, obj("item A"));
  EXPECT_EQ(plan.steps[1].object, obj("item B"));
  for (const auto& step : plan.steps) {
    EXPECT_EQ(step.source, (std::vector<LocationRef>{at("from", obj("conveyor belt"))})) << show(plan);
    EXPECT_EQ(step.target, (std::vector<LocationRef>{at("at", obj("Location 2"))})) << show(plan);
  }
}

TEST(InstructionParser, ConjunctionAndPluralPronoun) {
  const TaskPlan plan = parser().parse("Pick the cuboid and the cylinder and place them in the gray box.");
  ASSERT_EQ(plan.steps.size(), 2u) << show(plan);
  EXPECT_EQ(plan.steps[0].object, obj("cuboid"));
  EXPECT_EQ(plan.steps[1].object, obj("cylinder"));
  for (const auto& step : plan.steps)
    EXPECT_EQ(step.target, (std::vector<LocationRef>{at("in", obj("box", "gray"))})) << show(plan);
}

TEST(InstructionParser, ImplicitPickMultiWordNamesAndTheSame) {
  const TaskPlan plan = parser().parse(
      "Place the octagon next to the parallelogram. Pick up the aluminum workpiece and put it on the conveyor belt. "
      "Then take the red block and place the same on the tray.");
  ASSERT_EQ(plan.steps.size(), 3u) << show(plan);
  EXPECT_EQ(plan.steps[0].object, obj("octagon"));
  EXPECT_EQ(plan.steps[0].target, (std::vector<LocationRef>{at("next to", obj("parallelogram"))}));
  EXPECT_EQ(plan.steps[1].object, obj("aluminum workpiece"));
  EXPECT_EQ(plan.steps[1].target, (std::vector<LocationRef>{at("on", obj("conveyor belt"))}));
  EXPECT_EQ(plan.steps[2].object, obj("block", "red"));
  EXPECT_EQ(plan.steps[2].target, (std::vector<LocationRef>{at("on", obj("tray"))}));
}

TEST(InstructionParser, PronounInTheNextSentenceRefersToThePreviousObject) {
  const TaskPlan plan = parser().parse("Grab the green cube. Put it on top of the yellow block.");
  ASSERT_EQ(plan.steps.size(), 1u) << show(plan);
  EXPECT_EQ(plan.steps[0].object, obj("cube", "green"));
  EXPECT_EQ(plan.steps[0].target, (std::vector<LocationRef>{at("on top of", obj("block", "yellow"))}));
}

TEST(InstructionParser, SentencesKeepTokensAndCharacterOffsets) {
  const std::string text = "Pick up the cuboid. Place it in the gray box.";
  const TaskPlan plan = parser().parse(text);
  ASSERT_EQ(plan.sentences.size(), 2u);
  for (const auto& s : plan.sentences) {
    ASSERT_EQ(s.charBegin.size(), s.tokens.size());
    for (size_t k = 0; k < s.tokens.size(); ++k)
      EXPECT_EQ(text.substr(s.charBegin[k], s.charEnd[k] - s.charBegin[k]), s.tokens[k]);
  }
  EXPECT_EQ(plan.steps.at(0).objectAnchor.sentenceId, 0);
  EXPECT_EQ(plan.steps.at(0).objectAnchor.tokenId, 3);
}

TEST(InstructionParser, BadInputGivesNoStepsAndSaysWhy) {
  const std::vector<std::pair<std::string, std::string>> cases{
      {"", "empty"},
      {"   \n\t ", "empty"},
      {std::string(100 * 1024, 'a'), "bytes"},
      {"Nimm den Würfel aus der blauen Kiste und lege ihn in die graue Kiste.", "English"},
      {"12 34 5.6 -7", "no words"},
      {"The cuboid is in the blue box.", "no action"},
  };
  for (const auto& [text, reason] : cases) {
    SCOPED_TRACE(text.substr(0, 60));
    const TaskPlan plan = parser().parse(text);
    EXPECT_TRUE(plan.steps.empty()) << show(plan);
    ASSERT_FALSE(plan.warnings.empty());
    EXPECT_NE(plan.warnings.back().find(reason), std::string::npos) << plan.warnings.back();
  }
}

TEST(InstructionParser, JsonRoundTripKeepsTheSteps) {
  const TaskPlan plan = parser().parse(kAppendixA[0]);
  const auto j = toJson(plan);
  EXPECT_TRUE(j.at("steps")[0].at("object").at("color").is_null());
  EXPECT_EQ(j.at("steps")[0].at("source")[0].at("landmark").at("color"), "blue");
  const TaskPlan back = taskPlanFromJson(j);
  ASSERT_EQ(back.steps.size(), plan.steps.size());
  for (size_t s = 0; s < plan.steps.size(); ++s) {
    EXPECT_EQ(back.steps[s].object, plan.steps[s].object);
    EXPECT_EQ(back.steps[s].source, plan.steps[s].source);
    EXPECT_EQ(back.steps[s].target, plan.steps[s].target);
  }
  EXPECT_EQ(back.sentences.size(), plan.sentences.size());
}

TEST(InstructionParser, PronounLandmarkAndGappedSecondObject) {
  const TaskPlan a = parser().parse("Move the cuboid to the gray box. Then move the star next to it.");
  ASSERT_EQ(a.steps.size(), 2u) << show(a);
  EXPECT_EQ(a.steps[1].target, (std::vector<LocationRef>{at("next to", obj("cuboid"))})) << show(a);

  const TaskPlan b = parser().parse(
      "Pick up the cuboid and the star from the blue box, place the cuboid in the gray box and the star next to the cuboid");
  ASSERT_EQ(b.steps.size(), 2u) << show(b);
  EXPECT_EQ(b.steps[0].target, (std::vector<LocationRef>{at("in", obj("box", "gray"))})) << show(b);
  EXPECT_EQ(b.steps[1].object, obj("star"));
  EXPECT_EQ(b.steps[1].source, (std::vector<LocationRef>{at("from", obj("box", "blue"))})) << show(b);
  EXPECT_EQ(b.steps[1].target, (std::vector<LocationRef>{at("next to", obj("cuboid"))})) << show(b);
}

TEST(InstructionParser, ObjectsOnlyTextSelectsKnownSteps) {
  const TaskPlan demo = parser().parse(
      "Pick up the cuboid from the blue box and place it in the gray box. Then place the star next to the cuboid.");
  ASSERT_EQ(demo.steps.size(), 2u) << show(demo);
  const TaskPlan subset = parser().parse("Only the star this time.", demo.steps);
  ASSERT_EQ(subset.steps.size(), 1u) << show(subset);
  EXPECT_EQ(subset.steps[0].object, obj("star"));
  EXPECT_EQ(subset.steps[0].target, demo.steps[1].target);
  // Without a known plan the same text has no action: zero steps and a reason.
  const TaskPlan alone = parser().parse("Only the star this time.");
  EXPECT_TRUE(alone.steps.empty());
  ASSERT_FALSE(alone.warnings.empty());
}
