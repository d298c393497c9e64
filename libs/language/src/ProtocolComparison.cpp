#include "srp/language/ProtocolComparison.h"

#include <cmath>
#include <cstdio>

#include "srp/core/Error.h"
#include "srp/core/Json.h"

namespace srp::language {

namespace {
const std::vector<std::string> kTypes{"Action",  "Trajector", "SpatialIndicator", "GoalIndicator",
                                      "Color",   "Spatial",   "Transition",       "macro"};
// Two suite F1 closer than this are equal (F1 of the same counts, printed to 0.01 %).
constexpr double kSuiteF1Tol = 1e-9;
}  // namespace

ProtocolComparison::Configuration ProtocolComparison::Configuration::fromCrossValidation(
    const RepeatedCrossValidation& cv, size_t variant, const std::vector<CapabilitySuites::Result>& suites) {
  core::require(variant < cv.folds.size(), "ProtocolComparison: no CV variant " + std::to_string(variant));
  Configuration c;
  c.folds = cv.numFolds;
  c.seeds = cv.numSeeds;
  const auto j = toJson(cv)["variants"][cv.variantNames[variant]];
  for (const auto& t : kTypes) c.foldF1[t] = j[t]["f1_folds"].get<std::vector<double>>();
  for (const auto& s : suites) c.suiteF1[s.name] = {s.entities.f1(), s.relations.f1()};
  return c;
}

ProtocolComparison::Configuration ProtocolComparison::Configuration::fromJson(const nlohmann::json& cvJson,
                                                                            const std::string& variant) {
  Configuration c;
  c.folds = core::requireField(cvJson, "folds", "CV summary").get<int>();
  c.seeds = core::requireField(cvJson, "seeds", "CV summary").get<int>();
  const auto& v = core::requireField(core::requireField(cvJson, "variants", "CV summary"), variant, "CV variants");
  for (const auto& t : kTypes)
    c.foldF1[t] = core::requireField(core::requireField(v, t, "CV variant " + variant), "f1_folds", t)
                      .get<std::vector<double>>();
  if (v.contains("capabilities"))
    for (const auto& [name, s] : v["capabilities"].items())
      c.suiteF1[name] = {core::requireField(s, "entity_f1", name).get<double>(),
                         core::requireField(s, "relation_f1", name).get<double>()};
  return c;
}

ProtocolComparison::ProtocolComparison(const Configuration& candidate, const Configuration& baseline) {
  core::require(candidate.folds == baseline.folds && candidate.seeds == baseline.seeds,
                "ProtocolComparison: runs of " + std::to_string(candidate.folds) + " folds x " +
                    std::to_string(candidate.seeds) + " seeds and " + std::to_string(baseline.folds) + " x " +
                    std::to_string(baseline.seeds) + " are not paired; rerun with the same --cv and --cv-seeds");
  const int n = candidate.folds * candidate.seeds;
  for (const auto& t : kTypes) {
    const auto& a = candidate.foldF1.at(t);
    const auto& b = baseline.foldF1.at(t);
    core::require(static_cast<int>(a.size()) == n && static_cast<int>(b.size()) == n,
                  "ProtocolComparison: " + t + " does not have one F1 per fold in both runs");
    Difference d;
    for (int i = 0; i < n; ++i) {
      d.candidateMean += a[i] / n;
      d.mean += (a[i] - b[i]) / n;
    }
    double ss = 0.0;
    for (int i = 0; i < n; ++i) ss += std::pow(a[i] - b[i] - d.mean, 2);
    d.foldStd = n > 1 ? std::sqrt(ss / (n - 1)) : 0.0;
    d.stdOfMean = d.foldStd * std::sqrt(1.0 / n + 1.0 / (candidate.folds - 1));  // Nadeau & Bengio 2003
    cv_[t] = d;
    if (t == "macro") {
      holdsMacro_ = d.mean >= 0.0;
      cvGain_ = cvGain_ && d.mean > d.stdOfMean;
    } else {
      harmsNoType_ = harmsNoType_ && d.mean >= -d.stdOfMean;
      cvGain_ = cvGain_ && d.mean >= 0.0;
    }
  }
  for (const auto& [name, f1] : candidate.suiteF1) {
    auto it = baseline.suiteF1.find(name);
    if (it == baseline.suiteF1.end()) continue;
    suites_[name] = {f1, it->second};
    for (const double diff : {f1.first - it->second.first, f1.second - it->second.second}) {
      if (diff > kSuiteF1Tol) raisesASuite_ = true;
      if (diff < -kSuiteF1Tol) lowersNoSuite_ = false;
    }
  }
}

std::string ProtocolComparison::format() const {
  char line[256];
  std::string out = "pooled CV (F1 %): candidate mean, paired difference +- per-fold std (std of the mean)\n";
  for (const auto& t : kTypes) {
    const auto& d = cv_.at(t);
    std::snprintf(line, sizeof line, "  %-17s %6.2f   diff %+6.2f +- %5.2f (%4.2f)%s\n", t.c_str(), 100 * d.candidateMean,
                  100 * d.mean, 100 * d.foldStd, 100 * d.stdOfMean,
                  t != "macro" && d.mean < -d.stdOfMean ? "   lowered by more than its std" : "");
    out += line;
  }
  out += "capability suites (F1 %): entity (diff), relation (diff)\n";
  for (const auto& [name, cb] : suites_) {
    const auto& [c, b] = cb;
    std::snprintf(line, sizeof line, "  %-19s %6.2f (%+6.2f)   %6.2f (%+6.2f)\n", name.c_str(), 100 * c.first,
                  100 * (c.first - b.first), 100 * c.second, 100 * (c.second - b.second));
    out += line;
  }
  out += std::string("  CV: macro gain above its std, no type lower: ") + (cvGain_ ? "yes" : "no") + "\n";
  out += std::string("  (a) raises a suite: ") + (raisesASuite_ ? "yes" : "no") +
         ", lowers none: " + (lowersNoSuite_ ? "yes" : "no") + "\n  (b) no type lowered by more than its std: " +
         (harmsNoType_ ? "yes" : "no") + "\n  (c) 7-type mean held: " + (holdsMacro_ ? "yes" : "no") +
         "\n  verdict: " +
         (keptByCrossValidation() ? "kept (CV)" : keptByCapability() ? "kept (capability: a, b, c)" : "not kept") + "\n";
  return out;
}

nlohmann::json toJson(const RepeatedCrossValidation& cv, const std::vector<std::vector<CapabilitySuites::Result>>& suites) {
  nlohmann::json j = toJson(cv);
  for (size_t v = 0; v < suites.size() && v < cv.variantNames.size(); ++v)
    if (!suites[v].empty()) j["variants"][cv.variantNames[v]]["capabilities"] = CapabilitySuites::toJson(suites[v]);
  return j;
}

}  // namespace srp::language
