#pragma once
/// \file SyntheticCommandGrammar.h
/// \brief A small seeded grammar of pick & place commands that writes annotated
/// sentences in the corpus' SpERT schema (synthetic training data, the way the
/// thesis rendered synthetic images for its detector).
///
/// Structures (each a template filled from a lexicon of verbs, colours, objects
/// and landmarks; annotation as the corpus' guide: Action on the verb, Color on
/// the colour words, GoalIndicator on where the object goes with a Transition
/// from its action, SpatialIndicator on where an object is with a Trajector on
/// the located noun and a Spatial relation):
/// - source and goal phrases: "place the red block from the box on the tray",
///   "take the cup out of the bowl and put it on the plate";
/// - multi-word directions: "to the left of", "in front of", "on top of",
///   "next to", "left to", "at the top left corner of";
/// - directions with no landmark: "put it directly below .";
/// - pronouns ("it", "them"), relative clauses ("the cube that is on the box"),
///   conjunctions ("the cube and the star"), orders of two sentences.
///
/// Example:
/// \code
///   const auto sentences = SyntheticCommandGrammar().generate(500, 1);  // same seed, same sentences
/// \endcode

#include <vector>

#include "srp/language/TaskPlan.h"

namespace srp::language {

class SyntheticCommandGrammar {
 public:
  /// `count` annotated commands drawn with the seed `seed` (a 64-bit Mersenne
  /// Twister whose draws are mapped to choices without std distributions, so the
  /// sentences are the same on every platform).
  std::vector<AnnotatedSentence> generate(size_t count, unsigned seed) const;
};

}  // namespace srp::language
