#include "srp/language/SpertEvaluation.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <set>
#include <thread>
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

CrossValidationResult crossValidate(const std::vector<AnnotatedSentence>& corpus,
                                    const LanguageTrainingOptions& options, int folds, int threads) {
  core::require(folds >= 2 && folds <= static_cast<int>(corpus.size()),
                "crossValidate: folds must be in [2, corpus size], got " + std::to_string(folds));
  CrossValidationResult result;
  result.predictions.resize(corpus.size());
  auto runFold = [&](int fold) {
    std::vector<AnnotatedSentence> train;
    for (size_t i = 0; i < corpus.size(); ++i)
      if (static_cast<int>(i % folds) != fold) train.push_back(corpus[i]);
    const LanguageModel model = LanguageModel::train(train, options);
    for (size_t i = fold; i < corpus.size(); i += folds) result.predictions[i] = model.annotate(corpus[i].tokens);
  };
  const int workers = std::max(1, std::min(threads, folds));
  std::vector<std::thread> pool;
  for (int w = 0; w < workers; ++w)
    pool.emplace_back([&, w] {
      for (int fold = w; fold < folds; fold += workers) runFold(fold);
    });
  for (auto& t : pool) t.join();
  result.scores = scoreSpert(corpus, result.predictions);
  return result;
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
  if (scores.msPerSentence <= 0.0) return out;  // not timed (pooled or recounted scores)
  std::snprintf(line, sizeof line, "time per sentence: %.3f ms\n", scores.msPerSentence);
  return out + line;
}

}  // namespace srp::language

namespace srp::language {

std::vector<EntityError> entityErrors(const std::vector<AnnotatedSentence>& gold,
                                      const std::vector<AnnotatedSentence>& predicted) {
  core::require(gold.size() == predicted.size(),
                "entityErrors: " + std::to_string(predicted.size()) + " predicted sentences for " +
                    std::to_string(gold.size()) + " gold ones; annotate every gold sentence once");
  std::vector<EntityError> errors;
  auto overlaps = [](const EntitySpan& a, const EntitySpan& b) { return a.start < b.end && b.start < a.end; };
  for (size_t i = 0; i < gold.size(); ++i) {
    const auto& g = gold[i].entities;
    const auto& p = predicted[i].entities;
    // One side's entity against the other side: which kind of error, if any.
    auto classify = [&](const EntitySpan& e, const std::vector<EntitySpan>& other, bool goldSide) {
      EntityError err{"", static_cast<int>(i), goldSide, e, ""};
      bool sameType = false, otherType = false;
      for (const auto& o : other) {
        if (o == e) return;  // correct
        if (o.start == e.start && o.end == e.end) {
          if (!goldSide) return;  // listed once, as the gold entity's type error
          err.kind = "type";
          err.otherType = o.type;
          errors.push_back(err);
          return;
        }
        if (overlaps(o, e)) (o.type == e.type ? sameType : otherType) = true;
      }
      err.kind = sameType ? "boundary" : otherType ? "overlap" : goldSide ? "missed" : "spurious";
      errors.push_back(err);
    };
    for (const auto& e : g) classify(e, p, true);
    for (const auto& e : p) classify(e, g, false);
  }
  return errors;
}

std::string formatEntityErrors(const std::vector<AnnotatedSentence>& gold,
                               const std::vector<AnnotatedSentence>& predicted, const std::set<std::string>& types) {
  const auto all = entityErrors(gold, predicted);
  std::vector<EntityError> errors;
  for (const auto& e : all)
    if (types.empty() || types.count(e.entity.type)) errors.push_back(e);
  std::map<std::string, std::map<std::string, int>> counts;  // type -> "side kind" -> count
  for (const auto& e : errors) ++counts[e.entity.type][std::string(e.goldSide ? "gold " : "predicted ") + e.kind];
  std::string out = "entity errors (gold side: not predicted; predicted side: not in gold):\n";
  for (const auto& [type, byKind] : counts) {
    out += "  " + type + ":";
    for (const auto& [kind, n] : byKind) out += " " + kind + " " + std::to_string(n) + ";";
    out += "\n";
  }
  auto text = [](const AnnotatedSentence& s, int start, int end) {
    std::string t;
    for (int k = start; k < end && k < static_cast<int>(s.tokens.size()); ++k) t += (k > start ? " " : "") + s.tokens[k];
    return t;
  };
  auto bracketed = [&](const AnnotatedSentence& s) {
    std::vector<std::string> words = s.tokens;
    for (const auto& e : s.entities) {
      if ((!types.empty() && !types.count(e.type)) || e.start >= e.end || e.end > static_cast<int>(words.size())) continue;
      words[e.start] = "[" + words[e.start];
      words[e.end - 1] += "]" + e.type;
    }
    std::string t;
    for (const auto& w : words) t += (t.empty() ? "" : " ") + w;
    return t;
  };
  for (size_t k = 0; k < errors.size();) {
    const int i = errors[k].sentence;
    out += "#" + std::to_string(i) + "\n  gold: " + bracketed(gold[i]) + "\n  pred: " + bracketed(predicted[i]) + "\n";
    for (; k < errors.size() && errors[k].sentence == i; ++k) {
      const auto& e = errors[k];
      out += std::string("    ") + (e.goldSide ? "gold " : "pred ") + e.kind + " " + e.entity.type +
             (e.kind == "type" ? " -> " + e.otherType : "") + " \"" +
             text(e.goldSide ? gold[i] : predicted[i], e.entity.start, e.entity.end) + "\"\n";
    }
  }
  return out;
}

}  // namespace srp::language
