#include "srp/language/SpertEvaluation.h"

#include <chrono>
#include <cstdio>
#include <set>
#include <tuple>

#include "srp/core/Error.h"

namespace srp::language {

double TypeScore::precision() const {
  const int n = truePositives + falsePositives;
  return n == 0 ? 0.0 : static_cast<double>(truePositives) / n;
}
double TypeScore::recall() const {
  const int n = truePositives + falseNegatives;
  return n == 0 ? 0.0 : static_cast<double>(truePositives) / n;
}
double TypeScore::f1() const {
  const double p = precision(), r = recall();
  return p + r == 0.0 ? 0.0 : 2.0 * p * r / (p + r);
}

namespace {
using EntityKey = std::tuple<int, int, std::string>;
using RelationKey = std::tuple<std::string, EntityKey, EntityKey>;

std::set<EntityKey> entityKeys(const AnnotatedSentence& s) {
  std::set<EntityKey> keys;
  for (const auto& e : s.entities) keys.insert({e.start, e.end, e.type});
  return keys;
}
std::set<RelationKey> relationKeys(const AnnotatedSentence& s) {
  std::set<RelationKey> keys;
  for (const auto& r : s.relations) {
    const auto& h = s.entities.at(r.head);
    const auto& t = s.entities.at(r.tail);
    keys.insert({r.type, EntityKey{h.start, h.end, h.type}, EntityKey{t.start, t.end, t.type}});
  }
  return keys;
}
template <typename Key, typename TypeOf>
void count(const std::set<Key>& gold, const std::set<Key>& pred, TypeOf typeOf, std::map<std::string, TypeScore>& out) {
  for (const auto& k : pred) (gold.count(k) ? out[typeOf(k)].truePositives : out[typeOf(k)].falsePositives)++;
  for (const auto& k : gold)
    if (!pred.count(k)) out[typeOf(k)].falseNegatives++;
}
}  // namespace

SpertScores scoreSpert(const std::vector<AnnotatedSentence>& gold, const std::vector<AnnotatedSentence>& predicted) {
  core::require(gold.size() == predicted.size(),
                "scoreSpert: " + std::to_string(predicted.size()) + " predicted sentences for " +
                    std::to_string(gold.size()) + " gold ones; annotate every gold sentence once");
  SpertScores scores;
  for (const std::string t : {"Action", "Trajector", "SpatialIndicator", "GoalIndicator", "Color", "Spatial", "Transition"})
    scores.types[t];
  for (size_t i = 0; i < gold.size(); ++i) {
    core::require(gold[i].tokens.size() == predicted[i].tokens.size(),
                  "scoreSpert: sentence " + std::to_string(i) + " has different token counts in gold and prediction");
    count(entityKeys(gold[i]), entityKeys(predicted[i]), [](const EntityKey& k) { return std::get<2>(k); }, scores.types);
    count(relationKeys(gold[i]), relationKeys(predicted[i]), [](const RelationKey& k) { return std::get<0>(k); },
          scores.types);
  }
  return scores;
}

SpertScores evaluateModel(const LanguageModel& model, const std::vector<AnnotatedSentence>& gold) {
  std::vector<AnnotatedSentence> predicted;
  predicted.reserve(gold.size());
  const auto t0 = std::chrono::steady_clock::now();
  for (const auto& s : gold) predicted.push_back(model.annotate(s.tokens));
  const auto t1 = std::chrono::steady_clock::now();
  SpertScores scores = scoreSpert(gold, predicted);
  if (!gold.empty())
    scores.msPerSentence = std::chrono::duration<double, std::milli>(t1 - t0).count() / static_cast<double>(gold.size());
  return scores;
}

nlohmann::json toJson(const SpertScores& scores) {
  nlohmann::json types = nlohmann::json::object();
  for (const auto& [name, s] : scores.types)
    types[name] = {{"precision", s.precision()}, {"recall", s.recall()}, {"f1", s.f1()}, {"support", s.support()}};
  return {{"types", types}, {"ms_per_sentence", scores.msPerSentence}};
}

std::string formatScoreTable(const SpertScores& scores) {
  std::string out = "type               precision  recall     F1  support\n";
  char line[160];
  for (const std::string t : {"Action", "Trajector", "SpatialIndicator", "GoalIndicator", "Color", "Spatial", "Transition"}) {
    auto it = scores.types.find(t);
    if (it == scores.types.end()) continue;
    const auto& s = it->second;
    std::snprintf(line, sizeof line, "%-17s %9.2f %7.2f %6.2f %8d\n", t.c_str(), 100 * s.precision(), 100 * s.recall(),
                  100 * s.f1(), s.support());
    out += line;
  }
  std::snprintf(line, sizeof line, "time per sentence: %.3f ms\n", scores.msPerSentence);
  return out + line;
}

}  // namespace srp::language
