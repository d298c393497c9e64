#pragma once
/// \file InstructionParser.h
/// \brief Instruction text -> TaskPlan: the Language Module's entry point.
///
/// Pipeline: sentence split and tokenisation (offsets kept), entity and relation
/// recognition by the trained LanguageModel, then domain objects, references and
/// steps by PlanBuilder. Example:
/// \code
///   srp::language::InstructionParser parser;  // loads the shipped model once (< 1 s)
///   TaskPlan plan = parser.parse("Pick up the cuboid from the blue box and place it in the gray box.");
///   // plan.steps[0]: cuboid, source [from blue box], target [in gray box]
/// \endcode
/// Unusable text (empty, over kMaxInstructionBytes, no letters, not English, no
/// action, no object) gives a plan with zero steps and a warning saying why; it
/// never throws for text. parse() is const and thread-safe.

#include <memory>
#include <string>
#include <vector>

#include "srp/language/LanguageModel.h"
#include "srp/language/TaskPlan.h"
#include "srp/language/WordNetLexicon.h"

namespace srp::language {

class InstructionParser {
 public:
  /// Longest instruction accepted (one task is a paragraph, not a book).
  static constexpr std::size_t kMaxInstructionBytes = 10000;

  /// Loads the model at `modelPath` (default: the shipped one); throws
  /// srp::core::FileError when it is missing or corrupt.
  explicit InstructionParser(const std::string& modelPath = defaultModelPath());

  /// Parses one instruction. `knownSteps` (optional) is the plan of an earlier
  /// instruction, used to complete "back to" moves.
  TaskPlan parse(const std::string& text, const std::vector<PlanStep>& knownSteps = {}) const;

  const LanguageModel& model() const { return model_; }

 private:
  LanguageModel model_;
  WordNetLexicon lexicon_;
};

}  // namespace srp::language
