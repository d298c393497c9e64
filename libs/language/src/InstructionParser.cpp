#include "srp/language/InstructionParser.h"

#include <cctype>
#include <set>

#include "srp/language/PlanBuilder.h"
#include "srp/language/Tokenizer.h"

namespace srp::language {

namespace {
// Frequent English function words that WordNet does not list.
const std::set<std::string> kFunctionWords{
    "the", "a", "an", "and", "or", "it", "them", "they", "to", "of", "from", "on", "onto", "into", "with", "by",
    "this", "that", "these", "those", "then", "next", "is", "are", "be", "its", "your", "my", "me", "you", "i",
    "please", "up", "please", "which", "who", "at", "for", "after", "before", "finally", "first", "same", "both"};
}  // namespace

InstructionParser::InstructionParser(const std::string& modelPath) : model_(LanguageModel::load(modelPath)) {}

TaskPlan InstructionParser::parse(const std::string& text, const std::vector<PlanStep>& knownSteps) const {
  TaskPlan plan;
  if (text.size() > kMaxInstructionBytes) {
    plan.warnings.push_back("the instruction is " + std::to_string(text.size()) + " bytes; at most " +
                            std::to_string(kMaxInstructionBytes) + " are accepted (give one task per instruction)");
    return plan;
  }
  const auto sentences = tokenizeSentences(text);
  if (sentences.empty()) {
    plan.warnings.push_back("the instruction is empty: say what to move where, e.g. \"pick up the cuboid and place it in the gray box\"");
    return plan;
  }
  int words = 0, knownWords = 0;
  for (const auto& s : sentences)
    for (const auto& t : s) {
      if (!std::isalpha(static_cast<unsigned char>(t.text[0])) && static_cast<unsigned char>(t.text[0]) < 0x80) continue;
      ++words;
      const std::string w = toLowerAscii(t.text);
      const WordInfo info = lexicon_.lookup(w);
      knownWords += (kFunctionWords.count(w) || info.noun || info.verb || info.adjective || info.adverb) ? 1 : 0;
    }
  if (words == 0) {
    plan.warnings.push_back("the instruction has no words (only numbers or symbols): nothing to do");
    return plan;
  }
  constexpr double kMinEnglishFraction = 0.6;  // instructions in the corpus: > 0.9 of words known
  if (knownWords < kMinEnglishFraction * words) {
    plan.warnings.push_back("the instruction does not look like English (" + std::to_string(knownWords) + " of " +
                            std::to_string(words) + " words known); please give it in English");
    return plan;
  }
  for (const auto& s : sentences) {
    std::vector<std::string> tokens;
    for (const auto& t : s) tokens.push_back(t.text);
    AnnotatedSentence a = model_.annotate(tokens);
    for (const auto& t : s) {
      a.charBegin.push_back(t.charBegin);
      a.charEnd.push_back(t.charEnd);
    }
    plan.sentences.push_back(std::move(a));
  }
  plan.steps = buildPlanSteps(plan.sentences, lexicon_, knownSteps, plan.warnings);
  if (plan.steps.empty())
    plan.warnings.push_back("no action on an object found (e.g. \"pick up the cuboid\", \"place the star in the box\"): "
                            "the plan is empty");
  return plan;
}

}  // namespace srp::language
