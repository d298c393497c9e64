#pragma once
/// \file SpertEvaluation.h
/// \brief SpERT-style scoring of predicted entities and relations against a gold corpus.
///
/// An entity is correct when its type and token span [start, end) match a gold
/// entity exactly; a relation when its type and both its entities (type + span)
/// match a gold relation. Scores are micro-averaged per type over the corpus.

#include <map>
#include <set>
#include <string>
#include <utility>
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

/// Out-of-fold predictions of k-fold cross-validation and their pooled scores.
struct CrossValidationResult {
  SpertScores scores;                         ///< TP/FP/FN summed over the folds
  std::vector<AnnotatedSentence> predictions; ///< one per corpus sentence, same order
};

/// k-fold cross-validation: sentence i is in fold i % folds; each fold is
/// annotated by a model trained on the other folds with `options`. Folds run
/// on `threads` threads (each training single-threaded), so the result is
/// deterministic. Throws InvalidInputError when folds < 2 or > corpus size.
CrossValidationResult crossValidate(const std::vector<AnnotatedSentence>& corpus, const LanguageModel::Options& options,
                                    int folds, int threads = 1);

/// The pooled protocol (README "Protocol"): repeated k-fold cross-validation.
/// For each seed the corpus is shuffled (Fisher-Yates on std::mt19937_64(seed),
/// the same on every platform) and cut into `folds` folds; each fold is
/// annotated by a model trained on the others. One trained model per (seed,
/// fold) scores every decoding-rule variant, so rule ablations cost no retraining.
struct RepeatedCrossValidation {
  std::vector<std::string> variantNames;        ///< variants[0] is the baseline
  std::vector<std::vector<SpertScores>> folds;  ///< [variant][seed * folds + fold]
  /// Out-of-fold predictions of the baseline for the first seed, corpus order.
  std::vector<AnnotatedSentence> firstSeedPredictions;
  int numFolds = 0, numSeeds = 0;
  double trainSecondsPerFold = 0.0;  ///< mean wall time of one training
};

/// Runs the protocol with `options` (its rules are the baseline) and, on the
/// same trained models, each extra (name, rules) variant. Seeds are 1..seeds.
/// Throws InvalidInputError when folds < 2, seeds < 1 or folds > corpus size.
RepeatedCrossValidation repeatedCrossValidate(const std::vector<AnnotatedSentence>& corpus,
                                              const LanguageModel::Options& options, int folds, int seeds,
                                              int threads = 1,
                                              const std::vector<std::pair<std::string, DecodingRules>>& variants = {});

/// Mean and standard deviation (n - 1) of a type's F1 over a variant's folds,
/// fractions; and the same of the per-fold difference to the baseline (paired:
/// both are scored on the same folds by the same trained model or split).
struct CvSummary {
  double mean = 0.0, std = 0.0;
};
CvSummary cvF1(const std::vector<SpertScores>& folds, const std::string& type);
/// `type` "macro" is the mean F1 of the seven types per fold.
CvSummary cvF1Difference(const std::vector<SpertScores>& folds, const std::vector<SpertScores>& baseline,
                         const std::string& type);

/// The protocol's table: per type mean ± std F1 (percent) of each variant, and
/// for every variant after the first its paired difference to the first with
/// the verdict of the rule (kept when the macro mean difference exceeds its
/// standard deviation, i.e. the fold std of the difference corrected for the
/// overlapping training sets (Nadeau & Bengio 2003), and no type's mean falls).
std::string formatCrossValidation(const RepeatedCrossValidation& cv);
nlohmann::json toJson(const RepeatedCrossValidation& cv);

/// One entity that a prediction got wrong, on the gold side (a gold entity not
/// predicted) or the predicted side (a prediction not in gold).
struct EntityError {
  /// "missed" / "spurious": nothing of the same type overlaps it on the other side;
  /// "boundary": an entity of the same type overlaps it with another span;
  /// "type": the other side has the same span with another type (listed once, gold side);
  /// "overlap": only entities of other types overlap it.
  std::string kind;
  int sentence = 0;  ///< index in the corpus
  bool goldSide = true;
  EntitySpan entity;      ///< the gold entity (goldSide) or the predicted one
  std::string otherType;  ///< for "type": the predicted type
};

/// Every entity error of `predicted` against `gold` (same length, same tokens),
/// in sentence order; throws InvalidInputError when the corpora do not line up.
std::vector<EntityError> entityErrors(const std::vector<AnnotatedSentence>& gold,
                                      const std::vector<AnnotatedSentence>& predicted);

/// A readable error dump for the entity types `types` (all when empty): counts
/// per type and kind, then each sentence with an error, gold and predicted
/// spans bracketed ("[on top of]SpatialIndicator"), and its errors.
std::string formatEntityErrors(const std::vector<AnnotatedSentence>& gold,
                               const std::vector<AnnotatedSentence>& predicted,
                               const std::set<std::string>& types = {});

/// The `srp eval-language --json` form: {"types": {"Action": {"precision", "recall",
/// "f1", "support"}, ...}, "ms_per_sentence": x}.
nlohmann::json toJson(const SpertScores& scores);

/// A fixed-width table: type, precision, recall, F1 (percent), support; then the
/// time per sentence when the scores were timed (msPerSentence > 0).
std::string formatScoreTable(const SpertScores& scores);

}  // namespace srp::language
