#include "srp/language/IndicatorConventions.h"

#include <algorithm>

#include "srp/core/Error.h"
#include "srp/core/Json.h"
#include "srp/language/Tokenizer.h"

namespace srp::language {

namespace {

constexpr int kMaxIndicatorWords = 8;
constexpr int kMinWordCountForRareStart = 5;
constexpr double kMaxRareStartRate = 0.02;
constexpr int kMinPairCountForRareStart = 3;
constexpr double kMaxRarePairStartRate = 0.10;

/// "previous|word" of the word at `k` ("<s>" before the first word).
std::string pairKey(const std::vector<std::string>& lowerTokens, int k) {
  return (k > 0 ? lowerTokens[k - 1] : std::string("<s>")) + "|" + lowerTokens[k];
}

bool isIndicator(const std::string& type) { return type == "SpatialIndicator" || type == "GoalIndicator"; }

/// "verb|dir|first": action lemma, directional or not, first indicator of the clause or not.
std::string typeKey(const std::string& verbLemma, const std::string& firstWord, bool firstInClause) {
  static const std::set<std::string> kDirectional{"to", "into", "onto", "toward", "towards"};
  return verbLemma + (kDirectional.count(firstWord) ? "|dir|" : "|at|") + (firstInClause ? "first" : "later");
}

/// The most frequent key of `counts` when it has >= num/den of >= minTotal counts.
template <typename Key>
std::optional<Key> consistentMajority(const std::map<Key, int>& counts, int minTotal, int num, int den) {
  int total = 0, best = 0;
  Key bestKey{};
  for (const auto& [key, count] : counts) {
    total += count;
    if (count > best) best = count, bestKey = key;
  }
  if (total >= minTotal && den * best >= num * total) return bestKey;
  return std::nullopt;
}

}  // namespace

std::string IndicatorConventions::longestPhraseAt(const std::vector<std::string>& lowerTokens, int start) const {
  std::string phrase, longest;
  for (int k = start; k < static_cast<int>(lowerTokens.size()) && k < start + kMaxIndicatorWords; ++k) {
    phrase += (k > start ? " " : "") + lowerTokens[k];
    if (phrases_.count(phrase)) longest = phrase;
  }
  return longest;
}

bool IndicatorConventions::inRelativeClause(const std::vector<std::string>& lowerTokens, int start) {
  static const std::set<std::string> kRelativePronouns{"which", "that", "who"};
  static const std::set<std::string> kCopulas{"is", "are", "'s", "was", "were"};
  static const std::set<std::string> kParticiples{"sitting", "standing", "lying", "resting", "kept", "put", "set"};
  if (start <= 0 || start > static_cast<int>(lowerTokens.size())) return false;
  const std::string& prev = lowerTokens[start - 1];
  if (kParticiples.count(prev) || (prev.size() >= 5 && prev.compare(prev.size() - 2, 2, "ed") == 0)) return true;
  bool relative = false, copula = false;
  for (int k = std::max(0, start - 4); k < start; ++k) {
    relative |= kRelativePronouns.count(lowerTokens[k]) > 0;
    copula |= kCopulas.count(lowerTokens[k]) > 0;
  }
  return relative && copula;
}

IndicatorConventions IndicatorConventions::learn(const std::vector<AnnotatedSentence>& corpus,
                                                 const LemmaFunction& lemmaOf) {
  IndicatorConventions c;
  for (const auto& s : corpus)
    for (const auto& e : s.entities)
      if (isIndicator(e.type) && e.end - e.start <= kMaxIndicatorWords) {
        std::string phrase;
        for (int k = e.start; k < e.end; ++k) phrase += (k > e.start ? " " : "") + toLowerAscii(s.tokens[k]);
        c.phrases_.insert(phrase);
      }
  std::map<std::string, int> seen, starts, pairsSeen, pairStarts;
  for (const auto& s : corpus) {
    const auto lower = toLowerAscii(s.tokens);
    for (int k = 0; k < static_cast<int>(lower.size()); ++k) {
      ++seen[lower[k]];
      ++pairsSeen[pairKey(lower, k)];
    }
    for (const auto& e : s.entities)
      if (isIndicator(e.type) && e.start < static_cast<int>(lower.size())) {
        ++starts[lower[e.start]];
        ++pairStarts[pairKey(lower, e.start)];
      }
  }
  for (const auto& [word, count] : seen)
    if (count >= kMinWordCountForRareStart && starts[word] < kMaxRareStartRate * count) c.rarelyAnnotatedStarts_.insert(word);
  for (const auto& [pair, count] : pairsSeen)
    if (count >= kMinPairCountForRareStart && pairStarts[pair] <= kMaxRarePairStartRate * count)
      c.rarelyAnnotatedPairs_.insert(pair);
  std::map<std::string, std::map<int, int>> lengths;
  std::map<std::string, std::map<std::string, int>> types;
  for (const auto& s : corpus) {
    const auto lower = toLowerAscii(s.tokens);
    auto sorted = s.entities;
    std::sort(sorted.begin(), sorted.end(), [](const auto& a, const auto& b) { return a.start < b.start; });
    std::string verb;
    bool firstInClause = true;
    for (size_t i = 0; i < sorted.size(); ++i) {
      const auto& e = sorted[i];
      if (e.type == "Action") {
        verb = lemmaOf(lower[e.start]);
        firstInClause = true;
        continue;
      }
      if (!isIndicator(e.type)) continue;
      ++lengths[c.longestPhraseAt(lower, e.start)][e.end - e.start];
      if (inRelativeClause(lower, e.start)) continue;
      bool actionAfter = false;
      for (size_t j = i + 1; j < sorted.size(); ++j) actionAfter |= sorted[j].type == "Action";
      if (!actionAfter && !verb.empty()) ++types[typeKey(verb, lower[e.start], firstInClause)][e.type];
      firstInClause = false;
    }
  }
  for (const auto& [phrase, byLength] : lengths)
    if (auto length = consistentMajority(byLength, 2, 2, 3)) c.lengthByPhrase_[phrase] = *length;
  for (const auto& [key, byType] : types)
    if (auto type = consistentMajority(byType, 3, 9, 10)) c.typeByKey_[key] = *type;
  return c;
}

std::optional<int> IndicatorConventions::spanLength(const std::vector<std::string>& lowerTokens, int start) const {
  auto it = lengthByPhrase_.find(longestPhraseAt(lowerTokens, start));
  if (it == lengthByPhrase_.end()) return std::nullopt;
  return it->second;
}

std::optional<std::string> IndicatorConventions::indicatorType(const std::string& verbLemma, const std::string& firstWord,
                                                               bool firstInClause) const {
  auto it = typeByKey_.find(typeKey(verbLemma, firstWord, firstInClause));
  if (it == typeByKey_.end()) return std::nullopt;
  return it->second;
}

void IndicatorConventions::applySpanLengths(const std::vector<std::string>& tokens,
                                            std::vector<EntitySpan>& entities) const {
  const auto lower = toLowerAscii(tokens);
  const int n = static_cast<int>(tokens.size());
  std::vector<int> owner(n, -1);
  for (size_t e = 0; e < entities.size(); ++e)
    for (int k = entities[e].start; k < entities[e].end && k < n; ++k) owner[k] = static_cast<int>(e);
  for (size_t e = 0; e < entities.size(); ++e) {
    auto& span = entities[e];
    if (!isIndicator(span.type)) continue;
    const auto length = spanLength(lower, span.start);
    if (!length) continue;
    const int end = span.start + *length;
    bool free = true;
    for (int k = span.end; k < end; ++k) free &= owner[k] < 0;
    if (!free) continue;
    for (int k = span.start; k < std::max(end, span.end); ++k) owner[k] = k < end ? static_cast<int>(e) : -1;
    span.end = end;
  }
}

void IndicatorConventions::dropIndicatorsOutsideOrders(const std::vector<std::string>& tokens,
                                                       std::vector<EntitySpan>& entities) {
  const int n = static_cast<int>(tokens.size());
  std::vector<int> sentenceOf(n, 0);
  for (int i = 1; i < n; ++i) {
    const std::string& prev = tokens[i - 1];
    sentenceOf[i] = sentenceOf[i - 1] + (prev == "." || prev == "!" || prev == "?" ? 1 : 0);
  }
  std::map<int, int> firstAction;  // sentence -> first action token
  for (const auto& e : entities)
    if (e.type == "Action" && e.start < n) {
      auto [it, inserted] = firstAction.emplace(sentenceOf[e.start], e.start);
      if (!inserted) it->second = std::min(it->second, e.start);
    }
  if (firstAction.empty()) return;
  entities.erase(std::remove_if(entities.begin(), entities.end(),
                                [&](const EntitySpan& e) {
                                  if (!isIndicator(e.type) || e.start >= n) return false;
                                  auto it = firstAction.find(sentenceOf[e.start]);
                                  return it == firstAction.end() || e.start < it->second;
                                }),
                 entities.end());
}

void IndicatorConventions::dropRarelyAnnotatedStarts(const std::vector<std::string>& tokens,
                                                     std::vector<EntitySpan>& entities, bool byWord,
                                                     bool byPair) const {
  const auto lower = toLowerAscii(tokens);
  entities.erase(std::remove_if(entities.begin(), entities.end(),
                                [&](const EntitySpan& e) {
                                  return isIndicator(e.type) && e.start < static_cast<int>(lower.size()) &&
                                         ((byWord && rarelyAnnotatedStarts_.count(lower[e.start]) > 0) ||
                                          (byPair && e.type == "SpatialIndicator" &&
                                           rarelyAnnotatedPairs_.count(pairKey(lower, e.start)) > 0));
                                }),
                 entities.end());
}

nlohmann::json IndicatorConventions::toJson() const {
  return {{"phrases", phrases_},
          {"length_by_phrase", lengthByPhrase_},
          {"type_by_key", typeByKey_},
          {"rarely_annotated_starts", rarelyAnnotatedStarts_},
          {"rarely_annotated_pairs", rarelyAnnotatedPairs_}};
}

IndicatorConventions IndicatorConventions::fromJson(const nlohmann::json& j) {
  IndicatorConventions c;
  c.phrases_ = core::requireField(j, "phrases", "indicator conventions").get<std::set<std::string>>();
  c.lengthByPhrase_ = core::requireField(j, "length_by_phrase", "indicator conventions").get<std::map<std::string, int>>();
  c.typeByKey_ = core::requireField(j, "type_by_key", "indicator conventions").get<std::map<std::string, std::string>>();
  c.rarelyAnnotatedStarts_ =
      core::requireField(j, "rarely_annotated_starts", "indicator conventions").get<std::set<std::string>>();
  c.rarelyAnnotatedPairs_ =
      core::requireField(j, "rarely_annotated_pairs", "indicator conventions").get<std::set<std::string>>();
  return c;
}

}  // namespace srp::language
