#include "srp/language/AnnotationPrecedents.h"

#include <algorithm>
#include <set>
#include <utility>

#include "srp/core/Error.h"
#include "srp/language/Tokenizer.h"

namespace srp::language {

AnnotationPrecedents::AnnotationPrecedents(const std::vector<AnnotatedSentence>& reference, int radius)
    : radius_(radius) {
  core::require(radius >= 0, "AnnotationPrecedents: radius must be >= 0, got " + std::to_string(radius));
  for (const auto& s : reference) {
    const std::vector<std::string> lower = toLowerAscii(s.tokens);
    for (int i = 0; i < static_cast<int>(lower.size()); ++i) ++counts_[contextKey(lower, i)][labelAt(s, i)];
  }
}

std::string AnnotationPrecedents::labelAt(const AnnotatedSentence& sentence, int position) {
  std::string best;
  for (const auto& e : sentence.entities)
    if (e.start == position && (best.empty() || e.type < best.substr(0, best.find(':'))))
      best = e.type + ":" + std::to_string(e.end - e.start);
  return best.empty() ? "none" : best;
}

std::string AnnotationPrecedents::contextKey(const std::vector<std::string>& lowerTokens, int position) const {
  const int n = static_cast<int>(lowerTokens.size());
  std::string key;
  for (int k = position - radius_; k <= position + radius_; ++k) {
    key += k < 0 ? "<s>" : k >= n ? "</s>" : lowerTokens[k];
    key += ' ';
  }
  return key;
}

std::map<std::string, int> AnnotationPrecedents::at(const std::vector<std::string>& tokens, int position) const {
  auto it = counts_.find(contextKey(toLowerAscii(tokens), position));
  return it == counts_.end() ? std::map<std::string, int>{} : it->second;
}

std::string AnnotationPrecedents::majority(const std::map<std::string, int>& counts) {
  int total = 0;
  for (const auto& [label, n] : counts) total += n;
  for (const auto& [label, n] : counts)
    if (2 * n > total) return label;
  return {};
}

PrecedentCheck checkAgainstPrecedents(const std::vector<AnnotatedSentence>& gold,
                                      const std::vector<AnnotatedSentence>& predicted,
                                      const AnnotationPrecedents& precedents, const std::set<std::string>& types) {
  PrecedentCheck check;
  const SpertScores scores = scoreSpert(gold, predicted);
  for (const auto& [type, score] : scores.types)
    if (types.empty() || types.count(type)) check.ifConsistent[type] = score;
  auto typeOf = [](const std::string& label) { return label.substr(0, label.find(':')); };
  std::set<std::pair<int, int>> recounted;  // (sentence, position): a boundary error has two sides at one position
  for (const auto& e : entityErrors(gold, predicted)) {
    if (!types.empty() && !types.count(e.entity.type)) continue;
    ++check.errors;
    const auto& tokens = gold[e.sentence].tokens;
    const int p = e.entity.start;
    const std::string goldLabel = AnnotationPrecedents::labelAt(gold[e.sentence], p);
    const std::string predictedLabel = AnnotationPrecedents::labelAt(predicted[e.sentence], p);
    const auto counts = precedents.at(tokens, p);
    const std::string majority = AnnotationPrecedents::majority(counts);
    const bool against = !counts.empty() && majority == predictedLabel && majority != goldLabel;
    if (!counts.empty()) ++check.withPrecedent;
    if (against) ++check.againstPrecedent;
    if (against && recounted.insert({e.sentence, p}).second) {
      // The gold entity at p would not be there; the predicted one would be right.
      if (goldLabel != "none") {
        auto it = check.ifConsistent.find(typeOf(goldLabel));
        if (it != check.ifConsistent.end()) --it->second.falseNegatives;
      }
      if (predictedLabel != "none") {
        auto it = check.ifConsistent.find(typeOf(predictedLabel));
        if (it != check.ifConsistent.end()) {
          --it->second.falsePositives;
          ++it->second.truePositives;
        }
      }
    }
    std::string words;
    for (int k = std::max(0, p - precedents.radius()); k < std::min<int>(tokens.size(), p + precedents.radius() + 1); ++k)
      words += std::string(k == p ? "[" : "") + tokens[k] + (k == p ? "]" : "") + " ";
    std::string reference;
    for (const auto& [label, n] : counts) reference += (reference.empty() ? "" : ", ") + label + " x" + std::to_string(n);
    check.report += "#" + std::to_string(e.sentence) + " " + (e.goldSide ? "gold " : "pred ") + e.kind + " " +
                    e.entity.type + ": " + words + "| gold " + goldLabel + ", predicted " + predictedLabel +
                    ", reference " + (counts.empty() ? "-" : reference) + (against ? "  AGAINST PRECEDENT" : "") + "\n";
  }
  return check;
}

}  // namespace srp::language
