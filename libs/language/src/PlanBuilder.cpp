#include "srp/language/PlanBuilder.h"

#include <algorithm>
#include <sstream>
#include <cctype>
#include <map>
#include <optional>
#include <set>

#include "srp/language/Tokenizer.h"

namespace srp::language {

namespace {

const std::set<std::string> kPickVerbs{"pick", "take", "grab", "grasp", "lift", "get", "remove", "fetch", "collect",
                                       "hold", "catch", "retrieve", "unload"};
const std::set<std::string> kPlaceVerbs{"place", "put", "set", "position", "drop", "release", "lay", "deposit",
                                        "insert", "stack", "load", "leave", "store", "arrange"};
const std::set<std::string> kMoveVerbs{"move", "bring", "carry", "transfer", "relocate", "return", "push", "slide",
                                       "give", "hand", "pass", "shift", "transport"};
const std::set<std::string> kDeterminers{"the", "a", "an", "this", "these", "those", "another", "each", "every",
                                         "some", "any", "all", "both", "my", "your", "its", "their", "other"};
const std::set<std::string> kPronouns{"it", "them", "they", "that", "those", "these", "this", "both"};
const std::set<std::string> kParticles{"up", "down", "away"};
const std::set<std::string> kStopWords{"and", "or", "but", "then", "that", "which", "who", "while", "with", "by",
                                       "of", "to", "for", "as", "so", "is", "are", "be", "was", "very", "not"};
const std::set<std::string> kSourceWords{"from", "off", "out", "away"};
// Multi-word indicators first (longest match wins).
const std::vector<std::vector<std::string>> kIndicatorPhrases{
    {"in", "front", "of"}, {"on", "top", "of"}, {"to", "the", "left", "of"}, {"to", "the", "right", "of"},
    {"out", "of"},         {"next", "to"},      {"adjacent", "to"},          {"close", "to"},
    {"on", "to"},          {"inside", "of"},    {"in"},                      {"into"},
    {"on"},                {"onto"},            {"at"},                      {"from"},
    {"off"},               {"beside"},          {"alongside"},               {"near"},
    {"behind"},            {"above"},           {"below"},                   {"under"},
    {"over"},              {"between"},         {"inside"},                  {"atop"},
    {"to"},                {"toward"},          {"towards"},                 {"underneath"}};

// Noun-phrase modifiers that pick one of several objects of a kind (ObjectRef).
const std::map<std::string, int> kOrdinals{{"first", 1},  {"second", 2}, {"third", 3},  {"fourth", 4},
                                           {"fifth", 5},  {"sixth", 6},  {"seventh", 7}, {"eighth", 8},
                                           {"ninth", 9},  {"tenth", 10}, {"1st", 1},     {"2nd", 2},
                                           {"3rd", 3},    {"4th", 4},    {"5th", 5},     {"last", -1}};
const std::map<std::string, std::string> kSuperlatives{
    {"leftmost", "leftmost"},   {"rightmost", "rightmost"}, {"frontmost", "frontmost"}, {"foremost", "frontmost"},
    {"backmost", "backmost"},   {"rearmost", "backmost"},   {"hindmost", "backmost"},   {"biggest", "biggest"},
    {"largest", "biggest"},     {"smallest", "smallest"},   {"highest", "highest"},     {"topmost", "highest"},
    {"lowest", "lowest"},       {"closest", "closest"},     {"nearest", "closest"},     {"farthest", "farthest"},
    {"furthest", "farthest"}};
// "the left cube": a side adjective before the name reads as the superlative.
const std::map<std::string, std::string> kSideAdjectives{
    {"left", "leftmost"}, {"right", "rightmost"}, {"front", "frontmost"}, {"back", "backmost"}, {"rear", "backmost"}};

enum class VerbKind { Pick, Place, Move };

/// The view words of a corner phrase ("in the front left corner of" -> "front left"), "" otherwise.
std::string cornerOf(const std::string& relation) {
  std::istringstream words(relation);
  std::vector<std::string> w;
  for (std::string x; words >> x;) w.push_back(x);
  const auto corner = std::find(w.begin(), w.end(), "corner");
  if (corner == w.end()) return {};
  std::string out;
  for (auto it = w.begin(); it != corner; ++it)
    if (*it == "left" || *it == "right" || *it == "front" || *it == "back" || *it == "rear")
      out += (out.empty() ? "" : " ") + *it;
  return out;
}

struct Mention {
  ObjectRef object;
  TokenAnchor anchor;
};

struct NounPhrase {
  std::optional<Mention> mention;  // empty for a pronoun
  bool pronoun = false;
  bool plural = false;  // "them"/"they"/"those"
  int end = 0;
};

struct Location {
  LocationRef ref;
  TokenAnchor anchor;
  bool source = false;
  bool back = false;
};

class SentenceView {
 public:
  SentenceView(const AnnotatedSentence& s, int sentenceId, const WordNetLexicon& lexicon)
      : s_(s), id_(sentenceId), lexicon_(lexicon), n_(static_cast<int>(s.tokens.size())), owner_(n_, -1) {
    for (const auto& t : s.tokens) lower_.push_back(toLowerAscii(t));
    for (size_t e = 0; e < s.entities.size(); ++e)
      for (int k = s.entities[e].start; k < s.entities[e].end && k < n_; ++k) owner_[k] = static_cast<int>(e);
  }

  int size() const { return n_; }
  int id() const { return id_; }
  const std::string& lower(int k) const { return lower_[k]; }
  std::string typeAt(int k) const { return owner_[k] < 0 ? std::string() : s_.entities[owner_[k]].type; }
  const EntitySpan* entityAt(int k) const { return owner_[k] < 0 ? nullptr : &s_.entities[owner_[k]]; }

  std::string verbLemma(int k) const {
    const WordInfo info = lexicon_.lookup(lower_[k]);
    return info.verbLemma.empty() ? lower_[k] : info.verbLemma;
  }

  std::optional<VerbKind> verbKind(int k) const {
    const std::string lemma = verbLemma(k);
    if (kPickVerbs.count(lemma)) return VerbKind::Pick;
    if (kPlaceVerbs.count(lemma)) return VerbKind::Place;
    if (kMoveVerbs.count(lemma)) return VerbKind::Move;
    return std::nullopt;
  }

  /// A recognised Action, or a known manipulation verb in verb position (not after a determiner).
  bool isAction(int k) const {
    const std::string type = typeAt(k);
    if (type == "Action") {
      // "Finish by setting ...", "Begin by picking ...": the real verb comes after "by".
      return verbKind(k) || k + 1 >= n_ || (lower_[k + 1] != "by" && lower_[k + 1] != "with");
    }
    if (!(type.empty() || type == "Trajector") || !verbKind(k)) return false;
    if (k > 0 && (kDeterminers.count(lower_[k - 1]) || lexicon_.lookup(lower_[k - 1]).colour)) return false;
    if (k + 1 < n_ && lower_[k + 1] == "of") return false;
    // A verb needs something after it ("set"/"hand"/"leave" are nouns too).
    return k + 1 < n_ && !std::ispunct(static_cast<unsigned char>(lower_[k + 1][0]));
  }

  bool isColourWord(int k) const {
    if (typeAt(k) == "Color") return true;
    return typeAt(k).empty() && lexicon_.lookup(lower_[k]).colour && k + 1 < n_ && isNameWord(k + 1, false);
  }

  /// A word that can be part of an object name.
  bool isNameWord(int k, bool allowColour = true) const {
    const std::string& w = lower_[k];
    const std::string& raw = s_.tokens[k];
    if (raw.empty() || std::ispunct(static_cast<unsigned char>(raw[0]))) return false;
    const std::string type = typeAt(k);
    if (type == "Action" || type == "SpatialIndicator" || type == "GoalIndicator") return false;
    if (type == "Color") return allowColour;
    if (kStopWords.count(w) || kDeterminers.count(w) || kParticles.count(w)) return raw == "A";  // "item A"
    if (w == "it" || w == "them" || w == "they") return false;
    if (w == "back" && k + 1 < n_ && isIndicatorStart(k + 1)) return false;  // "back to the blue box"
    if (isIndicatorStart(k)) return false;
    if (std::isdigit(static_cast<unsigned char>(raw[0]))) return true;                         // "Location 2"
    if (raw.size() == 1 && std::isupper(static_cast<unsigned char>(raw[0]))) return true;     // "item B"
    if (std::isupper(static_cast<unsigned char>(raw[0])) && k > 0) return true;                // proper names
    const WordInfo info = lexicon_.lookup(w);
    if (info.noun || info.adjective) return !(info.adverb && !info.noun && !info.adjective);
    return !info.verb && !info.adverb && w.find_first_not_of("abcdefghijklmnopqrstuvwxyz-") == std::string::npos;
  }

  /// Length of a known indicator phrase starting at k (0 if none).
  int indicatorLength(int k) const {
    if (const EntitySpan* e = entityAt(k))
      if ((e->type == "SpatialIndicator" || e->type == "GoalIndicator") && e->start == k) return e->end - e->start;
    for (const auto& phrase : kIndicatorPhrases) {
      const int m = static_cast<int>(phrase.size());
      if (k + m > n_) continue;
      bool match = true;
      for (int i = 0; i < m && match; ++i) match = lower_[k + i] == phrase[i] && typeAt(k + i).empty();
      if (match) return m;
    }
    return 0;
  }
  bool isIndicatorStart(int k) const { return indicatorLength(k) > 0; }

  /// Object name as written: common nouns lower-cased, names and letters kept.
  std::string nameWord(int k) const {
    const std::string& raw = s_.tokens[k];
    const bool keep = (raw.size() == 1 && std::isupper(static_cast<unsigned char>(raw[0]))) ||
                      (k > 0 && std::isupper(static_cast<unsigned char>(raw[0])) &&
                       lower_[k - 1] != "." && lower_[k - 1] != ",");
    return keep ? raw : lower_[k];
  }

  /// A noun phrase starting at k: determiners, colours, name words; or a pronoun.
  std::optional<NounPhrase> nounPhrase(int k) const {
    NounPhrase np;
    if (k >= n_) return std::nullopt;
    if (lower_[k] == "the" && k + 1 < n_ && lower_[k + 1] == "same") {
      np.pronoun = true;
      np.end = k + 2;
      if (np.end < n_ && (lower_[np.end] == "one" || lower_[np.end] == "object" || lower_[np.end] == "objects")) ++np.end;
      return np;
    }
    if (kPronouns.count(lower_[k]) && !(k + 1 < n_ && isNameWord(k + 1))) {
      np.pronoun = true;
      np.plural = lower_[k] != "it" && lower_[k] != "that" && lower_[k] != "this";
      np.end = k + 1;
      return np;
    }
    int i = k;
    while (i < n_ && (kDeterminers.count(lower_[i]) && s_.tokens[i] != "A")) ++i;
    Mention m;
    std::vector<std::string> name, colours;
    int lastNameToken = -1;
    while (i < n_) {
      if (name.empty() && typeAt(i) != "Action" && kOrdinals.count(lower_[i]) && i + 1 < n_) {
        m.object.ordinal = kOrdinals.at(lower_[i]);
        ++i;
      } else if (name.empty() && typeAt(i) != "Action" && kSuperlatives.count(lower_[i]) && i + 1 < n_ &&
                 isNameWord(i + 1)) {
        m.object.superlative = kSuperlatives.at(lower_[i]);
        ++i;
      } else if (name.empty() && kSideAdjectives.count(lower_[i]) && typeAt(i).empty() && i + 1 < n_ &&
                 (isNameWord(i + 1, false) || isColourWord(i + 1)) && !isIndicatorStart(i + 1)) {
        m.object.superlative = kSideAdjectives.at(lower_[i]);
        ++i;
      } else if (!name.empty() && kSuperlatives.count(lower_[i])) {
        break;  // "the cube closest to the box": the modifier follows the name
      } else if (isColourWord(i)) {
        colours.push_back(lower_[i]);
        ++i;
      } else if (isNameWord(i, false)) {
        name.push_back(nameWord(i));
        lastNameToken = i;
        ++i;
      } else {
        break;
      }
    }
    if (name.empty()) return std::nullopt;
    for (size_t j = 0; j < name.size(); ++j) m.object.name += (j ? " " : "") + name[j];
    if (!colours.empty()) {
      std::string c;
      for (size_t j = 0; j < colours.size(); ++j) c += (j ? " " : "") + colours[j];
      m.object.colour = c;
    }
    m.anchor = {id_, lastNameToken};
    i = objectModifiers(i, m.object);
    np.mention = m;
    np.end = i;
    return np;
  }

  /// Modifiers after an object's name that say which one it is; returns the
  /// token after them. "closest to the box" / "nearest the box" / "farthest from
  /// the box" -> relation {"closest to"/"farthest from", box}; "that is behind the
  /// star" / "which is in the blue box" -> relation {"behind"/"in", star/box}.
  int objectModifiers(int i, ObjectRef& object) const {
    for (;;) {
      // Only right after the name: in "move the nearest cube to the box" the "to" is the goal.
      const std::string word = i < n_ && kSuperlatives.count(lower_[i]) ? kSuperlatives.at(lower_[i]) : "";
      if ((word == "closest" || word == "farthest") && i + 1 < n_) {
        int j = i + 1;
        if (lower_[j] == "to" || lower_[j] == "from") ++j;
        if (const auto lm = nounPhrase(j); lm && lm->mention) {
          object.relations.push_back(
              {word == "closest" ? "closest to" : "farthest from", lm->mention->object, std::nullopt, {}});
          i = lm->end;
          continue;
        }
      }
      if (i + 2 < n_ && (lower_[i] == "that" || lower_[i] == "which") &&
          (lower_[i + 1] == "is" || lower_[i + 1] == "are" || lower_[i + 1] == "stands" || lower_[i + 1] == "lies" ||
           lower_[i + 1] == "sits")) {
        const int len = indicatorLength(i + 2);
        if (len > 0) {
          std::string relation;
          for (int j = i + 2; j < i + 2 + len; ++j) relation += (j > i + 2 ? " " : "") + lower_[j];
          if (const auto lm = nounPhrase(i + 2 + len); lm && lm->mention) {
            object.relations.push_back({relation, lm->mention->object, std::nullopt, {}});
            i = lm->end;
            continue;
          }
        }
      }
      return i;
    }
  }

 private:
  const AnnotatedSentence& s_;
  int id_;
  const WordNetLexicon& lexicon_;
  int n_;
  std::vector<int> owner_;
  std::vector<std::string> lower_;
};

struct Referent {
  std::vector<int> stepIndices;
};

bool sameObject(const ObjectRef& a, const ObjectRef& b) {
  // "the first cube" and "the second cube" are two objects; "the cube" may be either.
  return a.name == b.name && (!a.colour || !b.colour || *a.colour == *b.colour) &&
         (!a.ordinal || !b.ordinal || *a.ordinal == *b.ordinal) &&
         (a.superlative.empty() || b.superlative.empty() || a.superlative == b.superlative);
}

/// The steps an instruction's clauses make, in order (buildPlanSteps): each
/// clause's target objects (a noun phrase list after the verb, or the latest
/// clause's objects for a pronoun) and its source and target locations.
class PlanStepsBuilder {
 public:
  explicit PlanStepsBuilder(std::vector<std::string>& warnings) : warnings_(warnings) {}

  void addSentence(const SentenceView& v, std::size_t sid) {
    std::vector<int> actions;
    for (int k = 0; k < v.size(); ++k)
      if (v.isAction(k) && (actions.empty() || actions.back() != k - 1 || v.typeAt(k) != "Action")) actions.push_back(k);
    for (std::size_t a = 0; a < actions.size(); ++a)
      addClause(v, sid, actions[a], a + 1 < actions.size() ? actions[a + 1] : v.size());
  }

  std::vector<PlanStep>& steps() { return steps_; }

 private:
  void addClause(const SentenceView& v, std::size_t sid, int verb, int clauseEnd) {
    const VerbKind kind = v.verbKind(verb).value_or(VerbKind::Move);
    int k = verb + 1;
    while (k < clauseEnd && (kParticles.count(v.lower(k)) || v.typeAt(k) == "Action")) ++k;

    bool namedObjects = false;
    std::vector<int> clauseSteps = clauseObjects(v, sid, k, clauseEnd, namedObjects);
    if (clauseSteps.empty()) clauseSteps = last_.stepIndices;
    if (!namedObjects && clauseSteps.empty()) return;
    std::sort(clauseSteps.begin(), clauseSteps.end());
    clauseSteps.erase(std::unique(clauseSteps.begin(), clauseSteps.end()), clauseSteps.end());

    applyLocations(clauseSteps, clauseLocations(v, k, clauseEnd, kind, clauseSteps));
    last_.stepIndices = clauseSteps;
  }

  /// Target objects: a noun phrase list right after the verb, from `k` (left
  /// after the list); `namedObjects` is set when one is not a pronoun.
  std::vector<int> clauseObjects(const SentenceView& v, std::size_t sid, int& k, int clauseEnd, bool& namedObjects) {
    std::vector<int> clauseSteps;
    while (k < clauseEnd) {
      const auto np = v.nounPhrase(k);
      if (!np || np->end > clauseEnd) break;
      if (np->pronoun) {
        clauseSteps.insert(clauseSteps.end(), last_.stepIndices.begin(), last_.stepIndices.end());
        if (last_.stepIndices.empty())
          warnings_.push_back("sentence " + std::to_string(sid + 1) + ": '" + v.lower(k) +
                              "' refers to no earlier object; ignored");
      } else {
        namedObjects = true;
        clauseSteps.push_back(stepFor(*np->mention));
      }
      k = np->end;
      // "X and Y", "X, Y and Z": more objects unless an action or indicator follows.
      if (k < clauseEnd && (v.lower(k) == "and" || v.lower(k) == ",")) {
        int j = k + 1;
        if (j < clauseEnd && v.lower(j) == "and") ++j;
        if (j < clauseEnd && !v.isIndicatorStart(j) && v.nounPhrase(j)) {
          k = j;
          continue;
        }
      }
      break;
    }
    return clauseSteps;
  }

  /// Locations: indicator + landmark phrases anywhere in the rest of the clause
  /// (from `k`). Gapping ("place the cuboid in the gray box and the star next to
  /// the cuboid") applies the locations so far and moves on to the next object:
  /// `clauseSteps` is then that object's step. Returns the last object's locations.
  std::vector<Location> clauseLocations(const SentenceView& v, int k, int clauseEnd, VerbKind kind,
                                        std::vector<int>& clauseSteps) {
    std::vector<Location> locations;
    for (int i = k; i < clauseEnd;) {
      int len = v.indicatorLength(i);
      if (len == 0) {
        // Gapping: "place the cuboid in the gray box and the star next to the cuboid".
        if (v.lower(i) == "and" || v.lower(i) == ",") {
          int j = i + 1;
          if (j < clauseEnd && v.lower(j) == "and") ++j;
          const auto np = v.nounPhrase(j);
          if (np && !np->pronoun && np->end < clauseEnd && v.isIndicatorStart(np->end)) {
            applyLocations(clauseSteps, locations);
            locations.clear();
            clauseSteps = {stepFor(*np->mention)};
            i = np->end;
            continue;
          }
        }
        ++i;
        continue;
      }
      // A recognised "adjacent"/"close" without its "to": take the connecting word along.
      if (i + len < clauseEnd && !v.nounPhrase(i + len) &&
          (v.lower(i + len) == "to" || v.lower(i + len) == "of" || v.lower(i + len) == "from"))
        ++len;
      std::string relation;
      for (int j = i; j < i + len; ++j) relation += (j > i ? " " : "") + v.lower(j);
      auto np = v.nounPhrase(i + len);
      if (np && np->pronoun && np->end <= clauseEnd) {
        // "next to it": the latest object that is not the one being moved.
        for (int s : last_.stepIndices)
          if (std::find(clauseSteps.begin(), clauseSteps.end(), s) == clauseSteps.end() && !np->mention)
            np->mention = Mention{steps_[s].object, steps_[s].objectAnchor};
      }
      if (!np || !np->mention || np->end > clauseEnd) {
        i += len;
        continue;
      }
      Location loc;
      loc.ref = {relation, np->mention->object, std::nullopt, cornerOf(relation)};
      loc.anchor = np->mention->anchor;
      loc.back = i > 0 && v.lower(i - 1) == "back";
      loc.source = isSource(v, i, np->end, clauseEnd, kind, locations);
      locations.push_back(loc);
      i = np->end;
    }
    return locations;
  }

  /// Whether the location phrase at `i` (its landmark ending at `landmarkEnd`)
  /// says where the objects come from, after `earlier` locations of the clause.
  static bool isSource(const SentenceView& v, int i, int landmarkEnd, int clauseEnd, VerbKind kind,
                       const std::vector<Location>& earlier) {
    const std::string type = v.typeAt(i);
    if (kSourceWords.count(v.lower(i))) return true;
    if (type == "GoalIndicator") return false;
    if (type != "SpatialIndicator" && !type.empty()) return false;  // a Location's default
    const bool targetSeen = std::any_of(earlier.begin(), earlier.end(), [](const Location& l) { return !l.source; });
    if (kind == VerbKind::Pick) return !targetSeen;
    if (kind == VerbKind::Place) return false;  // "place X next to Y in Z": every phrase says where X goes
    // "move X on top of Y to Z": a spatial phrase before a directional goal is the source.
    bool directionalGoalLater = false;
    for (int j = landmarkEnd; j < clauseEnd; ++j) {
      const std::string& w = v.lower(j);
      directionalGoalLater |= v.typeAt(j) == "GoalIndicator" &&
                              (w == "to" || w == "onto" || w == "into" || w == "toward" || w == "towards");
    }
    return !targetSeen && directionalGoalLater;
  }

  /// Reuse an open step of the same object (picked, not yet placed), else a new step.
  int stepFor(const Mention& m) {
    for (int s = static_cast<int>(steps_.size()) - 1; s >= 0; --s)
      if (sameObject(steps_[s].object, m.object) && steps_[s].target.empty()) return s;
    PlanStep step;
    step.object = m.object;
    step.objectAnchor = m.anchor;
    steps_.push_back(step);
    return static_cast<int>(steps_.size()) - 1;
  }

  void applyLocations(const std::vector<int>& stepIndices, const std::vector<Location>& locations) {
    for (int s : stepIndices)
      for (const auto& loc : locations) {
        auto& list = loc.source ? steps_[s].source : steps_[s].target;
        auto& anchors = loc.source ? steps_[s].sourceAnchors : steps_[s].targetAnchors;
        if (std::find(list.begin(), list.end(), loc.ref) == list.end()) {
          list.push_back(loc.ref);
          anchors.push_back(loc.anchor);
        }
        steps_[s].isReturn |= loc.back;
      }
  }

  std::vector<PlanStep> steps_;
  Referent last_;  // steps of the latest clause that named objects
  std::vector<std::string>& warnings_;
};

/// "Only the star this time": no action, but objects of the known plan -> those known steps.
std::vector<PlanStep> knownStepsNamed(const std::vector<AnnotatedSentence>& sentences, const WordNetLexicon& lexicon,
                                      const std::vector<PlanStep>& knownSteps) {
  std::vector<PlanStep> steps;
  for (std::size_t sid = 0; sid < sentences.size(); ++sid) {
    const SentenceView v(sentences[sid], static_cast<int>(sid), lexicon);
    for (int k = 0; k < v.size(); ++k) {
      const auto np = v.nounPhrase(k);
      if (!np || !np->mention) continue;
      for (const auto& known : knownSteps)
        if (sameObject(known.object, np->mention->object) &&
            std::none_of(steps.begin(), steps.end(), [&](const PlanStep& s) { return s.object == known.object; })) {
          steps.push_back(known);
          steps.back().objectAnchor = np->mention->anchor;
        }
      k = np->end - 1;
    }
  }
  return steps;
}

/// "back to": complete a return from the move it reverses (an earlier step, else a known one).
void completeReturns(std::vector<PlanStep>& steps, const std::vector<PlanStep>& knownSteps,
                     std::vector<std::string>& warnings) {
  for (std::size_t s = 0; s < steps.size(); ++s) {
    auto& step = steps[s];
    if (!step.isReturn || (!step.source.empty() && !step.target.empty())) continue;
    const PlanStep* known = nullptr;
    for (std::size_t j = 0; j < s; ++j)
      if (sameObject(steps[j].object, step.object) && !steps[j].isReturn) known = &steps[j];
    if (!known)
      for (const auto& j : knownSteps)
        if (sameObject(j.object, step.object)) known = &j;
    if (!known) {
      warnings.push_back("'back' for the " + describe(step.object) + ", but no earlier move of it is known");
      continue;
    }
    if (step.source.empty()) {
      step.source = known->target;
      step.sourceAnchors.assign(step.source.size(), TokenAnchor{});
    }
    if (step.target.empty()) {
      step.target = known->source;
      step.targetAnchors.assign(step.target.size(), TokenAnchor{});
    }
  }
}

}  // namespace

std::vector<PlanStep> buildPlanSteps(const std::vector<AnnotatedSentence>& sentences, const WordNetLexicon& lexicon,
                                     const std::vector<PlanStep>& knownSteps, std::vector<std::string>& warnings) {
  PlanStepsBuilder builder(warnings);
  for (std::size_t sid = 0; sid < sentences.size(); ++sid)
    builder.addSentence(SentenceView(sentences[sid], static_cast<int>(sid), lexicon), sid);
  std::vector<PlanStep> steps = std::move(builder.steps());
  if (steps.empty() && !knownSteps.empty()) steps = knownStepsNamed(sentences, lexicon, knownSteps);
  completeReturns(steps, knownSteps, warnings);
  return steps;
}

}  // namespace srp::language
