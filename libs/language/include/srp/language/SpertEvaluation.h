#pragma once
/// \file SpertEvaluation.h
/// \brief SpERT-style scoring of predicted entities and relations against a gold corpus.
///
/// An entity is correct when its type and token span [start, end) match a gold
/// entity exactly; a relation when its type and both its entities (type + span)
/// match a gold relation. Scores are micro-averaged per type over the corpus.

#include <map>
#include <string>
#include <vector>

#include "srp/language/LanguageModel.h"
#include "srp/language/TaskPlan.h"

namespace srp::language {

/// Counts and scores of one entity or relation type; fractions in [0, 1].
struct TypeScore {
  int truePositives = 0, falsePositives = 0, falseNegatives = 0;
  double precision() const;
  double recall() const;
  double f1() const;
  int support() const { return truePositives + falseNegatives; }  ///< gold count
};

/// Per-type scores (entity types and relation types share one map: names differ)
/// and the mean annotation time.
struct SpertScores {
  std::map<std::string, TypeScore> types;
  double msPerSentence = 0.0;  ///< mean wall time of LanguageModel::annotate, milliseconds
};

/// Scores `predicted` against `gold` (same length, same tokens); throws
/// InvalidInputError when the two corpora do not line up.
SpertScores scoreSpert(const std::vector<AnnotatedSentence>& gold, const std::vector<AnnotatedSentence>& predicted);

/// Annotates every gold sentence's tokens with `model`, times it and scores it.
SpertScores evaluateModel(const LanguageModel& model, const std::vector<AnnotatedSentence>& gold);

/// The `srp eval-language --json` form: {"types": {"Action": {"precision", "recall",
/// "f1", "support"}, ...}, "ms_per_sentence": x}.
nlohmann::json toJson(const SpertScores& scores);

/// A fixed-width table: type, precision, recall, F1 (percent), support.
std::string formatScoreTable(const SpertScores& scores);

}  // namespace srp::language
