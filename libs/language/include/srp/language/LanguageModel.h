#pragma once
/// \file LanguageModel.h
/// \brief The trained entity and relation recogniser of the Language Module.
///
/// Entities (Action, Trajector, SpatialIndicator, GoalIndicator, Color) are read
/// by a linear-chain structural SVM over BIO tags (dlib::sequence_labeler, order 1)
/// with lexical, word-shape, context, action-position and WordNet features.
/// Relations (Spatial: Trajector -> SpatialIndicator; Transition: Action ->
/// GoalIndicator) are scored by a linear SVM over candidate pairs (dlib
/// svm_c_linear_trainer, sparse features: distance, direction, entities and
/// words between); each indicator keeps its best head when the score is positive.
///
/// Example:
/// \code
///   auto model = LanguageModel::load(srp::language::defaultModelPath());
///   AnnotatedSentence s = model.annotate({"pick", "the", "red", "block", "on", "the", "table"});
/// \endcode

#include <memory>
#include <string>
#include <vector>

#include "srp/language/TaskPlan.h"

namespace srp::language {

/// Training settings; the defaults are the ones selected on val.json.
struct LanguageTrainingOptions {
  double entityC = 30.0;         ///< structural SVM C of the entity tagger
  double entityEpsilon = 0.01;   ///< its stopping tolerance (risk gap)
  double relationC = 1.0;        ///< linear SVM C of the relation classifier
  int minFeatureCount = 2;       ///< entity features seen fewer times in training are dropped
  int threads = 1;  ///< 1 keeps the loss sums in one order: bit-identical models everywhere
};

class LanguageModel {
 public:
  LanguageModel();
  ~LanguageModel();
  LanguageModel(LanguageModel&&) noexcept;
  LanguageModel& operator=(LanguageModel&&) noexcept;

  /// Trains both parts on SpERT sentences (entities and relations are used).
  /// Deterministic for a given corpus and options. Throws InvalidInputError on
  /// an empty corpus.
  static LanguageModel train(const std::vector<AnnotatedSentence>& corpus,
                             const LanguageTrainingOptions& options = {});

  /// Binary model file (dlib serialisation, format version checked).
  void save(const std::string& path) const;
  /// Throws srp::core::FileError naming the path when missing, corrupt or of an
  /// unknown format version (the fix: retrain with `srp train-language`).
  static LanguageModel load(const std::string& path);

  /// Entities and relations of one tokenised sentence (tokens as written).
  /// `tokens` is copied into the result; an empty input gives an empty result.
  AnnotatedSentence annotate(const std::vector<std::string>& tokens) const;

  /// Lemmas that the training corpus annotated as actions ("pick", "place", ...).
  const std::vector<std::string>& actionLemmas() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// The model shipped in the repo: SRP_DATASETS_DIR/language/model/language_model.dat.
std::string defaultModelPath();

/// Reads a SpERT corpus file (a JSON array of sentences); throws FileError /
/// InvalidInputError naming the file.
std::vector<AnnotatedSentence> readSpertCorpus(const std::string& path);

}  // namespace srp::language
