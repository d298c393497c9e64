#include "srp/language/SyntheticCommandGrammar.h"

#include <random>
#include <sstream>
#include <string>

namespace srp::language {

namespace {

// Lexicon. Words only (no counts from the corpus); a phrase is space-separated.
const std::vector<std::string> kPickVerbs{"pick", "grab", "take", "lift", "grasp", "get"};
const std::vector<std::string> kPlaceVerbs{"place", "put", "set", "drop", "move", "leave", "lay", "position"};
const std::vector<std::string> kFetchVerbs{"bring", "carry", "move", "take"};
const std::vector<std::string> kColours{"red",  "green", "blue",   "yellow",     "orange",    "white", "black",
                                       "gray", "grey",  "purple", "pink",       "brown",     "cyan",  "turquoise",
                                       "light blue", "dark grey", "dark green", "magenta"};
const std::vector<std::string> kObjects{"block", "cube", "pyramid", "cylinder", "cuboid", "star", "prism", "ball",
                                        "cup",   "bottle", "can",   "bowl",     "mug",    "octagon", "brick",
                                        "triangle", "workpiece", "tetrahedron", "sphere", "screw"};
const std::vector<std::string> kLandmarks{"box", "tray", "table", "plate", "shelf", "block", "cube", "bowl", "basket",
                                          "board", "bin", "container", "pallet", "stack", "tower", "drawer"};
// Where an object goes (goal phrases after a placing verb) and where it is.
const std::vector<std::string> kGoalPhrases{"on",          "in",          "into",          "onto",
                                            "on top of",   "inside",      "to",            "next to",
                                            "in front of", "behind",      "beside",        "above",
                                            "to the left of", "to the right of", "left to", "right to",
                                            "on the left of", "on the right of", "near",   "over",
                                            "at the top left corner of", "at the bottom right corner of",
                                            "in the middle of", "on the top left corner of", "below", "under"};
const std::vector<std::string> kSpatialPhrases{"on",     "in",          "on top of",      "next to",
                                               "near",   "in front of", "behind",         "beside",
                                               "under",  "below",       "to the left of", "to the right of",
                                               "inside", "between",     "at the top left corner of",
                                               "in the middle of", "left of", "right of", "above"};
const std::vector<std::string> kSourcePhrases{"from", "off", "out of", "from the top of", "from on top of"};
// Directions that need no landmark ("put it directly below").
const std::vector<std::string> kBareDirections{"below", "above", "behind", "on the left", "on the right",
                                               "to the left", "to the right", "in front", "on top", "underneath"};
const std::vector<std::string> kAdverbs{"directly", "right", "just", "immediately"};
const std::vector<std::string> kPolite{"please", "can you", "could you"};

class Rng {
 public:
  explicit Rng(unsigned seed) : engine_(seed) {}
  size_t below(size_t n) { return static_cast<size_t>(engine_() % n); }
  bool chance(int percent) { return static_cast<int>(engine_() % 100) < percent; }
  template <typename T>
  const T& pick(const std::vector<T>& v) { return v[below(v.size())]; }

 private:
  std::mt19937_64 engine_;  // fully specified by the standard: same draws everywhere
};

std::vector<std::string> split(const std::string& phrase) {
  std::istringstream in(phrase);
  std::vector<std::string> words;
  for (std::string w; in >> w;) words.push_back(w);
  return words;
}

/// Appends words and records their annotation.
class Builder {
 public:
  int words(const std::string& phrase, const std::string& type = "") {
    const int start = static_cast<int>(s_.tokens.size());
    for (auto& w : split(phrase)) s_.tokens.push_back(w);
    if (!type.empty()) return entity(start, static_cast<int>(s_.tokens.size()), type);
    return -1;
  }
  int entity(int start, int end, const std::string& type) {
    s_.entities.push_back({start, end, type});
    return static_cast<int>(s_.entities.size()) - 1;
  }
  void relation(int head, int tail, const std::string& type) {
    if (head >= 0 && tail >= 0) s_.relations.push_back({head, tail, type});
  }
  /// "the [red] block": returns the head noun's token index.
  int nounPhrase(Rng& rng, const std::string& noun, bool colour = true, const std::string& det = "the") {
    if (!det.empty()) words(det);
    if (colour) words(rng.pick(kColours), "Color");
    words(noun);
    return static_cast<int>(s_.tokens.size()) - 1;
  }
  AnnotatedSentence take(Rng& rng) {
    if (rng.chance(50) && !s_.tokens.empty()) {
      auto& w = s_.tokens.front();
      if (!w.empty() && w[0] >= 'a' && w[0] <= 'z') w[0] = static_cast<char>(w[0] - 'a' + 'A');
    }
    return std::move(s_);
  }

 private:
  AnnotatedSentence s_;
};

/// "Pick up the red block (from the box | on the table | that is on the box)":
/// the action's index; `located` tells whether a spatial phrase followed.
int pickClause(Rng& rng, Builder& b, bool allowSpatial) {
  const std::string verb = rng.pick(kPickVerbs);
  const int action = b.words(verb, "Action");
  if (verb == "pick" || (verb == "lift" && rng.chance(50))) b.words("up");
  const int head = b.nounPhrase(rng, rng.pick(kObjects), rng.chance(75));
  if (!allowSpatial || rng.chance(35)) return action;
  const int kind = static_cast<int>(rng.below(3));
  std::string phrase = kind == 0 ? rng.pick(kSourcePhrases) : rng.pick(kSpatialPhrases);
  if (kind == 2) b.words(rng.pick(std::vector<std::string>{"that is", "which is", "lying", "sitting"}));
  const int trajector = b.entity(head, head + 1, "Trajector");
  const int indicator = b.words(phrase, "SpatialIndicator");
  b.relation(trajector, indicator, "Spatial");
  b.nounPhrase(rng, rng.pick(kLandmarks), rng.chance(60));
  return action;
}

/// "place it (directly) on the green box" / "... directly below": the goal of `action`.
void goalPhrase(Rng& rng, Builder& b, int action) {
  if (rng.chance(12)) {
    if (rng.chance(60)) b.words(rng.pick(kAdverbs));
    b.relation(action, b.words(rng.pick(kBareDirections), "GoalIndicator"), "Transition");
    return;
  }
  b.relation(action, b.words(rng.pick(kGoalPhrases), "GoalIndicator"), "Transition");
  b.nounPhrase(rng, rng.pick(kLandmarks), rng.chance(65));
}

AnnotatedSentence command(Rng& rng) {
  Builder b;
  if (rng.chance(8)) b.words(rng.pick(kPolite));
  switch (rng.below(7)) {
    case 0: {  // pick (with where it is), then place it
      pickClause(rng, b, true);
      b.words(rng.chance(80) ? "and" : ", then");
      const int place = b.words(rng.pick(kPlaceVerbs), "Action");
      b.words(rng.chance(80) ? "it" : "that");
      goalPhrase(rng, b, place);
      break;
    }
    case 1: {  // place / move X from Y on Z: the source is spatial, the goal follows
      const int action = b.words(rng.pick(kPlaceVerbs), "Action");
      const int head = b.nounPhrase(rng, rng.pick(kObjects), rng.chance(75));
      const int trajector = b.entity(head, head + 1, "Trajector");
      b.relation(trajector, b.words(rng.pick(kSourcePhrases), "SpatialIndicator"), "Spatial");
      b.nounPhrase(rng, rng.pick(kLandmarks), rng.chance(60));
      goalPhrase(rng, b, action);
      break;
    }
    case 2: {  // place X (that is at Y) at Z
      const int action = b.words(rng.pick(kPlaceVerbs), "Action");
      const int head = b.nounPhrase(rng, rng.pick(kObjects), rng.chance(75));
      if (rng.chance(40)) {
        b.words(rng.pick(std::vector<std::string>{"that is", "which is"}));
        const int trajector = b.entity(head, head + 1, "Trajector");
        b.relation(trajector, b.words(rng.pick(kSpatialPhrases), "SpatialIndicator"), "Spatial");
        b.nounPhrase(rng, rng.pick(kLandmarks), rng.chance(60));
      }
      goalPhrase(rng, b, action);
      break;
    }
    case 3: {  // conjunction of objects, "them"
      const int pick = b.words(rng.pick(kPickVerbs), "Action");
      (void)pick;
      b.nounPhrase(rng, rng.pick(kObjects), rng.chance(70));
      b.words("and");
      b.nounPhrase(rng, rng.pick(kObjects), rng.chance(70));
      b.words("and");
      const int place = b.words(rng.pick(kPlaceVerbs), "Action");
      b.words("them");
      goalPhrase(rng, b, place);
      break;
    }
    case 4: {  // two sentences
      pickClause(rng, b, true);
      b.words(".");
      const int place = b.words(rng.pick(kPlaceVerbs), "Action");
      b.words(rng.chance(70) ? "it" : "the " + rng.pick(kObjects));
      goalPhrase(rng, b, place);
      b.words(".");
      break;
    }
    case 5: {  // fetch: bring X (from Y) to Z
      const int action = b.words(rng.pick(kFetchVerbs), "Action");
      const int head = b.nounPhrase(rng, rng.pick(kObjects), rng.chance(60));
      if (rng.chance(50)) {
        const int trajector = b.entity(head, head + 1, "Trajector");
        b.relation(trajector, b.words(rng.pick(kSourcePhrases), "SpatialIndicator"), "Spatial");
        b.nounPhrase(rng, rng.pick(kLandmarks), rng.chance(50));
      }
      b.relation(action, b.words(rng.pick(std::vector<std::string>{"to", "into", "onto"}), "GoalIndicator"),
                 "Transition");
      b.nounPhrase(rng, rng.pick(kLandmarks), rng.chance(50));
      break;
    }
    default: {  // pick only
      pickClause(rng, b, true);
      if (rng.chance(30)) b.words(".");
      break;
    }
  }
  if (rng.chance(5)) b.words("please");
  return b.take(rng);
}

}  // namespace

std::vector<AnnotatedSentence> SyntheticCommandGrammar::generate(size_t count, unsigned seed) const {
  Rng rng(seed);
  std::vector<AnnotatedSentence> out;
  out.reserve(count);
  for (size_t i = 0; i < count; ++i) out.push_back(command(rng));
  return out;
}

}  // namespace srp::language
