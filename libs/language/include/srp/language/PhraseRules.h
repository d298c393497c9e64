#pragma once
/// \file PhraseRules.h
/// \brief Decoding rules about the words of an indicator phrase, applied to the
/// tagger's entities (DecodingRules in LanguageModel.h switches each on or off).
///
/// Each rule is linguistic (closed word classes of English and the corpus'
/// span conventions, datasets/language/capabilities/README.md), not counted on
/// the corpus; the protocol (libs/language/README.md) keeps or drops it:
/// - direction spans: a multi-word direction phrase is one indicator, up to its
///   "of" / "to" ("left of", "right to", "in front of", "at the top left corner of",
///   "in the exact center of", "to the left of"), or, with no landmark after it,
///   up to its direction noun ("to the left", "in the middle", "on top"). A
///   region named without a direction word is the landmark ("in *the corner* of
///   the board"), and so is a side after "on / at / in" with no landmark ("on
///   *the left*");
/// - source spans: "out of", "away from" are one indicator;
/// - placing clause goal: a placing verb's clause without a goal takes its
///   direction phrase or its preposition with no landmark ("place it directly
///   *below*"); a phrase whose only landmark is "here" / "there" is no indicator;
/// - room "of": "the *table* *of* the kitchen": "of" between a noun and a room
///   (WordNet: a room, building or workplace) is a spatial indicator locating
///   the noun before it.
///
/// Example:
/// \code
///   PhraseRules::directionSpanLength({"place", "it", "at", "the", "top", "left", "corner", "of", "the", "box"}, 2);  // 6
///   PhraseRules::directionSpanLength({"put", "it", "in", "the", "corner", "of", "the", "board"}, 2);               // 0
/// \endcode

#include <functional>
#include <string>
#include <vector>

#include "srp/language/TaskPlan.h"

namespace srp::language {

class PhraseRules {
 public:
  /// Maps a lower-case word to its lemma ("placing" -> "place").
  using LemmaFunction = std::function<std::string(const std::string&)>;
  /// A test on a lower-case word (a noun, a room).
  using WordTest = std::function<bool(const std::string&)>;

  /// Words of the direction phrase starting at `i` of `lower` (lower-case tokens)
  /// as the corpus spans it, 0 when none starts there (class comment); "left to" /
  /// "right to" only with `sideTo` (train.json has one "place it right *to* the ...").
  static int directionSpanLength(const std::vector<std::string>& lower, int i, bool sideTo = true);
  /// Whether nothing that could be a landmark starts at `k`: the end, punctuation,
  /// "and", "then", "or", "please".
  static bool landmarklessAt(const std::vector<std::string>& lower, int k);
  /// "from", "off", "out of" or "away from" starts at `start`.
  static bool isSourceAt(const std::vector<std::string>& lower, int start);
  /// Verbs that put an object somewhere (put, place, drop, set, move, ...), by lemma.
  static bool isPlacingVerb(const std::string& lemma);

  /// Grows each indicator to its direction phrase (over free words and indicators
  /// inside it) and a lone "to" / "of" back over its relational word ("right *to*").
  static void applyDirectionSpans(const std::vector<std::string>& lower, std::vector<EntitySpan>& entities,
                                  bool sideTo = true);
  /// Grows an indicator at "out" over "of", and one at "from" back over "away".
  static void applySourceSpans(const std::vector<std::string>& lower, std::vector<EntitySpan>& entities);
  /// Adds the goal of each placing clause that has none, and drops indicators
  /// whose only landmark is "here" / "there".
  static void addPlacingClauseGoals(const std::vector<std::string>& lower, std::vector<EntitySpan>& entities,
                                    const LemmaFunction& lemmaOf, bool sideTo = true);
  /// Adds "of" between a noun and a room as a spatial indicator, and the noun
  /// before it as its trajector.
  static void addRoomOfIndicators(const std::vector<std::string>& lower, std::vector<EntitySpan>& entities,
                                  const WordTest& isNoun, const WordTest& isRoom);
};

}  // namespace srp::language
