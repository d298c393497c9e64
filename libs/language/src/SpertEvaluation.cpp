#include "srp/language/SpertEvaluation.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <random>
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

CrossValidationResult crossValidate(const std::vector<AnnotatedSentence>& corpus, const LanguageModel::Options& options,
                                    int folds, int threads) {
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

namespace {
const std::vector<std::string> kScoredTypes{"Action", "Trajector", "SpatialIndicator", "GoalIndicator",
                                            "Color",  "Spatial",   "Transition"};

double foldF1(const SpertScores& s, const std::string& type) {
  if (type != "macro") return s.types.at(type).f1();
  double sum = 0.0;
  for (const auto& t : kScoredTypes) sum += s.types.at(t).f1();
  return sum / static_cast<double>(kScoredTypes.size());
}

CvSummary meanStd(const std::vector<double>& v) {
  CvSummary out;
  if (v.empty()) return out;
  for (double x : v) out.mean += x;
  out.mean /= static_cast<double>(v.size());
  if (v.size() < 2) return out;
  double ss = 0.0;
  for (double x : v) ss += (x - out.mean) * (x - out.mean);
  out.std = std::sqrt(ss / static_cast<double>(v.size() - 1));
  return out;
}

/// Standard deviation of the mean of n = folds x seeds paired fold differences,
/// corrected for the overlap of the training sets (Nadeau & Bengio 2003,
/// "Inference for the generalization error": variance factor 1/n + n_test/n_train).
double correctedStdOfMean(double foldStd, int folds, int seeds) {
  const double n = static_cast<double>(folds) * seeds;
  return foldStd * std::sqrt(1.0 / n + 1.0 / (folds - 1));
}

/// Fisher-Yates with explicit modulo draws: the same order on every platform.
std::vector<size_t> shuffledIndices(size_t n, unsigned seed) {
  std::vector<size_t> order(n);
  for (size_t i = 0; i < n; ++i) order[i] = i;
  std::mt19937_64 engine(seed);
  for (size_t i = n; i > 1; --i) std::swap(order[i - 1], order[engine() % i]);
  return order;
}

bool passes(const RepeatedCrossValidation& cv, size_t variant) {
  const auto macro = cvF1Difference(cv.folds[variant], cv.folds[0], "macro");
  if (!(macro.mean > correctedStdOfMean(macro.std, cv.numFolds, cv.numSeeds))) return false;
  for (const auto& t : kScoredTypes)
    if (cvF1Difference(cv.folds[variant], cv.folds[0], t).mean < 0.0) return false;
  return true;
}
}  // namespace

CvSummary cvF1(const std::vector<SpertScores>& folds, const std::string& type) {
  std::vector<double> v;
  for (const auto& f : folds) v.push_back(foldF1(f, type));
  return meanStd(v);
}

CvSummary cvF1Difference(const std::vector<SpertScores>& folds, const std::vector<SpertScores>& baseline,
                         const std::string& type) {
  core::require(folds.size() == baseline.size(), "cvF1Difference: variants scored on different folds");
  std::vector<double> v;
  for (size_t i = 0; i < folds.size(); ++i) v.push_back(foldF1(folds[i], type) - foldF1(baseline[i], type));
  return meanStd(v);
}

RepeatedCrossValidation repeatedCrossValidate(const std::vector<AnnotatedSentence>& corpus,
                                              const LanguageModel::Options& options, int folds, int seeds, int threads,
                                              const std::vector<std::pair<std::string, DecodingRules>>& variants) {
  core::require(folds >= 2 && folds <= static_cast<int>(corpus.size()) && seeds >= 1,
                "repeatedCrossValidate: need 2 <= folds <= corpus size and seeds >= 1, got folds " +
                    std::to_string(folds) + ", seeds " + std::to_string(seeds));
  RepeatedCrossValidation cv;
  cv.numFolds = folds;
  cv.numSeeds = seeds;
  cv.variantNames.push_back("baseline");
  std::vector<DecodingRules> rules{options.rules};
  for (const auto& [name, r] : variants) {
    cv.variantNames.push_back(name);
    rules.push_back(r);
  }
  const int jobs = folds * seeds;
  cv.folds.assign(rules.size(), std::vector<SpertScores>(jobs));
  cv.firstSeedPredictions.resize(corpus.size());
  std::vector<std::vector<size_t>> orders;
  for (int s = 0; s < seeds; ++s) orders.push_back(shuffledIndices(corpus.size(), static_cast<unsigned>(s + 1)));
  std::vector<double> seconds(jobs, 0.0);
  auto runJob = [&](int job) {
    const int seed = job / folds, fold = job % folds;
    const auto& order = orders[seed];
    std::vector<AnnotatedSentence> train, test;
    std::vector<size_t> testIds;
    for (size_t k = 0; k < order.size(); ++k) {
      if (static_cast<int>(k % folds) == fold) {
        test.push_back(corpus[order[k]]);
        testIds.push_back(order[k]);
      } else {
        train.push_back(corpus[order[k]]);
      }
    }
    const auto t0 = std::chrono::steady_clock::now();
    LanguageModel model = LanguageModel::train(train, options);
    seconds[job] = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    for (size_t v = 0; v < rules.size(); ++v) {
      model.setDecodingRules(rules[v]);
      std::vector<AnnotatedSentence> predicted;
      for (const auto& sentence : test) predicted.push_back(model.annotate(sentence.tokens));
      cv.folds[v][job] = scoreSpert(test, predicted);
      if (v == 0 && seed == 0)
        for (size_t k = 0; k < testIds.size(); ++k) cv.firstSeedPredictions[testIds[k]] = predicted[k];
    }
  };
  const int workers = std::max(1, std::min(threads, jobs));
  std::vector<std::thread> pool;
  for (int w = 0; w < workers; ++w)
    pool.emplace_back([&, w] {
      for (int job = w; job < jobs; job += workers) runJob(job);
    });
  for (auto& t : pool) t.join();
  for (double x : seconds) cv.trainSecondsPerFold += x / jobs;
  return cv;
}

std::string formatCrossValidation(const RepeatedCrossValidation& cv) {
  char line[256];
  std::string out;
  std::snprintf(line, sizeof line, "%d-fold cross-validation x %d seeds (F1 %%, mean +- std over %d folds)\n",
                cv.numFolds, cv.numSeeds, cv.numFolds * cv.numSeeds);
  out += line;
  std::vector<std::string> types = kScoredTypes;
  types.push_back("macro");
  for (size_t v = 0; v < cv.folds.size(); ++v) {
    out += (v == 0 ? "" : "\n") + cv.variantNames[v] + (v == 0 ? "" : " (difference to baseline, paired)") + ":\n";
    for (const auto& t : types) {
      const auto s = cvF1(cv.folds[v], t);
      if (v == 0) {
        std::snprintf(line, sizeof line, "  %-17s %6.2f +- %5.2f\n", t.c_str(), 100 * s.mean, 100 * s.std);
      } else {
        const auto d = cvF1Difference(cv.folds[v], cv.folds[0], t);
        std::snprintf(line, sizeof line, "  %-17s %6.2f +- %5.2f   diff %+6.2f +- %5.2f (of the mean %4.2f)\n",
                      t.c_str(), 100 * s.mean, 100 * s.std, 100 * d.mean, 100 * d.std,
                      100 * correctedStdOfMean(d.std, cv.numFolds, cv.numSeeds));
      }
      out += line;
    }
    if (v > 0) out += std::string("  verdict: ") + (passes(cv, v) ? "better than baseline" : "not better") + "\n";
  }
  std::snprintf(line, sizeof line, "training: %.1f s per fold\n", cv.trainSecondsPerFold);
  return out + line;
}

nlohmann::json toJson(const RepeatedCrossValidation& cv) {
  nlohmann::json variants = nlohmann::json::object();
  std::vector<std::string> types = kScoredTypes;
  types.push_back("macro");
  for (size_t v = 0; v < cv.folds.size(); ++v) {
    nlohmann::json j = nlohmann::json::object();
    for (const auto& t : types) {
      const auto s = cvF1(cv.folds[v], t);
      j[t] = {{"f1_mean", s.mean}, {"f1_std", s.std}};
      std::vector<double> perFold;  // seed-major: compare runs fold by fold (same seeds, same splits)
      for (const auto& f : cv.folds[v]) perFold.push_back(foldF1(f, t));
      j[t]["f1_folds"] = perFold;
      if (v > 0) {
        const auto d = cvF1Difference(cv.folds[v], cv.folds[0], t);
        j[t]["diff_mean"] = d.mean;
        j[t]["diff_std"] = d.std;
        j[t]["diff_std_of_mean"] = correctedStdOfMean(d.std, cv.numFolds, cv.numSeeds);
      }
    }
    if (v > 0) j["better_than_baseline"] = passes(cv, v);
    variants[cv.variantNames[v]] = j;
  }
  return {{"folds", cv.numFolds}, {"seeds", cv.numSeeds}, {"variants", variants}};
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
