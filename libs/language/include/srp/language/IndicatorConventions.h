#pragma once
/// \file IndicatorConventions.h
/// \brief How the training corpus annotates spatial and goal indicators, counted
/// from its gold spans and applied when decoding the tagger's output.
///
/// Three conventions, each learned from a SpERT corpus by `learn`:
/// - **span length**: when several annotated indicator phrases start at the same
///   word ("on", "on top", "on top of", "on top of the"), how far the corpus'
///   spans reach, keyed by the longest annotated phrase the text spells there
///   (train.json: "on top of the ..." is annotated "on top of" 156 of 160 times);
/// - **indicator type** of an indicator with no action after it, keyed by the
///   clause's action lemma, whether the indicator is directional ("to / into /
///   onto / toward(s)") and whether it is the clause's first indicator, not
///   counting indicators in relative clauses (inRelativeClause)
///   ("take the knife on the board": spatial 34 of 35; "take it to the kitchen":
///   goal 20 of 20; "place it on ...": goal 140 of 143);
/// - **orders only**: indicators are annotated only in a sentence that gives an
///   order, after its action (train: none of 30 prepositions before a sentence's
///   first action, e.g. "there is a row of blocks in the middle. pick ...");
/// - **rarely annotated starts**: words the corpus reads >= 5 times and starts
///   an indicator with in < 2 % of them ("of": 3 of 360, "with", "the") do not
///   start an indicator ("grab hold of the block", "the knife with the handle");
///   nor does a spatial indicator start with a word after the word before it
///   when that pair is read >= 3 times and starts an indicator in <= 10 % of
///   them ("parallelipiped in": 0 of 5, "second from": 0 of 7; goals keep
///   theirs: on train the rule removed right ones among goals in CV).
///
/// Example:
/// \code
///   const auto conventions = IndicatorConventions::learn(readSpertCorpus("train.json"), lemmaOf);
///   conventions.spanLength({"on", "top", "of", "the", "box"}, 0);  // 3
///   conventions.indicatorType("take", "on", true);                  // "SpatialIndicator"
/// \endcode

#include <functional>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "srp/language/TaskPlan.h"

namespace srp::language {

class IndicatorConventions {
 public:
  /// Maps a lower-case action word to its lemma ("placed" -> "place").
  using LemmaFunction = std::function<std::string(const std::string&)>;

  /// A span length is kept when one length covers >= 2/3 of >= 2 gold indicators
  /// starting with the same longest phrase; an indicator type when >= 90 % of
  /// >= 3 gold indicators of the same key agree.
  static IndicatorConventions learn(const std::vector<AnnotatedSentence>& corpus, const LemmaFunction& lemmaOf);

  /// Words of the corpus' indicator span starting at `start` of `lowerTokens`
  /// (lower-case), when the corpus is consistent there.
  std::optional<int> spanLength(const std::vector<std::string>& lowerTokens, int start) const;

  /// Type ("SpatialIndicator" / "GoalIndicator") of an indicator starting with
  /// `firstWord` (lower-case) in a clause of the action `verbLemma`, with no
  /// action after it, when the corpus is consistent there.
  std::optional<std::string> indicatorType(const std::string& verbLemma, const std::string& firstWord,
                                           bool firstInClause) const;

  /// Whether the indicator starting at `start` describes where an object is, by
  /// its syntax: after a participle ("the cube placed on", "sitting on top of") or
  /// in a relative clause ("the block that is on"). Train: 128 of 128 such
  /// indicators are spatial; they are not the clause's first (goal) indicator.
  static bool inRelativeClause(const std::vector<std::string>& lowerTokens, int start);

  /// Sets each indicator of `entities` (spans over `tokens`, as written) to its
  /// conventional length; a span grows only over words no other entity holds.
  void applySpanLengths(const std::vector<std::string>& tokens, std::vector<EntitySpan>& entities) const;

  /// Removes indicators before the first action of their sentence (sentences end
  /// at ". ! ?") and in sentences without an action, unless no action was
  /// recognised at all (then the tagger missed it and its indicators are kept).
  static void dropIndicatorsOutsideOrders(const std::vector<std::string>& tokens, std::vector<EntitySpan>& entities);

  /// Removes indicators whose first word the corpus often reads but (almost)
  /// never annotates as an indicator's start ("grab hold *of*", "the knife
  /// *with* the black handle": a word seen >= 5 times, < 2 % annotated), and
  /// indicators tagged spatial whose (previous word, first word) pair is such
  /// a pair ("parallelipiped *in* the corner": seen >= 3 times, <= 10 %).
  /// `byWord` / `byPair` switch the two halves (pooled-CV ablations).
  void dropRarelyAnnotatedStarts(const std::vector<std::string>& tokens, std::vector<EntitySpan>& entities,
                                 bool byWord = true, bool byPair = true) const;

  nlohmann::json toJson() const;
  /// Throws InvalidInputError when a field is missing.
  static IndicatorConventions fromJson(const nlohmann::json& j);

 private:
  std::string longestPhraseAt(const std::vector<std::string>& lowerTokens, int start) const;

  std::set<std::string> phrases_;                 ///< annotated indicator spans, lower-case, ' '-joined
  std::map<std::string, int> lengthByPhrase_;     ///< longest known phrase at a start -> annotated length
  std::map<std::string, std::string> typeByKey_;  ///< "verb|dir|first" -> indicator type
  std::set<std::string> rarelyAnnotatedStarts_;   ///< frequent words almost never starting an indicator
  std::set<std::string> rarelyAnnotatedPairs_;    ///< "previous|word" pairs almost never starting one
};

}  // namespace srp::language
