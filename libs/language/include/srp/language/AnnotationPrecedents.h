#pragma once
/// \file AnnotationPrecedents.h
/// \brief How a reference corpus annotates the same words around a position:
/// the precedents of a prediction error, to tell a model's errors from places
/// where two corpora annotate the same wording differently.
///
/// A position's *context* is its lower-case word with `radius` words on each
/// side (sentence edges are part of it: "<s>", "</s>"); its *label* is the type
/// and length of the entity starting there ("SpatialIndicator:3") or "none".
/// An entity error of a prediction is *against precedent* when the reference
/// corpus has the error's context and its most frequent label there (more than
/// half of the occurrences) is the prediction's label, not the gold one: a
/// model that follows the reference corpus cannot get it right.
///
/// Example (`srp eval-language --data val.json --precedents train.json`):
/// \code
///   const AnnotationPrecedents train(readSpertCorpus("train.json"));
///   const auto check = checkAgainstPrecedents(val, predicted, train, {"SpatialIndicator"});
///   check.againstPrecedent;                  // errors where train annotates as predicted
///   check.ifConsistent.at("SpatialIndicator").f1();  // F1 if val followed train there
/// \endcode

#include <map>
#include <set>
#include <string>
#include <vector>

#include "srp/language/SpertEvaluation.h"
#include "srp/language/TaskPlan.h"

namespace srp::language {

/// Label counts of every context of a reference corpus.
class AnnotationPrecedents {
 public:
  /// Counts the label of every token position of `reference`.
  explicit AnnotationPrecedents(const std::vector<AnnotatedSentence>& reference, int radius = 3);

  /// "Type:length" of the entity of `sentence` starting at `position` (the
  /// first one by type name when several do), "none" when none does.
  static std::string labelAt(const AnnotatedSentence& sentence, int position);

  /// Label counts of the reference corpus in the context of `position` in
  /// `tokens`; empty when the reference never has that context.
  std::map<std::string, int> at(const std::vector<std::string>& tokens, int position) const;

  /// The label with more than half of the counts, "" when none has.
  static std::string majority(const std::map<std::string, int>& counts);

  int radius() const { return radius_; }

 private:
  std::string contextKey(const std::vector<std::string>& lowerTokens, int position) const;
  int radius_;
  std::map<std::string, std::map<std::string, int>> counts_;
};

/// Entity errors of a prediction set against their precedents.
struct PrecedentCheck {
  int errors = 0;            ///< entity errors of the checked types
  int withPrecedent = 0;     ///< of them, whose context the reference corpus has
  int againstPrecedent = 0;  ///< of them, where the reference's majority label is the predicted one
  /// Scores per entity type with the errors against precedent counted right
  /// (the gold entity removed, the predicted one accepted).
  std::map<std::string, TypeScore> ifConsistent;
  std::string report;  ///< one line per error: sentence, words, gold / predicted / reference labels
};

/// Checks every entity error of `predicted` against `gold` whose entity type is
/// in `types` (all when empty) against `precedents`.
PrecedentCheck checkAgainstPrecedents(const std::vector<AnnotatedSentence>& gold,
                                      const std::vector<AnnotatedSentence>& predicted,
                                      const AnnotationPrecedents& precedents, const std::set<std::string>& types = {});

}  // namespace srp::language
