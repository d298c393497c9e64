#include "srp/language/PhraseRules.h"

#include <algorithm>
#include <cctype>
#include <set>

namespace srp::language {

namespace {

const std::set<std::string> kStarters{"on", "at", "in", "to", "onto", "into", "toward", "towards", "from", "by"};
const std::set<std::string> kArticles{"the", "a", "an", "its"};
const std::set<std::string> kDirections{"left", "right", "top", "bottom", "front", "back", "middle", "center", "centre", "rear"};
const std::set<std::string> kRegions{"corner", "edge", "side", "end", "border", "margin", "surface"};
const std::set<std::string> kModifiers{"far", "upper", "lower", "exact", "very", "lefthand", "righthand"};
// Directions that make a phrase without a landmark ("in the middle", "on top", "in front");
// a side after "on / at / in" is itself the place ("on the left": train annotates "on").
const std::set<std::string> kPlaceDirections{"middle", "top", "front"};
const std::set<std::string> kRelationalBeforeTo{"next",    "adjacent", "close",    "closest",
                                                "near",    "nearest",  "opposite", "parallel", "perpendicular"};
const std::set<std::string> kSides{"left", "right"};  // "left of", and with sideTo "left to"
const std::set<std::string> kClauseWords{"and", "then", "or", "please"};
const std::set<std::string> kBarePrepositions{"above", "below", "under", "underneath", "beneath", "behind",
                                              "inside", "over", "beside", "atop", "outside"};
const std::set<std::string> kPlacingVerbs{"put",   "place",    "drop",    "set",     "move",    "leave",
                                          "lay",   "stack",    "position", "insert", "release", "shift",
                                          "slide", "transfer", "deposit", "return",  "push"};
const std::set<std::string> kRelativeWords{"that", "which", "who"};
// A measured offset ("one square to the left") is a move by a distance, not a place.
const std::set<std::string> kCountWords{"one", "two", "three", "four", "five", "1", "2", "3", "4", "5"};
const std::set<std::string> kGridUnits{"square", "squares", "space", "spaces", "step", "steps", "cell", "cells",
                                       "cm", "centimetre", "centimetres", "centimeter", "centimeters", "inch", "inches"};
// Prepositions that can open a placing verb's goal ("place X from Y *onto* Z").
const std::set<std::string> kGoalPrepositions{"on",    "onto",  "in",     "into",   "to",    "at",   "inside",
                                              "under", "above", "below",  "over",   "beside", "behind", "near",
                                              "between", "underneath", "beneath", "atop", "upon"};
const std::set<std::string> kDeterminers{"the", "a", "an", "my", "your", "his", "her", "our", "their", "this", "that"};

bool isPunct(const std::string& w) {
  return !w.empty() && std::all_of(w.begin(), w.end(), [](char c) { return std::ispunct(static_cast<unsigned char>(c)); });
}
bool isIndicator(const std::string& type) { return type == "SpatialIndicator" || type == "GoalIndicator"; }
bool endsSentence(const std::string& w) { return w == "." || w == ";" || w == "!" || w == "?"; }

/// Entity index owning each token (-1: none).
std::vector<int> owners(int n, const std::vector<EntitySpan>& entities) {
  std::vector<int> owner(n, -1);
  for (size_t e = 0; e < entities.size(); ++e)
    for (int k = std::max(0, entities[e].start); k < entities[e].end && k < n; ++k) owner[k] = static_cast<int>(e);
  return owner;
}

void sortByStart(std::vector<EntitySpan>& entities) {
  std::stable_sort(entities.begin(), entities.end(), [](const EntitySpan& a, const EntitySpan& b) { return a.start < b.start; });
}

}  // namespace

bool PhraseRules::landmarklessAt(const std::vector<std::string>& lower, int k) {
  return k >= static_cast<int>(lower.size()) || isPunct(lower[k]) || kClauseWords.count(lower[k]) > 0;
}

int PhraseRules::directionSpanLength(const std::vector<std::string>& w, int i, bool sideTo) {
  const int n = static_cast<int>(w.size());
  if (i < 0 || i >= n) return 0;
  if (i + 1 < n && ((w[i + 1] == "to" && (kRelationalBeforeTo.count(w[i]) || (sideTo && kSides.count(w[i])))) ||
                    (w[i + 1] == "of" && kSides.count(w[i]))))
    return 2;
  if (!kStarters.count(w[i])) return 0;
  int j = i + 1;
  if (j < n && kArticles.count(w[j])) ++j;
  const int first = j;
  int head = -1;
  while (j < n && (kModifiers.count(w[j]) || kDirections.count(w[j]) || kRegions.count(w[j]))) head = j++;
  if (head < 0 || kModifiers.count(w[head])) return 0;
  const bool region = kRegions.count(w[head]) > 0;
  if (j < n && (w[j] == "of" || w[j] == "to")) return region && head == first ? 0 : j + 1 - i;
  // "at / from the center" name the centre as a place (train: "[at] the center"), "in the center" a direction.
  const bool centre = w[head] == "center" || w[head] == "centre";
  if (!region && landmarklessAt(w, j) && (w[i] == "to" || kPlaceDirections.count(w[head]) || (centre && w[i] == "in")))
    return j - i;
  return 0;
}

bool PhraseRules::isSourceAt(const std::vector<std::string>& lower, int start) {
  const int n = static_cast<int>(lower.size());
  if (start < 0 || start >= n) return false;
  const std::string& w = lower[start];
  const std::string next = start + 1 < n ? lower[start + 1] : std::string();
  return w == "from" || w == "off" || (w == "out" && next == "of") || (w == "away" && next == "from");
}

bool PhraseRules::isPlacingVerb(const std::string& lemma) { return kPlacingVerbs.count(lemma) > 0; }

void PhraseRules::applyDirectionSpans(const std::vector<std::string>& lower, std::vector<EntitySpan>& entities,
                                      bool sideTo) {
  const int n = static_cast<int>(lower.size());
  sortByStart(entities);
  std::vector<bool> removed(entities.size(), false);
  for (size_t e = 0; e < entities.size(); ++e) {
    if (removed[e] || !isIndicator(entities[e].type)) continue;
    const std::vector<int> owner = owners(n, entities);
    EntitySpan& span = entities[e];
    // A lone "to" / "of" after its relational word: "right [to]" -> "[right to]".
    if (span.end - span.start == 1 && span.start > 0 && owner[span.start - 1] < 0 &&
        directionSpanLength(lower, span.start - 1, sideTo) == 2)
      --span.start;
    const int length = directionSpanLength(lower, span.start, sideTo);
    if (length <= span.end - span.start) continue;
    const int end = span.start + length;
    std::vector<size_t> absorbed;
    bool free = true;
    for (int k = span.end; k < end; ++k) {
      const int o = owner[k];
      if (o < 0 || o == static_cast<int>(e)) continue;
      if (isIndicator(entities[o].type) && entities[o].end <= end) {
        absorbed.push_back(static_cast<size_t>(o));
      } else {
        free = false;
      }
    }
    if (!free) continue;
    for (size_t a : absorbed) removed[a] = true;
    span.end = end;
  }
  std::vector<EntitySpan> kept;
  for (size_t e = 0; e < entities.size(); ++e)
    if (!removed[e]) kept.push_back(entities[e]);
  entities = kept;
}

void PhraseRules::applySourceSpans(const std::vector<std::string>& lower, std::vector<EntitySpan>& entities) {
  const int n = static_cast<int>(lower.size());
  const std::vector<int> owner = owners(n, entities);
  for (auto& span : entities) {
    if (!isIndicator(span.type) || span.start >= n) continue;
    if (lower[span.start] == "out" && span.end == span.start + 1 && span.end < n && lower[span.end] == "of" &&
        owner[span.end] < 0)
      ++span.end;
    else if (lower[span.start] == "from" && span.start > 0 && lower[span.start - 1] == "away" && owner[span.start - 1] < 0)
      --span.start;
  }
}

void PhraseRules::addPlacingClauseGoals(const std::vector<std::string>& lower, std::vector<EntitySpan>& entities,
                                        const LemmaFunction& lemmaOf, bool sideTo) {
  const int n = static_cast<int>(lower.size());
  // No indicator whose only landmark is "here" / "there" ("put the books over there").
  entities.erase(std::remove_if(entities.begin(), entities.end(),
                                [&](const EntitySpan& e) {
                                  return isIndicator(e.type) && e.end < n &&
                                         (lower[e.end] == "here" || lower[e.end] == "there") &&
                                         landmarklessAt(lower, e.end + 1);
                                }),
                 entities.end());
  sortByStart(entities);
  std::vector<EntitySpan> added;
  for (size_t a = 0; a < entities.size(); ++a) {
    if (entities[a].type != "Action" || !isPlacingVerb(lemmaOf(lower[entities[a].start]))) continue;
    int clauseEnd = n;
    for (size_t b = a + 1; b < entities.size(); ++b)
      if (entities[b].type == "Action") {
        clauseEnd = entities[b].start;
        break;
      }
    for (int k = entities[a].end; k < clauseEnd; ++k)
      if (endsSentence(lower[k])) clauseEnd = k;
    bool hasGoal = false;
    for (const auto& e : entities) hasGoal |= e.type == "GoalIndicator" && e.start >= entities[a].end && e.start < clauseEnd;
    if (hasGoal) continue;
    const std::vector<int> owner = owners(n, entities);
    bool afterSource = false;  // "place X from Y onto Z": after the source, the next phrase is the goal
    for (int k = entities[a].end; k < clauseEnd; ++k) {
      if (kRelativeWords.count(lower[k])) break;  // a relative clause locates the object; its phrase is no goal
      if (owner[k] >= 0) {
        afterSource |= isIndicator(entities[owner[k]].type) && entities[owner[k]].start == k && isSourceAt(lower, k);
        continue;
      }
      if (k >= 2 && kCountWords.count(lower[k - 2]) && kGridUnits.count(lower[k - 1])) break;
      if (afterSource && kGoalPrepositions.count(lower[k]) && !landmarklessAt(lower, k + 1)) {
        added.push_back({k, k + std::max(1, directionSpanLength(lower, k, sideTo)), "GoalIndicator"});
        break;
      }
      const int length = directionSpanLength(lower, k, sideTo);
      bool free = length > 0 && k + length <= clauseEnd;
      for (int m = k; free && m < k + length; ++m) free = owner[m] < 0;
      if (free) {
        added.push_back({k, k + length, "GoalIndicator"});
        break;
      }
      if (kBarePrepositions.count(lower[k]) && landmarklessAt(lower, k + 1)) {
        added.push_back({k, k + 1, "GoalIndicator"});
        break;
      }
    }
  }
  entities.insert(entities.end(), added.begin(), added.end());
  sortByStart(entities);
}

void PhraseRules::addRoomOfIndicators(const std::vector<std::string>& lower, std::vector<EntitySpan>& entities,
                                      const WordTest& isNoun, const WordTest& isRoom) {
  const int n = static_cast<int>(lower.size());
  std::vector<int> owner = owners(n, entities);
  std::vector<EntitySpan> added;
  for (int k = 1; k + 1 < n; ++k) {
    if (lower[k] != "of" || owner[k] >= 0) continue;
    const std::string& before = lower[k - 1];
    if (!isNoun(before) || kDirections.count(before) || kRegions.count(before)) continue;
    int m = k + 1;
    while (m < n && kDeterminers.count(lower[m])) ++m;
    int head = -1;
    while (m < n && isNoun(lower[m]) && !kDeterminers.count(lower[m])) head = m++;
    if (head < 0 || !isRoom(lower[head])) continue;
    added.push_back({k, k + 1, "SpatialIndicator"});
    if (owner[k - 1] < 0) {
      added.push_back({k - 1, k, "Trajector"});
      owner[k - 1] = -2;
    }
  }
  entities.insert(entities.end(), added.begin(), added.end());
  sortByStart(entities);
}

}  // namespace srp::language
