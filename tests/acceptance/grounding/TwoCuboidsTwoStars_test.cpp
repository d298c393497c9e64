// Issue 19 acceptance, grounding half: the instructions written for the scene with
// two cuboids and two stars of different colours (tests/acceptance/data/
// two_cuboids_two_stars.json) go through the real parser (the bundled language
// model) and planFromLanguage; each moved part's noun phrase must ground to the
// expected instance, and the refused ones must fail naming the candidates.
#include <gtest/gtest.h>

#include <set>

#include "srp/core/Json.h"
#include "srp/execution/CellDescription.h"
#include "srp/execution/PlanConversion.h"
#include "srp/execution/SceneGrounder.h"
#include "srp/language/InstructionParser.h"

using namespace srp;

namespace {

const std::string kData = std::string(SRP_SOURCE_DIR) + "/tests/acceptance/data/two_cuboids_two_stars.json";

struct Setup {
  nlohmann::json data = core::readJsonFile(kData);
  execution::CellDescription cell =
      execution::CellDescription::loadScene(std::string(SRP_SOURCE_DIR) + "/" + data.at("scene").get<std::string>());
  language::InstructionParser parser;
};

Setup& setup() {
  static Setup s;
  return s;
}

}  // namespace

TEST(TwoCuboidsTwoStars, TenInstructionsGroundTheMovedPartToTheExpectedInstance) {
  auto& s = setup();
  const auto& instructions = s.data.at("instructions");
  ASSERT_EQ(instructions.size(), 10u);
  const execution::SceneGrounder grounder(s.cell);
  std::set<std::string> rules;
  for (const auto& item : instructions) {
    const std::string text = item.at("text");
    const language::TaskPlan parsed = s.parser.parse(text);
    const execution::ExecutionPlan plan = execution::planFromLanguage(parsed);
    ASSERT_EQ(plan.steps.size(), 1u) << text << "\n" << language::describe(parsed);
    const auto& step = plan.steps[0];
    try {
      const auto& part = grounder.ground(step.object, step.source, execution::CellObjectKind::Part);
      EXPECT_EQ(part.name, item.at("object").get<std::string>()) << text << "\n" << language::describe(parsed);
    } catch (const execution::GroundingError& e) {
      ADD_FAILURE() << text << ": " << e.what() << "\n" << language::describe(parsed);
    }
    rules.insert(item.at("grounding").get<std::string>());
  }
  // Every kind of grounding the issue names is exercised.
  for (const char* rule : {"colour", "ordinal", "superlative", "landmark relation"}) EXPECT_TRUE(rules.count(rule)) << rule;
}

TEST(TwoCuboidsTwoStars, AmbiguousOrImpossiblePhrasesAreRefusedNamingTheCandidates) {
  auto& s = setup();
  for (const auto& item : s.data.at("refused")) {
    const std::string text = item.at("text");
    const execution::ExecutionPlan plan = execution::planFromLanguage(s.parser.parse(text));
    ASSERT_EQ(plan.steps.size(), 1u) << text;
    const std::vector<std::string> problems = execution::groundingProblems(plan, s.cell);
    ASSERT_EQ(problems.size(), 1u) << text;
    for (const auto& word : item.at("message")) {
      EXPECT_NE(problems[0].find(word.get<std::string>()), std::string::npos)
          << text << ": '" << word.get<std::string>() << "' not in: " << problems[0];
    }
  }
}
