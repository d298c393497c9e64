#pragma once
/// \file CapabilitySuites.h
/// \brief Behavioural tests of the language model (CheckList style, Ribeiro et
/// al. 2020): one SpERT file per linguistic capability, scored on its own.
///
/// A suite is a file `<folder>/<name>.json` in the corpus schema (readSpertCorpus),
/// written for one capability ("source_goal": "place X from Y on Z";
/// "no_landmark": "place it directly below"; datasets/language/capabilities/README.md).
/// Suites are never trained on. Each is scored by SpERT scoring; its summary is
/// the entity F1 pooled over the five entity types and the relation F1 pooled
/// over the two relation types (micro averages: every entity / relation counts once).
///
/// Example:
/// \code
///   const auto suites = CapabilitySuites::load(CapabilitySuites::defaultFolder());
///   const auto results = suites.score(LanguageModel::load(defaultModelPath()));
///   std::cout << CapabilitySuites::formatTable(results);
///   // suite               sentences  entity P    R     F1  relation P    R     F1
///   // direction_phrases          42     ...
/// \endcode

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "srp/language/LanguageModel.h"
#include "srp/language/SpertEvaluation.h"

namespace srp::language {

class CapabilitySuites {
 public:
  struct Suite {
    std::string name;  ///< file name without ".json"
    std::vector<AnnotatedSentence> sentences;
  };
  /// One suite's scores: per type, and pooled over the entity / relation types.
  struct Result {
    std::string name;
    int sentences = 0;
    SpertScores scores;
    TypeScore entities;   ///< counts summed over Action, Trajector, SpatialIndicator, GoalIndicator, Color
    TypeScore relations;  ///< counts summed over Spatial, Transition
  };

  /// The shipped suites, `datasets/language/capabilities` of srp's data folder
  /// (core::DataPaths). Throws FileError when it is not there.
  static std::string defaultFolder();
  /// Every `*.json` of `folder`, in name order. Throws FileError naming the
  /// folder when it is missing or holds no suite, or naming a malformed file.
  static CapabilitySuites load(const std::string& folder);

  const std::vector<Suite>& suites() const { return suites_; }
  /// Annotates every sentence of every suite with `model` and scores it.
  std::vector<Result> score(const LanguageModel& model) const;

  /// Sums the scores' counts over entity and relation types (Result::entities / relations).
  static Result summarise(const std::string& name, int sentences, const SpertScores& scores);
  /// One line per suite: sentences, entity P/R/F1, relation P/R/F1 (percent); with
  /// `before` (same suites, same order) also the F1 before and the difference.
  static std::string formatTable(const std::vector<Result>& results, const std::vector<Result>& before = {});
  /// {"<suite>": {"sentences", "entity_f1", "relation_f1", "types": {...}}}.
  static nlohmann::json toJson(const std::vector<Result>& results);

 private:
  std::vector<Suite> suites_;
};

}  // namespace srp::language
