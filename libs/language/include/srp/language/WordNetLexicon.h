#pragma once
/// \file WordNetLexicon.h
/// \brief Lexicon features of English words from WordNet 3.0 (wordnet-base):
/// parts of speech, base forms and a few semantic classes from the hypernym tree.

#include <map>
#include <mutex>
#include <string>

namespace srp::language {

/// What WordNet knows about one lower-cased word form.
struct WordInfo {
  bool noun = false, verb = false, adjective = false, adverb = false;
  std::string verbLemma;  ///< base form as a verb ("placing" -> "place"), empty if none
  std::string nounLemma;  ///< base form as a noun ("boxes" -> "box"), empty if none
  bool colour = false;     ///< a noun sense under "chromatic color"/"color" (red, grey, ...)
  bool artifact = false;  ///< a noun sense under "artifact" or "object" (box, block, ...)
  bool shape = false;     ///< a noun sense under "shape"/"plane figure"/"solid" (cube, star)
  bool location = false;  ///< a noun sense under "location"/"region" (corner, edge)
  bool room = false;      ///< a noun sense under "room", "building" or "workplace" (kitchen, office, "room" itself)
};

/// Looks words up in WordNet, caching each answer. The WordNet C library keeps
/// global state, so all instances share one lock; lookups are thread-safe.
/// When the WordNet data files are missing every word gets an empty WordInfo
/// (available() is false) and the models lose only these features.
class WordNetLexicon {
 public:
  WordNetLexicon();
  bool available() const { return available_; }
  /// Information for `lowerWord` (ASCII lower case); cached after the first call.
  WordInfo lookup(const std::string& lowerWord) const;

 private:
  bool available_ = false;
  mutable std::mutex mutex_;
  mutable std::map<std::string, WordInfo> cache_;
};

}  // namespace srp::language
