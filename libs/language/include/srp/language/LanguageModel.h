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
#include <utility>
#include <vector>

#include "srp/language/TaskPlan.h"

namespace srp::language {

/// Switches of the decoding rules applied after the tagger (each one counted on
/// the training corpus, written from its annotation conventions or from English
/// phrase structure, PhraseRules.h; README "Decoding rules"). Every rule is kept
/// or dropped by the protocol (`srp train-language --cv 5 --cv-seeds 3 --ablate`:
/// pooled cross-validation and the capability suites, ProtocolComparison.h): the
/// defaults are what it kept; the others stay available for ablations.
struct DecodingRules {
  bool spanLengths = false;            ///< indicator span reaches as the corpus' spans from that word
  bool ordersOnly = false;             ///< no indicator before a sentence's first action
  bool rareStartWords = true;          ///< no indicator starting at a word almost never annotated ("of")
  bool rareStartPairs = false;         ///< no spatial indicator at a (previous, word) pair almost never annotated
  bool actionAfterIsSpatial = true;    ///< an indicator with another action after it is spatial
  bool relativeClauseIsSpatial = true; ///< "the cube placed on" / "that is on": spatial
  bool conventionTypes = true;         ///< learned indicator type per (action, direction, first)
  bool oneGoalPerClause = false;       ///< of two goals in a clause, "to/onto/into" or the first stays
  bool addTrajectors = true;           ///< a spatial indicator after a verb gets the head noun as trajector
  bool dropUnlocatedTrajectors = true; ///< a trajector with no spatial indicator after it is dropped
  bool sourceIsSpatial = true;         ///< "from / off / out of / away from" phrases are spatial, not the clause's
                                       ///< goal, and locate the moved object even after the goal
  bool placingFirstIsGoal = false;     ///< a placing verb's first phrase is its goal unless a "to / into" goal follows
  bool directionSpans = true;          ///< "left of", "at the top left corner of", "to the left": the whole phrase
  bool placingClauseGoal = true;       ///< a placing clause without a goal takes its bare or direction phrase
  bool ofRoomIsSpatial = true;         ///< "the table *of* the kitchen": "of" before a room locates the noun before it
  bool goalLandmarkLocatives = true;   ///< a phrase after a goal does not locate a trajector before the goal
  bool sideToSpans = false;            ///< with direction_spans / placing_clause_goal: "left to", "right to" too

  /// Name and member of every switch, in README order (for ablations and the model file).
  /// A switch missing from a model file is off (the model predates it).
  static const std::vector<std::pair<std::string, bool DecodingRules::*>>& all();
};

/// Optional groups of tagger features (linguistic evidence that does not depend
/// on the corpus' words); each is kept only if the protocol says so (none is).
struct FeatureGroups {
  bool sourceGoalRole = false;    ///< preposition role: source (from/off/out of), goal (to/onto/into, on/in after a placing verb)
  bool directionPhrases = false;  ///< multi-word direction phrases (in front of, left of, at the ... corner)
  bool noLandmark = false;        ///< an indicator word with no noun phrase after it ("directly below .")
  static const std::vector<std::pair<std::string, bool FeatureGroups::*>>& all();
};

class LanguageModel {
 public:
  /// Training settings; the defaults are the ones selected by pooled cross-validation.
  struct Options {
    double entityC = 30.0;        ///< structural SVM C of the entity tagger
    double entityEpsilon = 0.01;  ///< its stopping tolerance (risk gap)
    double relationC = 1.0;       ///< linear SVM C of the relation classifier
    int minFeatureCount = 2;      ///< entity features seen fewer times in training are dropped
    int threads = 1;              ///< 1 keeps the loss sums in one order: bit-identical models everywhere
    DecodingRules rules;          ///< stored in the model file
    FeatureGroups features;       ///< stored in the model file
    /// Synthetic commands (SyntheticCommandGrammar) added to the training corpus:
    /// this many per real sentence (0 = none), generated with `syntheticSeed`.
    double syntheticRatio = 0.0;
    unsigned syntheticSeed = 1;
  };

  LanguageModel();
  ~LanguageModel();
  LanguageModel(LanguageModel&&) noexcept;
  LanguageModel& operator=(LanguageModel&&) noexcept;

  /// Trains both parts on SpERT sentences (entities and relations are used).
  /// Deterministic for a given corpus and options. Throws InvalidInputError on
  /// an empty corpus.
  static LanguageModel train(const std::vector<AnnotatedSentence>& corpus, const Options& options);
  static LanguageModel train(const std::vector<AnnotatedSentence>& corpus) { return train(corpus, Options{}); }

  /// Binary model file (dlib serialisation, format version checked).
  void save(const std::string& path) const;
  /// Throws srp::core::FileError naming the path when missing, corrupt or of an
  /// unknown format version (the fix: retrain with `srp train-language`).
  static LanguageModel load(const std::string& path);

  /// Entities and relations of one tokenised sentence (tokens as written).
  /// `tokens` is copied into the result; an empty input gives an empty result.
  AnnotatedSentence annotate(const std::vector<std::string>& tokens) const;

  /// The decoding rules in use; setDecodingRules changes them (cross-validation
  /// ablations score one trained model under several rule sets).
  const DecodingRules& decodingRules() const;
  void setDecodingRules(const DecodingRules& rules);

  /// Lemmas that the training corpus annotated as actions ("pick", "place", ...).
  const std::vector<std::string>& actionLemmas() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// The shipped model, `datasets/language/model/language_model.dat` of srp's data
/// folder (core::DataPaths). Throws FileError when it is not there.
std::string defaultModelPath();

/// Reads a SpERT corpus file (a JSON array of sentences); throws FileError /
/// InvalidInputError naming the file.
std::vector<AnnotatedSentence> readSpertCorpus(const std::string& path);

}  // namespace srp::language
