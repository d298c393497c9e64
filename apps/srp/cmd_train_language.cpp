// srp train-language: trains the Language Module's entity/relation model on the
// pooled corpus and writes the model file that `srp parse` loads; with --cv runs
// the pooled cross-validation protocol instead, with the capability suites and
// the protocol's verdict on each variant (libs/language/README.md "Protocol").
#include <chrono>
#include <iostream>
#include <set>
#include <sstream>
#include <vector>

#include "CommandRegistry.h"
#include "CommonOptions.h"
#include "LanguageSwitches.h"
#include "srp/core/DataPaths.h"
#include "srp/core/Error.h"
#include "srp/core/Json.h"
#include "srp/core/OutputFile.h"
#include "srp/language/CapabilitySuites.h"
#include "srp/language/LanguageModel.h"
#include "srp/language/ProtocolComparison.h"
#include "srp/language/SpertEvaluation.h"
#include "srp/language/SyntheticCommandGrammar.h"

namespace {

void setupTrainLanguage(CLI::App& app) {
  auto trainPaths = std::make_shared<std::vector<std::string>>();
  auto scorePath = std::make_shared<std::string>();
  auto outPath = std::make_shared<std::string>("language_model.dat");
  app.add_option("--train", *trainPaths,
                 "SpERT corpora, pooled for training and cross-validation (default: the shipped "
                 "datasets/language/train.json and val.json of srp's data folder)");
  app.add_option("--score", *scorePath, "SpERT corpus scored after training (not for choosing anything)");
  app.add_option("-o,--out", *outPath, "model file to write (use it with 'srp parse --model FILE')")
      ->capture_default_str();
  auto json = std::make_shared<bool>(false);
  app.add_flag("--json", *json,
               "print the result as JSON: with --cv the summary --cv-json writes, else the model file, the corpus size "
               "and the training time");
  auto options = std::make_shared<srp::language::LanguageModel::Options>();
  app.add_option("--entity-c", options->entityC, "entity tagger SVM C")->capture_default_str();
  app.add_option("--relation-c", options->relationC, "relation classifier SVM C")->capture_default_str();
  app.add_option("--min-feature-count", options->minFeatureCount, "drop rarer entity features")->capture_default_str();
  auto rules = std::make_shared<std::vector<std::string>>();
  auto features = std::make_shared<std::vector<std::string>>();
  app.add_option("--rules", *rules,
                 "decoding rule switches, e.g. span_lengths=0,source_is_spatial=1; rules: " +
                     srp::app::switchNames<srp::language::DecodingRules>())
      ->delimiter(',');
  app.add_option("--features", *features,
                 "tagger feature groups, e.g. source_goal_role=1; groups: " +
                     srp::app::switchNames<srp::language::FeatureGroups>())
      ->delimiter(',');
  app.add_option("--synthetic-ratio", options->syntheticRatio,
                 "synthetic commands added to training per real sentence (SyntheticCommandGrammar)")
      ->capture_default_str();
  app.add_option("--synthetic-seed", options->syntheticSeed, "seed of the synthetic commands")->capture_default_str();
  auto cvFolds = std::make_shared<int>(0);
  auto cvSeeds = std::make_shared<int>(3);
  auto cvThreads = std::make_shared<int>(2);
  auto cvPredictions = std::make_shared<std::string>();
  auto cvJson = std::make_shared<std::string>();
  auto ablate = std::make_shared<bool>(false);
  app.add_option("--cv", *cvFolds, "only run the pooled protocol with this many folds (no model written)");
  app.add_option("--cv-seeds", *cvSeeds, "repetitions of the k-fold split (seeds 1..n)")->capture_default_str();
  app.add_option("--cv-threads", *cvThreads, "folds trained in parallel")->capture_default_str();
  app.add_option("--cv-predictions", *cvPredictions, "write the first seed's out-of-fold predictions (SpERT JSON)");
  app.add_option("--cv-json", *cvJson, "write the CV summary (mean, std, paired differences) as JSON");
  app.add_flag("--ablate", *ablate, "with --cv: also score each decoding rule switched the other way");
  auto cvErrors = std::make_shared<bool>(false);
  auto errorTypes = std::make_shared<std::vector<std::string>>();
  app.add_flag("--errors", *cvErrors, "with --cv: also print the first seed's out-of-fold entity errors");
  app.add_option("--error-types", *errorTypes, "entity types of the error dump (default: all)")->delimiter(',');
  auto capabilitiesDir = std::make_shared<std::string>();  // empty: the shipped suites
  app.add_option("--capabilities-dir", *capabilitiesDir,
                 "capability suites scored after training, and in --cv mode for each variant (a model trained on "
                 "the whole pooled corpus; default: the shipped datasets/language/capabilities of srp's data folder)");
  auto compareTo = std::make_shared<std::string>();
  app.add_option("--compare-to", *compareTo,
                 "with --cv: a --cv-json file of an earlier run (same folds and seeds); prints the protocol's verdict "
                 "on this run's options against that run's")
      ->check(CLI::ExistingFile);
  auto syntheticOut = std::make_shared<std::string>();
  auto syntheticCount = std::make_shared<int>(200);
  app.add_option("--write-synthetic", *syntheticOut, "only write synthetic commands (SpERT JSON) to this file");
  app.add_option("--synthetic-count", *syntheticCount, "how many, for --write-synthetic")->capture_default_str();
  auto overwrite = std::make_shared<bool>(false);
  srp::app::addOverwriteFlag(app, *overwrite);
  app.callback([=] {
    std::vector<srp::core::PathRole> inputs = {{"--score", *scorePath}};
    for (const auto& p : *trainPaths) inputs.push_back({"--train", p});
    std::vector<srp::core::PathRole> outputs = {{"--write-synthetic", *syntheticOut}};
    if (syntheticOut->empty() && *cvFolds > 0)
      outputs = {{"--cv-predictions", *cvPredictions}, {"--cv-json", *cvJson}};
    else if (syntheticOut->empty())
      outputs = {{"--out", *outPath}};
    srp::core::checkOutputPaths(outputs, inputs, *overwrite);
    srp::app::applySwitches(*rules, options->rules, "decoding rule");
    srp::app::applySwitches(*features, options->features, "feature group");
    if (!syntheticOut->empty()) {
      nlohmann::json out = nlohmann::json::array();
      for (const auto& s : srp::language::SyntheticCommandGrammar().generate(
               static_cast<size_t>(std::max(0, *syntheticCount)), options->syntheticSeed))
        out.push_back(srp::language::toJson(s));
      srp::core::writeJsonFile(*syntheticOut, out);
      std::cout << "wrote " << out.size() << " synthetic commands to " << *syntheticOut << "\n";
      return;
    }
    if (trainPaths->empty())
      for (const char* split : {"train.json", "val.json"})
        trainPaths->push_back(srp::core::DataPaths::file(std::string("datasets/language/") + split).string());
    if (capabilitiesDir->empty()) *capabilitiesDir = srp::language::CapabilitySuites::defaultFolder();
    const auto suites = srp::language::CapabilitySuites::load(*capabilitiesDir);
    std::vector<srp::language::AnnotatedSentence> corpus;
    for (const auto& path : *trainPaths) {
      const auto part = srp::language::readSpertCorpus(path);
      corpus.insert(corpus.end(), part.begin(), part.end());
    }
    if (*cvFolds > 0) {
      std::vector<std::pair<std::string, srp::language::DecodingRules>> variants;
      if (*ablate)
        for (const auto& [name, member] : srp::language::DecodingRules::all()) {
          auto r = options->rules;
          r.*member = !(r.*member);
          variants.push_back({name + ((r.*member) ? "=1" : "=0"), r});
        }
      const nlohmann::json earlier = compareTo->empty() ? nlohmann::json() : srp::core::readJsonFile(*compareTo);
      if (!srp::app::quietFlag())
        std::cerr << *cvFolds << "-fold x " << *cvSeeds << " cross-validation on " << corpus.size()
                  << " pooled sentences...\n";
      const auto cv = srp::language::repeatedCrossValidate(corpus, *options, *cvFolds, *cvSeeds, *cvThreads, variants);
      // The suites are scored by one model trained on the whole pooled corpus, under each variant's rules.
      if (!srp::app::quietFlag())
        std::cerr << "training on " << corpus.size() << " pooled sentences for the capability suites...\n";
      auto full = srp::language::LanguageModel::train(corpus, *options);
      std::vector<std::vector<srp::language::CapabilitySuites::Result>> suiteResults{suites.score(full)};
      for (const auto& variant : variants) {
        full.setDecodingRules(variant.second);
        suiteResults.push_back(suites.score(full));
      }
      if (!cvPredictions->empty()) {
        nlohmann::json out = nlohmann::json::array();
        for (const auto& s : cv.firstSeedPredictions) out.push_back(srp::language::toJson(s));
        srp::core::writeJsonFile(*cvPredictions, out);
      }
      if (!cvJson->empty()) srp::core::writeJsonFile(*cvJson, srp::language::toJson(cv, suiteResults));
      if (*json) {
        std::cout << srp::language::toJson(cv, suiteResults).dump(2) << "\n";
        return;
      }
      std::cout << "pooled corpus:";
      for (const auto& p : *trainPaths) std::cout << " " << p;
      std::cout << " (" << corpus.size() << " sentences)\n" << srp::language::formatCrossValidation(cv);
      std::cout << "\ncapability suites (" << *capabilitiesDir << "), model trained on the pooled corpus:\n"
                << srp::language::CapabilitySuites::formatTable(suiteResults[0]);
      using Comparison = srp::language::ProtocolComparison;
      const auto baseline = Comparison::Configuration::fromCrossValidation(cv, 0, suiteResults[0]);
      // Each ablation is judged as "rule on" against "rule off", the other rules as given.
      for (size_t v = 1; v < cv.variantNames.size(); ++v) {
        const auto variant = Comparison::Configuration::fromCrossValidation(cv, v, suiteResults[v]);
        const std::string& name = cv.variantNames[v];
        const bool switchedOn = name.size() > 2 && name.compare(name.size() - 2, 2, "=1") == 0;
        std::cout << "\nprotocol, " << name.substr(0, name.find('=')) << " on against off (other rules as given):\n"
                  << (switchedOn ? Comparison(variant, baseline) : Comparison(baseline, variant)).format();
      }
      if (!earlier.is_null())
        std::cout << "\nprotocol, these options against " << *compareTo << ":\n"
                  << Comparison(baseline, Comparison::Configuration::fromJson(earlier, "baseline")).format();
      if (*cvErrors)
        std::cout << srp::language::formatEntityErrors(corpus, cv.firstSeedPredictions,
                                                       std::set<std::string>(errorTypes->begin(), errorTypes->end()));
      return;
    }
    if (!srp::app::quietFlag()) std::cerr << "training on " << corpus.size() << " pooled sentences...\n";
    const auto t0 = std::chrono::steady_clock::now();
    const auto model = srp::language::LanguageModel::train(corpus, *options);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    model.save(*outPath);
    if (*json) {
      std::cout << nlohmann::json{{"model", *outPath}, {"sentences", corpus.size()}, {"train_s", seconds}}.dump(2)
                << "\n";
      return;
    }
    std::cout << "trained in " << seconds << " s, wrote " << *outPath << "\n"
              << "capability suites (" << *capabilitiesDir << "):\n"
              << srp::language::CapabilitySuites::formatTable(suites.score(model));
    if (!scorePath->empty())
      std::cout << "scores on " << *scorePath << ":\n"
                << srp::language::formatScoreTable(
                       srp::language::evaluateModel(model, srp::language::readSpertCorpus(*scorePath)));
  });
}
const srp::app::CommandRegistrar kReg{"train-language", "Train the instruction entity/relation model on the corpus", 21,
                                      setupTrainLanguage};
}  // namespace
