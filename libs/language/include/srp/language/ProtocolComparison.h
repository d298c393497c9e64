#pragma once
/// \file ProtocolComparison.h
/// \brief The decision rule of the language model's protocol (libs/language/README.md
/// "Protocol"): is a candidate configuration kept against a baseline?
///
/// A rule, feature group or other change is kept when CV alone shows it: its paired
/// macro gain exceeds the standard deviation of that mean and no type's mean falls
/// (the rule for the corpus' own regularities and for learned hyper-parameters); or,
/// for a change aimed at a capability, when
/// - (a) it raises a capability suite's F1 (entity or relation F1, CapabilitySuites)
///   and lowers no suite's entity or relation F1;
/// - (b) it lowers no type's pooled-CV F1 by more than the standard deviation of
///   that type's mean paired difference (15 per-fold differences, same splits,
///   corrected for the overlap of the training sets: Nadeau & Bengio 2003);
/// - (c) the mean F1 of the seven types ("macro") does not fall in CV.
///
/// Example:
/// \code
///   const auto base = ProtocolComparison::Configuration::fromJson(core::readJsonFile("base_cv.json"), "baseline");
///   const auto cand = ProtocolComparison::Configuration::fromCrossValidation(cv, 0, suiteResults);
///   const ProtocolComparison c(cand, base);
///   std::cout << c.format();  // per-type CV difference, per-suite difference, (a) (b) (c), verdict
/// \endcode

#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "srp/language/CapabilitySuites.h"
#include "srp/language/SpertEvaluation.h"

namespace srp::language {

class ProtocolComparison {
 public:
  /// What the protocol knows of one configuration: per type (and "macro") the
  /// F1 of each CV fold (fractions, seed-major), and per suite the entity and
  /// relation F1 of the model trained on the whole pooled corpus.
  struct Configuration {
    std::map<std::string, std::vector<double>> foldF1;
    std::map<std::string, std::pair<double, double>> suiteF1;  ///< suite -> (entity F1, relation F1)
    int folds = 0, seeds = 0;

    /// Variant `variant` of a CV run (0 = its baseline) with its suite scores.
    static Configuration fromCrossValidation(const RepeatedCrossValidation& cv, size_t variant,
                                             const std::vector<CapabilitySuites::Result>& suites);
    /// A variant of `toJson(cv, suites)` (as written by `srp train-language --cv-json`).
    /// Throws InvalidInputError naming the missing variant or field.
    static Configuration fromJson(const nlohmann::json& cvJson, const std::string& variant);
  };

  /// Throws InvalidInputError when the two were not scored on the same folds and seeds.
  ProtocolComparison(const Configuration& candidate, const Configuration& baseline);

  bool raisesASuite() const { return raisesASuite_; }      ///< (a), first half
  bool lowersNoSuite() const { return lowersNoSuite_; }    ///< (a), second half
  bool harmsNoType() const { return harmsNoType_; }        ///< (b)
  bool holdsTheMacroMean() const { return holdsMacro_; }   ///< (c)
  /// The CV rule: macro gain above the std of its mean, no type's mean lower.
  bool keptByCrossValidation() const { return cvGain_; }
  /// (a), (b) and (c).
  bool keptByCapability() const { return raisesASuite_ && lowersNoSuite_ && harmsNoType_ && holdsMacro_; }
  bool kept() const { return keptByCrossValidation() || keptByCapability(); }

  /// Per type: candidate mean, paired difference mean, its per-fold std and the
  /// std of its mean; per suite: entity and relation F1 and their differences;
  /// then the CV rule, (a), (b), (c) and the verdict.
  std::string format() const;

 private:
  struct Difference {
    double candidateMean = 0, mean = 0, foldStd = 0, stdOfMean = 0;
  };
  std::map<std::string, Difference> cv_;
  std::map<std::string, std::pair<std::pair<double, double>, std::pair<double, double>>> suites_;  // (cand, base)
  bool raisesASuite_ = false, lowersNoSuite_ = true, harmsNoType_ = true, holdsMacro_ = true, cvGain_ = true;
};

/// `toJson(cv)` with each variant's suite scores added under "capabilities"
/// (`suites[v]` for variant v; variants without scores are left as they are).
nlohmann::json toJson(const RepeatedCrossValidation& cv, const std::vector<std::vector<CapabilitySuites::Result>>& suites);

}  // namespace srp::language
