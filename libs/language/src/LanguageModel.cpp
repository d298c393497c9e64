#include "srp/language/LanguageModel.h"

#include <dlib/svm.h>
#include <dlib/svm_threaded.h>

#include <algorithm>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <unordered_map>

#include "srp/core/DataPaths.h"
#include "srp/core/Error.h"
#include "srp/core/Json.h"
#include "srp/core/OutputFile.h"
#include "srp/language/IndicatorConventions.h"
#include "srp/language/PhraseRules.h"
#include "srp/language/SyntheticCommandGrammar.h"
#include "srp/language/Tokenizer.h"
#include "srp/language/WordNetLexicon.h"

namespace srp::language {

namespace {

constexpr int kModelFormatVersion = 4;  // 2: indicator span and type conventions; 3: rarely annotated starts;
                                        // 4: decoding rule switches and feature groups
const std::vector<std::string> kEntityTypes{"Action", "Trajector", "SpatialIndicator", "GoalIndicator", "Color"};
constexpr unsigned long kNumLabels = 11;  // O, then B-/I- for each of the five types

// Label encoding: 0 = O, 1 + 2t = B-type t, 2 + 2t = I-type t.
inline bool isInside(unsigned long label) { return label != 0 && label % 2 == 0; }
inline unsigned long typeOfLabel(unsigned long label) { return (label - 1) / 2; }

/// dlib sequence_labeler feature extractor: each token carries the ids of its
/// (label-independent) features; weights are per (label, feature) plus label
/// transitions and a start-label bias.
class EntityFeatureExtractor {
 public:
  using sequence_type = std::vector<std::vector<unsigned long>>;
  unsigned long numEmission = 0;

  unsigned long num_features() const { return kNumLabels * numEmission + kNumLabels * kNumLabels + kNumLabels; }
  unsigned long order() const { return 1; }
  unsigned long num_labels() const { return kNumLabels; }

  template <typename EXP>
  bool reject_labeling(const sequence_type&, const dlib::matrix_exp<EXP>& y, unsigned long position) const {
    if (!isInside(y(0))) return false;
    if (position == 0) return true;  // I-X cannot start a sentence
    const unsigned long prev = y(1);
    return prev == 0 || typeOfLabel(prev) != typeOfLabel(y(0));  // I-X follows B-X or I-X only
  }

  template <typename feature_setter, typename EXP>
  void get_features(feature_setter& set_feature, const sequence_type& x, const dlib::matrix_exp<EXP>& y,
                    unsigned long position) const {
    const unsigned long label = y(0);
    for (unsigned long f : x[position]) set_feature(label * numEmission + f);
    if (y.size() > 1)
      set_feature(kNumLabels * numEmission + y(1) * kNumLabels + label);
    else
      set_feature(kNumLabels * numEmission + kNumLabels * kNumLabels + label);
  }
};

void serialize(const EntityFeatureExtractor& fe, std::ostream& out) { dlib::serialize(fe.numEmission, out); }
void deserialize(EntityFeatureExtractor& fe, std::istream& in) { dlib::deserialize(fe.numEmission, in); }

using SparseVector = std::vector<std::pair<unsigned long, double>>;
using RelationKernel = dlib::sparse_linear_kernel<SparseVector>;

const std::set<std::string> kPronouns{"it", "them", "they", "this", "that", "these", "those", "one"};
const std::set<std::string> kDeterminers{"the", "a", "an", "this", "that", "these", "those", "another", "each",
                                         "every", "some", "any", "all", "both", "my", "your", "its", "their"};
const std::set<std::string> kPrepositions{"on",   "in",    "into",   "onto",  "from",   "to",     "at",
                                          "above", "below", "under", "over",  "near",   "next",   "beside",
                                          "behind", "between", "of", "off",  "inside", "atop", "alongside",
                                          "adjacent", "across", "toward", "towards", "out", "by", "with",
                                          "underneath", "beneath", "upon", "within", "against", "along",
                                          "around", "opposite", "among", "through"};

std::string lowerOf(const std::string& s) { return toLowerAscii(s); }

// Linguistic word classes of the optional feature groups (closed classes of
// English, not counted on the corpus).
const std::set<std::string> kSourcePreps{"from", "off"};
const std::set<std::string> kGoalPreps{"to", "onto", "into", "toward", "towards"};
const std::set<std::string> kPlacingVerbs{"put",  "place", "drop",     "set",    "move",   "leave", "lay",
                                          "stack", "position", "insert", "release", "shift", "slide", "push",
                                          "transfer", "deposit", "return"};
const std::set<std::string> kFetchVerbs{"bring", "carry", "give", "pass", "hand", "fetch", "deliver"};
const std::set<std::string> kPickVerbs{"pick", "grab", "grasp", "take", "get", "lift", "catch", "remove", "hold", "raise"};
// Nouns and adjectives of direction that head a multi-word indicator ("on the top left corner of").
const std::set<std::string> kDirectionNouns{"left", "right", "top",   "bottom", "front", "back",   "side",
                                            "middle", "center", "centre", "edge", "corner", "end", "rear",
                                            "front", "border", "margin", "surface"};
const std::set<std::string> kDirectionModifiers{"far", "top", "bottom", "left", "right", "upper", "lower",
                                                "very", "front", "back", "lefthand", "righthand", "exact"};
// Adjectives that take "to" ("next to", "close to", "left to").
const std::set<std::string> kRelationalAdjectives{"next", "adjacent", "close", "closest", "near", "nearest",
                                                  "left", "right", "opposite", "parallel", "perpendicular"};
const std::set<std::string> kDegreeAdverbs{"directly", "right", "just", "immediately", "exactly", "slightly",
                                           "straight", "somewhere", "anywhere"};

std::string verbClassOf(const std::string& lemma) {
  if (kPlacingVerbs.count(lemma)) return "place";
  if (kFetchVerbs.count(lemma)) return "fetch";
  if (kPickVerbs.count(lemma)) return "pick";
  return "other";
}

/// Length of the multi-word direction phrase starting at `i` ("in front of",
/// "on the top left corner", "left to", "at the far right corner of"), 0 when none.
int directionPhraseLength(const std::vector<std::string>& w, int i) {
  const int n = static_cast<int>(w.size());
  static const std::set<std::string> kStarters{"on", "at", "in", "to", "from", "onto", "into", "towards", "toward", "by"};
  int j = i;
  if (kStarters.count(w[i])) {
    j = i + 1;
    if (j < n && (w[j] == "the" || w[j] == "a" || w[j] == "its")) ++j;
    int head = -1;
    while (j < n && (kDirectionModifiers.count(w[j]) || kDirectionNouns.count(w[j]))) head = j++;
    if (head < 0 || !kDirectionNouns.count(w[head])) return 0;
  } else if (kRelationalAdjectives.count(w[i])) {
    j = i + 1;
    if (j >= n || w[j] != "to") return 0;
    return 2;
  } else {
    return 0;
  }
  if (j < n && (w[j] == "of" || w[j] == "to")) ++j;
  return j - i >= 2 ? j - i : 0;
}

bool isPunct(const std::string& w) {
  return !w.empty() && std::all_of(w.begin(), w.end(), [](char c) { return std::ispunct(static_cast<unsigned char>(c)); });
}

std::string shapeOf(const std::string& w) {
  std::string shape;
  for (char c : w) {
    char k = std::isupper(static_cast<unsigned char>(c))   ? 'A'
             : std::islower(static_cast<unsigned char>(c)) ? 'a'
             : std::isdigit(static_cast<unsigned char>(c)) ? '0'
                                                            : c;
    if (shape.empty() || shape.back() != k) shape.push_back(k);
  }
  return shape;
}

}  // namespace

struct LanguageModel::Impl {
  WordNetLexicon lexicon;
  std::vector<std::string> actionLemmas;
  std::set<std::string> actionLemmaSet;
  std::vector<std::string> entityFeatureNames;
  std::unordered_map<std::string, unsigned long> entityFeatureIds;
  dlib::sequence_labeler<EntityFeatureExtractor> tagger;
  std::vector<std::string> relationFeatureNames;
  std::unordered_map<std::string, unsigned long> relationFeatureIds;
  dlib::decision_function<RelationKernel> relationScorer;
  IndicatorConventions indicatorConventions;  ///< counted on the training corpus
  DecodingRules rules;
  FeatureGroups features;

  std::string lemmaOf(const std::string& lower) const {
    const WordInfo info = lexicon.lookup(lower);
    if (!info.verbLemma.empty()) return info.verbLemma;
    if (!info.nounLemma.empty()) return info.nounLemma;
    return lower;
  }

  bool isActionWord(const std::string& lower) const {
    return actionLemmaSet.count(lower) > 0 || actionLemmaSet.count(lemmaOf(lower)) > 0;
  }

  /// A sentence's lower-cased words with what the lexicon and the clause
  /// structure say about each (tokenFeatures).
  struct SentenceWords {
    int n = 0;
    std::vector<std::string> w;
    std::vector<WordInfo> info;
    std::vector<std::string> nextPrep;  ///< the next preposition in the clause (up to an action word or stop), "<none>"
    std::vector<bool> laterPhrase;      ///< a preposition after a noun later in the clause
    std::vector<bool> actionAheadOf;    ///< an action word later in the sentence
    std::string word(int i) const { return i < 0 ? "<s>" : i >= n ? "</s>" : w[i]; }
  };

  /// What the tokens before the current one showed (tokenFeatures' running state).
  struct ClauseState {
    int actionsBefore = 0, andsBefore = 0;
    std::string prevAction = "<none>";
    bool pronounSinceAction = false, nounSinceAction = false, prepSinceAction = false;
    bool sourceSinceAction = false, goalSinceAction = false;
    std::vector<int> inDirectionPhrase;  ///< 1 inside, 2 last word of a direction phrase
  };

  bool nounish(const SentenceWords& s, int i) const {
    return s.info[i].noun && !s.info[i].colour && !kPrepositions.count(s.w[i]) && !kPronouns.count(s.w[i]) &&
           !kDeterminers.count(s.w[i]) && !isActionWord(s.w[i]);
  }

  SentenceWords sentenceWords(const std::vector<std::string>& tokens) const {
    SentenceWords s;
    const int n = s.n = static_cast<int>(tokens.size());
    s.w.resize(n);
    s.info.resize(n);
    for (int i = 0; i < n; ++i) {
      s.w[i] = lowerOf(tokens[i]);
      s.info[i] = lexicon.lookup(s.w[i]);
    }
    const auto& w = s.w;
    s.nextPrep.assign(n, "<none>");
    std::string next = "<none>";
    for (int i = n - 1; i >= 0; --i) {
      s.nextPrep[i] = next;
      if (isActionWord(w[i]) || w[i] == "." || w[i] == ";") next = "<none>";
      if (kPrepositions.count(w[i])) next = w[i];
    }
    s.laterPhrase.assign(n, false);
    bool prepSeen = false, phrase = false;
    for (int i = n - 1; i >= 0; --i) {
      s.laterPhrase[i] = phrase;
      if (isActionWord(w[i]) || w[i] == "." || w[i] == ";") prepSeen = phrase = false;
      if (kPrepositions.count(w[i])) prepSeen = true;
      if (nounish(s, i) && prepSeen) phrase = true;
    }
    bool anyActionAhead = false;
    s.actionAheadOf.assign(n, false);
    for (int i = n - 1; i >= 0; --i) {
      s.actionAheadOf[i] = anyActionAhead;
      anyActionAhead |= isActionWord(w[i]);
    }
    return s;
  }

  /// WordNet classes of word i (none outside the sentence), each as `prefix` + class.
  static void wnClasses(const SentenceWords& s, int i, const std::string& prefix, std::vector<std::string>& out) {
    if (i < 0 || i >= s.n) return;
    const WordInfo& k = s.info[i];
    if (k.noun) out.push_back(prefix + "n");
    if (k.verb) out.push_back(prefix + "v");
    if (k.adjective) out.push_back(prefix + "a");
    if (k.colour) out.push_back(prefix + "color");
    if (k.artifact) out.push_back(prefix + "artifact");
    if (k.shape) out.push_back(prefix + "shape");
    if (k.location) out.push_back(prefix + "loc");
    if (kPrepositions.count(s.w[i])) out.push_back(prefix + "prep");
    if (kPronouns.count(s.w[i])) out.push_back(prefix + "pron");
  }

  /// Where word i stands in its clause: the clause context of a preposition or
  /// noun, the first noun after the action, the next preposition, a relative ahead.
  void clauseContextFeatures(const SentenceWords& s, int i, const ClauseState& c, std::vector<std::string>& f) const {
    const auto& w = s.w;
    const bool firstNoun = c.actionsBefore > 0 && !c.nounSinceAction && nounish(s, i);
    if (kPrepositions.count(w[i]) || s.info[i].noun) {
      const std::string ctx = std::string(s.laterPhrase[i] ? "L" : "-") + (s.actionAheadOf[i] ? "A" : "-") +
                              std::to_string(std::min(c.actionsBefore, 2)) + (c.pronounSinceAction ? "p" : "-") +
                              (c.nounSinceAction ? "n" : "-");
      f.push_back("ctx=" + ctx);
      if (kPrepositions.count(w[i])) {
        f.push_back("prep|ctx=" + ctx);
        f.push_back("prep|act|ctx=" + c.prevAction + "|" + ctx);
      } else if (firstNoun) {
        f.push_back("noun1|act|ctx=" + c.prevAction + "|" + ctx);
      }
      f.push_back("w|ctx=" + w[i] + "|" + ctx);
    }
    f.push_back("nextPrep=" + s.nextPrep[i]);
    if (s.nextPrep[i] != "<none>") f.push_back("hasNextPrep");
    if (firstNoun) {
      f.push_back("firstNoun");
      f.push_back("firstNoun|nextPrep=" + s.nextPrep[i]);
      f.push_back("firstNoun|nact=" + std::to_string(std::min(c.actionsBefore, 2)) +
                  (s.nextPrep[i] != "<none>" ? "p" : "-"));
    }
    if (kPrepositions.count(w[i])) {
      f.push_back(std::string("prep|nounSinceAct=") + (c.nounSinceAction ? "1" : "0") +
                  (c.prepSinceAction ? "1" : "0") + std::to_string(std::min(c.actionsBefore, 2)) +
                  (c.pronounSinceAction ? "p" : "-"));
    }
    bool relativeAhead = false;
    for (int k = i + 1; k <= i + 3 && k < s.n; ++k) relativeAhead |= w[k] == "that" || w[k] == "which" || w[k] == "who";
    if (relativeAhead) f.push_back("relAhead3");
  }

  /// The word itself and its neighbours: words, lemma, suffix, shape, WordNet classes, action words.
  void lexicalFeatures(const SentenceWords& s, const std::vector<std::string>& tokens, int i,
                       std::vector<std::string>& f) const {
    const auto& w = s.w;
    f.push_back("bias");
    f.push_back("w=" + w[i]);
    f.push_back("lem=" + lemmaOf(w[i]));
    f.push_back("w-1=" + s.word(i - 1));
    f.push_back("w+1=" + s.word(i + 1));
    f.push_back("w-2=" + s.word(i - 2));
    f.push_back("w+2=" + s.word(i + 2));
    f.push_back("w-1w=" + s.word(i - 1) + "|" + w[i]);
    f.push_back("ww+1=" + w[i] + "|" + s.word(i + 1));
    f.push_back("w+1w+2=" + s.word(i + 1) + "|" + s.word(i + 2));
    f.push_back("w-2w-1=" + s.word(i - 2) + "|" + s.word(i - 1));
    if (w[i].size() > 3) f.push_back("suf3=" + w[i].substr(w[i].size() - 3));
    f.push_back("shape=" + shapeOf(tokens[i]));
    if (isPunct(w[i])) f.push_back("punct");
    wnClasses(s, i, "wn:", f);
    wnClasses(s, i - 1, "wn-1:", f);
    wnClasses(s, i + 1, "wn+1:", f);
    wnClasses(s, i + 2, "wn+2:", f);
    if (isActionWord(w[i])) f.push_back("actlex");
    if (i > 0 && isActionWord(w[i - 1])) f.push_back("actlex-1");
  }

  /// What the clause showed before word i: actions, "and"s, pronouns, nouns, prepositions; what lies ahead.
  void clauseStateFeatures(const SentenceWords& s, int i, const ClauseState& c, std::vector<std::string>& f) const {
    const auto& w = s.w;
    const int n = s.n;
    f.push_back("nact=" + std::to_string(std::min(c.actionsBefore, 2)));
    f.push_back("prevact=" + c.prevAction);
    f.push_back("nand=" + std::to_string(std::min(c.andsBefore, 2)));
    if (c.pronounSinceAction) f.push_back("pronSinceAct");
    if (c.nounSinceAction) f.push_back("nounSinceAct");
    if (c.prepSinceAction) f.push_back("prepSinceAct");
    f.push_back("nact|pron=" + std::to_string(std::min(c.actionsBefore, 2)) + (c.pronounSinceAction ? "p" : "-") +
                (c.prepSinceAction ? "x" : "-"));
    bool prepAhead = false;
    for (int k = i + 1; k <= i + 3 && k < n; ++k) prepAhead |= kPrepositions.count(w[k]) > 0;
    if (prepAhead) f.push_back("prepAhead3");
    bool actionAhead = false;
    for (int k = i + 1; k < n; ++k) actionAhead |= isActionWord(w[k]);
    if (actionAhead) f.push_back("actionAhead");
    f.push_back("pos=" + std::string(i == 0 ? "first" : i == n - 1 ? "last" : "mid"));
  }

  /// Location words (prepositions, relational adjectives, direction nouns): their
  /// source/goal role, direction phrases ("in front of") and a missing landmark.
  void locationFeatures(const SentenceWords& s, int i, ClauseState& c, std::vector<std::string>& f) const {
    const auto& w = s.w;
    const int n = s.n;
    const bool prepLike =
        kPrepositions.count(w[i]) > 0 || kRelationalAdjectives.count(w[i]) > 0 || kDirectionNouns.count(w[i]) > 0;
    if (features.sourceGoalRole && prepLike) {
      const std::string vclass = c.actionsBefore > 0 ? verbClassOf(c.prevAction) : "none";
      std::string role = "other";
      if (kSourcePreps.count(w[i]) || (w[i] == "out" && s.word(i + 1) == "of")) role = "source";
      else if (kGoalPreps.count(w[i])) role = "goal";
      else if (vclass == "place" && kPrepositions.count(w[i])) role = "placeLoc";
      const std::string seen = std::string(c.sourceSinceAction ? "S" : "-") + (c.goalSinceAction ? "G" : "-");
      f.push_back("role=" + role);
      f.push_back("role|v=" + role + "|" + vclass);
      f.push_back("role|seen=" + role + "|" + seen);
      f.push_back("role|v|seen=" + role + "|" + vclass + "|" + seen);
    }
    if (features.directionPhrases) {
      if (const int len = directionPhraseLength(w, i)) {
        f.push_back("dp=B");
        f.push_back("dp|len=" + std::to_string(std::min(len, 5)));
        f.push_back(std::string("dp|end=") + (w[i + len - 1] == "of" || w[i + len - 1] == "to" ? "prep" : "noun"));
        for (int k = i + 1; k < i + len; ++k) c.inDirectionPhrase[k] = i + len - 1 == k ? 2 : 1;
      }
      if (c.inDirectionPhrase[i] == 1) f.push_back("dp=I");
      if (c.inDirectionPhrase[i] == 2) f.push_back("dp=L");
    }
    if (features.noLandmark && prepLike) {
      int k = i + 1;
      while (k < n && kDirectionModifiers.count(w[k])) ++k;
      const bool landmarkless = k >= n || isPunct(w[k]) || w[k] == "and" || isActionWord(w[k]);
      if (landmarkless) {
        f.push_back("noLm");
        f.push_back("noLm|w=" + w[i]);
      }
      if (i > 0 && kDegreeAdverbs.count(w[i - 1])) f.push_back("advBefore");
    }
  }

  /// The state after word i: an action word starts a new clause.
  void advance(const SentenceWords& s, int i, ClauseState& c) const {
    const auto& w = s.w;
    if (isActionWord(w[i])) {
      ++c.actionsBefore;
      c.prevAction = lemmaOf(w[i]);
      c.pronounSinceAction = c.nounSinceAction = c.prepSinceAction = c.sourceSinceAction = c.goalSinceAction = false;
    } else {
      c.sourceSinceAction |= kSourcePreps.count(w[i]) > 0 || (w[i] == "out" && s.word(i + 1) == "of");
      c.goalSinceAction |= kGoalPreps.count(w[i]) > 0;
      c.pronounSinceAction |= kPronouns.count(w[i]) > 0;
      c.nounSinceAction |= nounish(s, i);
      c.prepSinceAction |= kPrepositions.count(w[i]) > 0;
    }
    if (w[i] == "and" || w[i] == ",") ++c.andsBefore;
  }

  /// Feature strings of every token (label-independent).
  std::vector<std::vector<std::string>> tokenFeatures(const std::vector<std::string>& tokens) const {
    const SentenceWords s = sentenceWords(tokens);
    std::vector<std::vector<std::string>> feats(s.n);
    ClauseState c;
    c.inDirectionPhrase.assign(s.n, 0);
    for (int i = 0; i < s.n; ++i) {
      auto& f = feats[i];
      clauseContextFeatures(s, i, c, f);
      lexicalFeatures(s, tokens, i, f);
      clauseStateFeatures(s, i, c, f);
      locationFeatures(s, i, c, f);
      advance(s, i, c);
    }
    return feats;
  }

  EntityFeatureExtractor::sequence_type entitySequence(const std::vector<std::string>& tokens) const {
    EntityFeatureExtractor::sequence_type seq;
    for (const auto& names : tokenFeatures(tokens)) {
      std::vector<unsigned long> ids;
      for (const auto& name : names) {
        auto it = entityFeatureIds.find(name);
        if (it != entityFeatureIds.end()) ids.push_back(it->second);
      }
      std::sort(ids.begin(), ids.end());
      ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
      seq.push_back(std::move(ids));
    }
    return seq;
  }

  /// Sparse features of a candidate relation head -> tail (both entity indices).
  std::vector<std::string> relationFeatureNamesOf(const std::vector<std::string>& tokens,
                                                  const std::vector<EntitySpan>& entities, int head,
                                                  int tail) const {
    const EntitySpan& h = entities[head];
    const EntitySpan& t = entities[tail];
    const bool headFirst = h.start < t.start;
    const int lo = headFirst ? h.end : t.end;
    const int hi = headFirst ? t.start : h.start;
    const int distance = std::max(0, hi - lo);
    int sameTypeBetween = 0, actionsBetween = 0, indicatorsBetween = 0;
    for (size_t k = 0; k < entities.size(); ++k) {
      const auto& e = entities[k];
      if (static_cast<int>(k) == head || static_cast<int>(k) == tail) continue;
      if (e.start >= lo && e.end <= hi) {
        if (e.type == h.type) ++sameTypeBetween;
        if (e.type == "Action") ++actionsBetween;
        if (e.type == t.type) ++indicatorsBetween;
      }
    }
    std::string headText, tailText;
    for (int k = h.start; k < h.end; ++k) headText += (k > h.start ? " " : "") + lowerOf(tokens[k]);
    for (int k = t.start; k < t.end; ++k) tailText += (k > t.start ? " " : "") + lowerOf(tokens[k]);
    const std::string tp = h.type + ">" + t.type + ":";
    std::vector<std::string> f{tp + "bias",
                               tp + "dir=" + (headFirst ? "ht" : "th"),
                               tp + "dist=" + std::to_string(std::min(distance, 8)),
                               tp + "dir|same=" + (headFirst ? "ht" : "th") + std::to_string(std::min(sameTypeBetween, 3)),
                               tp + "same=" + std::to_string(std::min(sameTypeBetween, 3)),
                               tp + "act=" + std::to_string(std::min(actionsBetween, 2)),
                               tp + "ind=" + std::to_string(std::min(indicatorsBetween, 2)),
                               tp + "h=" + headText,
                               tp + "t=" + tailText};
    bool pronounBetween = false;
    for (int k = lo; k < hi; ++k) {
      const std::string w = lowerOf(tokens[k]);
      f.push_back(tp + "bw=" + w);
      pronounBetween |= kPronouns.count(w) > 0;
    }
    if (pronounBetween) f.push_back(tp + "pronBetween");
    if (headFirst && h.end == t.start) f.push_back(tp + "adjacent");
    return f;
  }

  SparseVector relationVector(const std::vector<std::string>& names) const {
    SparseVector v;
    for (const auto& name : names) {
      auto it = relationFeatureIds.find(name);
      if (it != relationFeatureIds.end()) v.push_back({it->second, 1.0});
    }
    std::sort(v.begin(), v.end());
    v.erase(std::unique(v.begin(), v.end()), v.end());
    return v;
  }

  bool isNounish(const std::string& lower) const {
    const WordInfo k = lexicon.lookup(lower);
    static const std::set<std::string> kPersonalPronouns{"i", "me", "you", "us", "him", "her", "we"};
    return k.noun && !k.colour && !kPrepositions.count(lower) && !kPronouns.count(lower) &&
           !kPersonalPronouns.count(lower) && !kDeterminers.count(lower) && !isActionWord(lower);
  }

  /// Corpus regularities the tagger does not always respect (train.json counts):
  /// an indicator with another action after it describes where an object *is*
  /// (SpatialIndicator: 113 of 114); otherwise the type the training corpus gives
  /// to indicators of that action, direction and place in the clause, where it is
  /// consistent (IndicatorConventions: every indicator of "pick" is spatial, the
  /// first of "put / place" a goal, "take / bring ... on" spatial, "... to" a goal).
  static bool isIndicatorType(const std::string& type) { return type == "GoalIndicator" || type == "SpatialIndicator"; }

  /// Whether a "to / onto / into" indicator follows entity `i` before the next action.
  static bool directionalGoalFollows(const std::vector<std::string>& lower, const std::vector<EntitySpan>& entities,
                                     size_t i) {
    static const std::set<std::string> kDirectional{"to", "onto", "into"};
    for (size_t j = i + 1; j < entities.size() && entities[j].type != "Action"; ++j)
      if (isIndicatorType(entities[j].type) && kDirectional.count(lower[entities[j].start])) return true;
    return false;
  }

  /// Whether the next action after entity `i` takes a pronoun ("... and place *it* on"): the
  /// object of the clause before is then carried on, so that clause was only a pick.
  static bool nextActionTakesAPronoun(const std::vector<std::string>& lower, const std::vector<EntitySpan>& entities,
                                      size_t i) {
    for (size_t j = i + 1; j < entities.size(); ++j) {
      if (entities[j].type != "Action") continue;
      int k = entities[j].end;
      if (k < static_cast<int>(lower.size()) && (lower[k] == "up" || lower[k] == "down")) ++k;
      return k < static_cast<int>(lower.size()) && kPronouns.count(lower[k]) > 0;
    }
    return false;
  }

  void relabelIndicators(const std::vector<std::string>& tokens, std::vector<EntitySpan>& entities) const {
    const std::vector<std::string> lower = toLowerAscii(tokens);
    std::sort(entities.begin(), entities.end(), [](const EntitySpan& a, const EntitySpan& b) { return a.start < b.start; });
    std::string verb;
    bool firstInClause = true, firstPlaceInClause = true;
    for (size_t i = 0; i < entities.size(); ++i) {
      auto& e = entities[i];
      if (e.type == "Action") {
        verb = lemmaOf(lowerOf(tokens[e.start]));
        firstInClause = firstPlaceInClause = true;
        continue;
      }
      if (!isIndicatorType(e.type)) continue;
      bool actionAfter = false;
      for (size_t j = i + 1; j < entities.size(); ++j) actionAfter |= entities[j].type == "Action";
      const bool relative = IndicatorConventions::inRelativeClause(lower, e.start);
      const bool source = PhraseRules::isSourceAt(lower, e.start);
      if (rules.relativeClauseIsSpatial && relative) {
        e.type = "SpatialIndicator";
        continue;  // locates an object: the clause's first goal may still follow
      }
      if (rules.sourceIsSpatial && source) {
        e.type = "SpatialIndicator";
        continue;  // where the object comes from: the clause's goal may still follow
      }
      if (actionAfter && rules.actionAfterIsSpatial) {
        e.type = "SpatialIndicator";
      } else if (!actionAfter && rules.conventionTypes) {
        if (auto type = indicatorConventions.indicatorType(verb, lowerOf(tokens[e.start]), firstInClause)) e.type = *type;
      }
      // A placing verb's first place is its goal ("move the block in front of the box"), unless a
      // "to / into" goal follows: then it says where the object is ("move X on top of Y to Z").
      if (rules.placingFirstIsGoal && (!actionAfter || !nextActionTakesAPronoun(lower, entities, i)) && !relative &&
          !source && firstPlaceInClause && PhraseRules::isPlacingVerb(verb) && verb != "release" && verb != "leave")
        e.type = directionalGoalFollows(lower, entities, i) ? "SpatialIndicator" : "GoalIndicator";
      if (!relative && !source) firstPlaceInClause = false;
      firstInClause = false;
    }
    // One goal per clause (train: only 1 clause has two goals): of several goals the
    // directional one ("to / onto / into the ...") stays, else the first.
    for (size_t i = 0; rules.oneGoalPerClause && i < entities.size();) {
      size_t end = i + 1;
      while (end < entities.size() && entities[end].type != "Action") ++end;
      std::vector<size_t> goals;
      for (size_t k = i; k < end; ++k)
        if (entities[k].type == "GoalIndicator") goals.push_back(k);
      if (goals.size() > 1) {
        size_t keep = goals.front();
        for (size_t k : goals) {
          const std::string first = lowerOf(tokens[entities[k].start]);
          if (first == "to" || first == "onto" || first == "into") {
            keep = k;
            break;
          }
        }
        for (size_t k : goals)
          if (k != keep) entities[k].type = "SpatialIndicator";
      }
      i = end;
    }
  }

  /// The corpus annotates a Trajector exactly when a SpatialIndicator locates it
  /// (train: 344 of 352). Decoding enforces that: an indicator without a
  /// trajector in its clause gets the head noun of the clause's first noun
  /// phrase; a trajector with no indicator after it in its clause is dropped.
  void enforceTrajectorConsistency(const std::vector<std::string>& tokens, std::vector<EntitySpan>& entities) const {
    const int n = static_cast<int>(tokens.size());
    const std::vector<std::string> lower = toLowerAscii(tokens);
    std::vector<int> owner(n, -1);  // token -> entity index
    for (size_t e = 0; e < entities.size(); ++e)
      for (int k = entities[e].start; k < entities[e].end; ++k) owner[k] = static_cast<int>(e);
    auto typeAt = [&](int k) { return owner[k] < 0 ? std::string() : entities[owner[k]].type; };
    auto clauseStart = [&](int pos) {
      int k = pos - 1;
      while (k >= 0 && typeAt(k) != "Action" && lower[k] != "." && lower[k] != ";") --k;
      return k + 1;
    };
    std::vector<EntitySpan> added;
    for (const auto& e : entities) {
      if (e.type != "SpatialIndicator" || !rules.addTrajectors) continue;
      const int clause = clauseStart(e.start);
      if (clause == 0 || typeAt(clause - 1) != "Action") continue;  // no verb before it: nothing is being moved
      // After a goal the phrase locates the goal's landmark ("on the table in the
      // kitchen": train 22 of 22), so its trajector is sought after the goal.
      // A source locates the moved object wherever it stands ("move X to Y from Z").
      const bool source = rules.sourceIsSpatial && PhraseRules::isSourceAt(lower, e.start);
      int from = clause, to = e.start;
      for (int k = clause; k < e.start; ++k)
        if (typeAt(k) == "GoalIndicator") {
          if (source) {
            to = k;
            break;
          }
          from = k + 1;
        }
      bool hasTrajector = false;
      for (int k = from; k < to; ++k) hasTrajector |= typeAt(k) == "Trajector";
      if (hasTrajector) continue;
      int head = -1;
      for (int k = from; k < to; ++k) {
        if (typeAt(k) == "Color") continue;  // "the single red block": the head is after the colour
        if (owner[k] >= 0) {
          if (head >= 0) break;
          continue;
        }
        if (isNounish(lower[k])) {
          head = k;
        } else if (head >= 0) {
          break;
        }
      }
      if (head >= 0 && owner[head] < 0) {
        added.push_back({head, head + 1, "Trajector"});
        owner[head] = -2;
      }
    }
    std::vector<EntitySpan> kept;
    for (const auto& e : entities) {
      if (e.type == "Trajector" && rules.dropUnlocatedTrajectors) {
        bool located = false, goalBetween = false;
        bool afterGoal = false;  // the trajector is a goal's landmark
        for (int k = clauseStart(e.start); k < e.start; ++k) afterGoal |= typeAt(k) == "GoalIndicator";
        for (int k = e.end; k < n && typeAt(k) != "Action" && lower[k] != "." && lower[k] != ";"; ++k) {
          goalBetween |= typeAt(k) == "GoalIndicator";
          if (typeAt(k) != "SpatialIndicator") continue;
          const bool source = rules.sourceIsSpatial && PhraseRules::isSourceAt(lower, entities[owner[k]].start);
          // A source locates the moved object, not a goal's landmark; a phrase after a goal
          // locates the goal's landmark, not the object before it.
          if (source && afterGoal) continue;
          if (rules.goalLandmarkLocatives && goalBetween && !source) continue;
          located = true;
        }
        if (!located) continue;
      }
      kept.push_back(e);
    }
    kept.insert(kept.end(), added.begin(), added.end());
    std::sort(kept.begin(), kept.end(), [](const EntitySpan& a, const EntitySpan& b) { return a.start < b.start; });
    entities = kept;
  }

  static std::string relationTypeFor(const std::string& headType, const std::string& tailType) {
    if (headType == "Trajector" && tailType == "SpatialIndicator") return "Spatial";
    if (headType == "Action" && tailType == "GoalIndicator") return "Transition";
    return {};
  }

  std::vector<RelationLink> predictRelations(const std::vector<std::string>& tokens,
                                             const std::vector<EntitySpan>& entities) const {
    std::vector<RelationLink> out;
    for (size_t tail = 0; tail < entities.size(); ++tail) {
      double best = 0.0;
      int bestHead = -1;
      std::string bestType;
      for (size_t head = 0; head < entities.size(); ++head) {
        const std::string type = relationTypeFor(entities[head].type, entities[tail].type);
        if (type.empty()) continue;
        const double score = relationScorer(relationVector(
            relationFeatureNamesOf(tokens, entities, static_cast<int>(head), static_cast<int>(tail))));
        if (score > best) {
          best = score;
          bestHead = static_cast<int>(head);
          bestType = type;
        }
      }
      if (bestHead >= 0) out.push_back({bestHead, static_cast<int>(tail), bestType});
    }
    return out;
  }
};

LanguageModel::LanguageModel() : impl_(std::make_unique<Impl>()) {}
LanguageModel::~LanguageModel() = default;
LanguageModel::LanguageModel(LanguageModel&&) noexcept = default;
LanguageModel& LanguageModel::operator=(LanguageModel&&) noexcept = default;

const std::vector<std::string>& LanguageModel::actionLemmas() const { return impl_->actionLemmas; }
const DecodingRules& LanguageModel::decodingRules() const { return impl_->rules; }
void LanguageModel::setDecodingRules(const DecodingRules& rules) { impl_->rules = rules; }

const std::vector<std::pair<std::string, bool DecodingRules::*>>& DecodingRules::all() {
  static const std::vector<std::pair<std::string, bool DecodingRules::*>> kAll{
      {"span_lengths", &DecodingRules::spanLengths},
      {"orders_only", &DecodingRules::ordersOnly},
      {"rare_start_words", &DecodingRules::rareStartWords},
      {"rare_start_pairs", &DecodingRules::rareStartPairs},
      {"action_after_is_spatial", &DecodingRules::actionAfterIsSpatial},
      {"relative_clause_is_spatial", &DecodingRules::relativeClauseIsSpatial},
      {"convention_types", &DecodingRules::conventionTypes},
      {"one_goal_per_clause", &DecodingRules::oneGoalPerClause},
      {"add_trajectors", &DecodingRules::addTrajectors},
      {"drop_unlocated_trajectors", &DecodingRules::dropUnlocatedTrajectors},
      {"source_is_spatial", &DecodingRules::sourceIsSpatial},
      {"placing_first_is_goal", &DecodingRules::placingFirstIsGoal},
      {"direction_spans", &DecodingRules::directionSpans},
      {"placing_clause_goal", &DecodingRules::placingClauseGoal},
      {"of_room_is_spatial", &DecodingRules::ofRoomIsSpatial},
      {"goal_landmark_locatives", &DecodingRules::goalLandmarkLocatives},
      {"side_to_spans", &DecodingRules::sideToSpans}};
  return kAll;
}

const std::vector<std::pair<std::string, bool FeatureGroups::*>>& FeatureGroups::all() {
  static const std::vector<std::pair<std::string, bool FeatureGroups::*>> kAll{
      {"source_goal_role", &FeatureGroups::sourceGoalRole},
      {"direction_phrases", &FeatureGroups::directionPhrases},
      {"no_landmark", &FeatureGroups::noLandmark}};
  return kAll;
}

namespace {
template <typename Switches>
nlohmann::json switchesToJson(const Switches& s) {
  nlohmann::json j = nlohmann::json::object();
  for (const auto& [name, member] : Switches::all()) j[name] = s.*member;
  return j;
}
template <typename Switches>
Switches switchesFromJson(const nlohmann::json& j, const std::string& what) {
  core::require(j.is_object(), what + ": expected an object of switches");
  Switches s;
  for (const auto& [name, member] : Switches::all()) s.*member = j.contains(name) && j.at(name).template get<bool>();
  return s;
}
}  // namespace

LanguageModel LanguageModel::train(const std::vector<AnnotatedSentence>& corpus,
                                   const LanguageModel::Options& options) {
  core::require(!corpus.empty(), "language training corpus is empty; pass datasets/language/train.json");
  LanguageModel model;
  Impl& m = *model.impl_;
  m.rules = options.rules;
  m.features = options.features;
  // The indicator conventions are counted on the real sentences only: they describe
  // the corpus' annotation, which the synthetic commands only imitate.
  m.indicatorConventions =
      IndicatorConventions::learn(corpus, [&m](const std::string& word) { return m.lemmaOf(word); });
  if (options.syntheticRatio > 0.0) {
    std::vector<AnnotatedSentence> mixed = corpus;
    const auto count = static_cast<size_t>(options.syntheticRatio * static_cast<double>(corpus.size()) + 0.5);
    const auto synthetic = SyntheticCommandGrammar().generate(count, options.syntheticSeed);
    mixed.insert(mixed.end(), synthetic.begin(), synthetic.end());
    LanguageModel::Options realOnly = options;
    realOnly.syntheticRatio = 0.0;
    LanguageModel mixedModel = train(mixed, realOnly);
    mixedModel.impl_->indicatorConventions = m.indicatorConventions;
    return mixedModel;
  }

  // Action lexicon from the annotation.
  for (const auto& s : corpus)
    for (const auto& e : s.entities)
      if (e.type == "Action" && e.end - e.start == 1) m.actionLemmaSet.insert(m.lemmaOf(lowerOf(s.tokens[e.start])));
  m.actionLemmas.assign(m.actionLemmaSet.begin(), m.actionLemmaSet.end());

  // Entity feature dictionary (sorted names, so ids do not depend on hashing).
  std::map<std::string, int> counts;
  for (const auto& s : corpus)
    for (const auto& tok : m.tokenFeatures(s.tokens))
      for (const auto& f : tok) ++counts[f];
  for (const auto& [name, count] : counts)
    if (count >= options.minFeatureCount) {
      m.entityFeatureIds[name] = m.entityFeatureNames.size();
      m.entityFeatureNames.push_back(name);
    }

  // BIO labels; overlapping gold spans (2 in train) keep the first-starting one.
  std::vector<EntityFeatureExtractor::sequence_type> samples;
  std::vector<std::vector<unsigned long>> labels;
  for (const auto& s : corpus) {
    if (s.tokens.empty()) continue;
    std::vector<unsigned long> y(s.tokens.size(), 0);
    auto sorted = s.entities;
    std::sort(sorted.begin(), sorted.end(), [](const auto& a, const auto& b) { return a.start < b.start; });
    for (const auto& e : sorted) {
      const auto t = std::find(kEntityTypes.begin(), kEntityTypes.end(), e.type) - kEntityTypes.begin();
      if (t >= static_cast<long>(kEntityTypes.size())) continue;
      bool free = true;
      for (int k = e.start; k < e.end; ++k) free &= y[k] == 0;
      if (!free) continue;
      y[e.start] = 1 + 2 * t;
      for (int k = e.start + 1; k < e.end; ++k) y[k] = 2 + 2 * t;
    }
    samples.push_back(m.entitySequence(s.tokens));
    labels.push_back(std::move(y));
  }
  EntityFeatureExtractor fe;
  fe.numEmission = m.entityFeatureNames.size();
  dlib::structural_sequence_labeling_trainer<EntityFeatureExtractor> trainer(fe);
  trainer.set_c(options.entityC);
  trainer.set_epsilon(options.entityEpsilon);
  trainer.set_num_threads(static_cast<unsigned long>(std::max(1, options.threads)));
  m.tagger = trainer.train(samples, labels);

  // Relations: every type-compatible pair of gold entities is a sample.
  std::vector<std::vector<std::string>> relNames;
  std::vector<double> relLabels;
  for (const auto& s : corpus) {
    std::set<std::pair<int, int>> gold;
    for (const auto& r : s.relations) gold.insert({r.head, r.tail});
    for (size_t h = 0; h < s.entities.size(); ++h)
      for (size_t t = 0; t < s.entities.size(); ++t) {
        if (Impl::relationTypeFor(s.entities[h].type, s.entities[t].type).empty()) continue;
        relNames.push_back(m.relationFeatureNamesOf(s.tokens, s.entities, static_cast<int>(h), static_cast<int>(t)));
        relLabels.push_back(gold.count({static_cast<int>(h), static_cast<int>(t)}) ? +1.0 : -1.0);
      }
  }
  std::set<std::string> relVocabulary;
  for (const auto& v : relNames) relVocabulary.insert(v.begin(), v.end());
  for (const auto& name : relVocabulary) {
    m.relationFeatureIds[name] = m.relationFeatureNames.size();
    m.relationFeatureNames.push_back(name);
  }
  std::vector<SparseVector> relSamples;
  for (const auto& v : relNames) relSamples.push_back(m.relationVector(v));
  core::require(std::count(relLabels.begin(), relLabels.end(), 1.0) > 0 &&
                    std::count(relLabels.begin(), relLabels.end(), -1.0) > 0,
                "language training corpus needs both related and unrelated entity pairs");
  dlib::svm_c_linear_trainer<RelationKernel> relTrainer;
  relTrainer.set_c(options.relationC);
  m.relationScorer = relTrainer.train(relSamples, relLabels);
  return model;
}

void LanguageModel::save(const std::string& path) const {
  std::ostringstream out(std::ios::binary);
  const Impl& m = *impl_;
  dlib::serialize(std::string("srp-language-model"), out);
  dlib::serialize(kModelFormatVersion, out);
  dlib::serialize(m.actionLemmas, out);
  dlib::serialize(m.entityFeatureNames, out);
  dlib::serialize(m.tagger, out);
  dlib::serialize(m.relationFeatureNames, out);
  dlib::serialize(m.relationScorer, out);
  dlib::serialize(m.indicatorConventions.toJson().dump(), out);
  dlib::serialize(nlohmann::json{{"rules", switchesToJson(m.rules)}, {"features", switchesToJson(m.features)}}.dump(),
                  out);
  core::writeFileAtomically(path, out.str());  // a model is replaced whole or not at all
}

LanguageModel LanguageModel::load(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in)
    throw core::FileError(path, "language model not found; train it with `srp train-language` (see libs/language/README.md)");
  LanguageModel model;
  Impl& m = *model.impl_;
  try {
    std::string magic;
    int version = 0;
    dlib::deserialize(magic, in);
    if (magic != "srp-language-model") throw core::FileError(path, "is not an srp language model");
    dlib::deserialize(version, in);
    if (version != kModelFormatVersion)
      throw core::FileError(path, "has model format version " + std::to_string(version) + ", this build reads " +
                                      std::to_string(kModelFormatVersion) + "; retrain with `srp train-language`");
    dlib::deserialize(m.actionLemmas, in);
    dlib::deserialize(m.entityFeatureNames, in);
    dlib::deserialize(m.tagger, in);
    dlib::deserialize(m.relationFeatureNames, in);
    dlib::deserialize(m.relationScorer, in);
    std::string conventions;
    dlib::deserialize(conventions, in);
    m.indicatorConventions = IndicatorConventions::fromJson(nlohmann::json::parse(conventions));
    std::string switches;
    dlib::deserialize(switches, in);
    const auto j = nlohmann::json::parse(switches);
    m.rules = switchesFromJson<DecodingRules>(core::requireField(j, "rules", "model switches"), "decoding rules");
    m.features = switchesFromJson<FeatureGroups>(core::requireField(j, "features", "model switches"), "feature groups");
  } catch (const dlib::serialization_error& e) {
    throw core::FileError(path, std::string("is corrupt (") + e.what() + "); retrain with `srp train-language`");
  } catch (const nlohmann::json::exception& e) {
    throw core::FileError(path, std::string("is corrupt (") + e.what() + "); retrain with `srp train-language`");
  } catch (const core::InvalidInputError& e) {
    throw core::FileError(path, std::string("is corrupt (") + e.what() + "); retrain with `srp train-language`");
  }
  m.actionLemmaSet.insert(m.actionLemmas.begin(), m.actionLemmas.end());
  for (size_t i = 0; i < m.entityFeatureNames.size(); ++i) m.entityFeatureIds[m.entityFeatureNames[i]] = i;
  for (size_t i = 0; i < m.relationFeatureNames.size(); ++i) m.relationFeatureIds[m.relationFeatureNames[i]] = i;
  return model;
}

AnnotatedSentence LanguageModel::annotate(const std::vector<std::string>& tokens) const {
  AnnotatedSentence out;
  out.tokens = tokens;
  if (tokens.empty()) return out;
  const std::vector<unsigned long> y = impl_->tagger(impl_->entitySequence(tokens));
  for (size_t i = 0; i < y.size();) {
    if (y[i] == 0) {
      ++i;
      continue;
    }
    const unsigned long type = typeOfLabel(y[i]);
    size_t j = i + 1;
    while (j < y.size() && isInside(y[j]) && typeOfLabel(y[j]) == type) ++j;
    out.entities.push_back({static_cast<int>(i), static_cast<int>(j), kEntityTypes[type]});
    i = j;
  }
  const DecodingRules& rules = impl_->rules;
  if (rules.spanLengths) impl_->indicatorConventions.applySpanLengths(tokens, out.entities);
  if (rules.ordersOnly) IndicatorConventions::dropIndicatorsOutsideOrders(tokens, out.entities);
  if (rules.rareStartWords || rules.rareStartPairs)
    impl_->indicatorConventions.dropRarelyAnnotatedStarts(tokens, out.entities, rules.rareStartWords,
                                                          rules.rareStartPairs);
  const std::vector<std::string> lower = toLowerAscii(tokens);
  if (rules.directionSpans) PhraseRules::applyDirectionSpans(lower, out.entities, rules.sideToSpans);
  if (rules.sourceIsSpatial) PhraseRules::applySourceSpans(lower, out.entities);
  impl_->relabelIndicators(tokens, out.entities);
  if (rules.placingClauseGoal)
    PhraseRules::addPlacingClauseGoals(
        lower, out.entities, [this](const std::string& w) { return impl_->lemmaOf(w); }, rules.sideToSpans);
  if (rules.ofRoomIsSpatial)
    PhraseRules::addRoomOfIndicators(
        lower, out.entities,
        [this](const std::string& w) {  // a noun, or a word WordNet does not know ("nightstand")
          const WordInfo info = impl_->lexicon.lookup(w);
          const bool unknown = !info.noun && !info.verb && !info.adjective && !info.adverb;
          return (info.noun || unknown) && !isPunct(w) && !kPrepositions.count(w) && !kPronouns.count(w) &&
                 !kDeterminers.count(w) && !impl_->isActionWord(w);
        },
        [this](const std::string& w) { return impl_->lexicon.lookup(w).room; });
  impl_->enforceTrajectorConsistency(tokens, out.entities);
  out.relations = impl_->predictRelations(tokens, out.entities);
  return out;
}

std::string defaultModelPath() { return core::DataPaths::file("datasets/language/model/language_model.dat").string(); }

std::vector<AnnotatedSentence> readSpertCorpus(const std::string& path) {
  const nlohmann::json j = core::readJsonFile(path);
  if (!j.is_array()) throw core::FileError(path, "is not a SpERT corpus (expected a JSON array of sentences)");
  std::vector<AnnotatedSentence> out;
  out.reserve(j.size());
  for (size_t i = 0; i < j.size(); ++i) {
    try {
      out.push_back(annotatedSentenceFromJson(j[i]));
    } catch (const core::InvalidInputError& e) {
      throw core::FileError(path, "sentence " + std::to_string(i) + ": " + e.what());
    }
  }
  return out;
}

}  // namespace srp::language
