// srp eval-language: scores the language model on a SpERT corpus (precision,
// recall, F1 and support per entity and relation type; time per sentence), or
// on the capability suites (entity and relation F1 per suite).
#include <fstream>
#include <iostream>
#include <set>
#include <vector>

#include "CommandRegistry.h"
#include "LanguageSwitches.h"
#include "srp/core/Json.h"
#include "srp/core/OutputFile.h"
#include "srp/language/AnnotationPrecedents.h"
#include "srp/language/CapabilitySuites.h"
#include "srp/language/LanguageModel.h"
#include "srp/language/SpertEvaluation.h"

namespace {
void setupEvalLanguage(CLI::App& app) {
  auto dataPath = std::make_shared<std::string>();
  auto modelPath = std::make_shared<std::string>();
  auto predictionsPath = std::make_shared<std::string>();
  auto json = std::make_shared<bool>(false);
  auto capabilities = std::make_shared<bool>(false);
  auto capabilitiesDir = std::make_shared<std::string>();  // empty: the shipped suites
  auto* input = app.add_option_group("input", "what to score (one of)");
  input->add_option("--data", *dataPath, "SpERT corpus to score (e.g. datasets/language/val.json)")
      ->check(CLI::ExistingFile);
  input->add_flag("--capabilities", *capabilities,
                  "score every capability suite of --capabilities-dir instead (entity and relation F1 per suite)");
  input->require_option(1);
  app.add_option("--capabilities-dir", *capabilitiesDir,
                 "folder of capability suites (<name>.json, SpERT format; default: the shipped "
                 "datasets/language/capabilities of srp's data folder)");
  app.add_option("--model", *modelPath,
                 "language model file (default: the shipped datasets/language/model/language_model.dat of srp's data folder)");
  auto rules = std::make_shared<std::vector<std::string>>();
  app.add_option("--rules", *rules,
                 "decoding rules switched from the model's own, e.g. source_is_spatial=1,span_lengths=0; rules: " +
                     srp::app::switchNames<srp::language::DecodingRules>())
      ->delimiter(',');
  app.add_option("--predictions", *predictionsPath, "also write the predicted sentences (SpERT JSON) here");
  app.add_flag("--json", *json, "print {\"types\": {...}, \"ms_per_sentence\": x}");
  auto errorTypes = std::make_shared<std::vector<std::string>>();
  auto errors = std::make_shared<bool>(false);
  app.add_flag("--errors", *errors, "also print the entity errors: counts per kind, gold vs predicted spans per sentence");
  app.add_option("--error-types", *errorTypes, "entity types of the error dump (default: all)")->delimiter(',');
  auto precedentsPath = std::make_shared<std::string>();
  app.add_option("--precedents", *precedentsPath,
                 "SpERT corpus (e.g. train.json) to check each error against: how it annotates the same 7 words, "
                 "and the scores if the scored corpus followed it where the model did")
      ->check(CLI::ExistingFile);
  auto overwrite = std::make_shared<bool>(false);
  srp::app::addOverwriteFlag(app, *overwrite);
  app.callback([=] {
    srp::core::checkOutputPaths({{"--predictions", *predictionsPath}},
                                {{"--data", *dataPath}, {"--model", *modelPath}, {"--precedents", *precedentsPath}},
                                *overwrite);
    auto model =
        srp::language::LanguageModel::load(modelPath->empty() ? srp::language::defaultModelPath() : *modelPath);
    if (!rules->empty()) {
      auto switched = model.decodingRules();
      srp::app::applySwitches(*rules, switched, "decoding rule");
      model.setDecodingRules(switched);
    }
    if (*capabilities) {
      if (capabilitiesDir->empty()) *capabilitiesDir = srp::language::CapabilitySuites::defaultFolder();
      const auto suites = srp::language::CapabilitySuites::load(*capabilitiesDir);
      const auto results = suites.score(model);
      if (*json)
        std::cout << srp::language::CapabilitySuites::toJson(results).dump(2) << "\n";
      else
        std::cout << "capability suites of " << *capabilitiesDir << "\n"
                  << srp::language::CapabilitySuites::formatTable(results);
      if (*errors)
        for (const auto& suite : suites.suites()) {
          std::vector<srp::language::AnnotatedSentence> predicted;
          for (const auto& s : suite.sentences) predicted.push_back(model.annotate(s.tokens));
          (*json ? std::cerr : std::cout) << "suite " << suite.name << ": "
                                          << srp::language::formatEntityErrors(
                                                 suite.sentences, predicted,
                                                 std::set<std::string>(errorTypes->begin(), errorTypes->end()));
        }
      return;
    }
    const auto gold = srp::language::readSpertCorpus(*dataPath);
    const auto scores = srp::language::evaluateModel(model, gold);
    std::vector<srp::language::AnnotatedSentence> predicted;
    if (!predictionsPath->empty() || *errors || !precedentsPath->empty())
      for (const auto& s : gold) predicted.push_back(model.annotate(s.tokens));
    if (!predictionsPath->empty()) {
      nlohmann::json out = nlohmann::json::array();
      for (const auto& s : predicted) out.push_back(srp::language::toJson(s));
      srp::core::writeJsonFile(*predictionsPath, out);
    }
    if (*json)
      std::cout << srp::language::toJson(scores).dump(2) << "\n";
    else
      std::cout << gold.size() << " sentences of " << *dataPath << "\n" << srp::language::formatScoreTable(scores);
    if (*errors)
      (*json ? std::cerr : std::cout) << srp::language::formatEntityErrors(
          gold, predicted, std::set<std::string>(errorTypes->begin(), errorTypes->end()));
    if (!precedentsPath->empty()) {
      const srp::language::AnnotationPrecedents precedents(srp::language::readSpertCorpus(*precedentsPath));
      const auto check = srp::language::checkAgainstPrecedents(
          gold, predicted, precedents, std::set<std::string>(errorTypes->begin(), errorTypes->end()));
      std::ostream& out = *json ? std::cerr : std::cout;
      out << "errors against " << *precedentsPath << " (the same " << 2 * precedents.radius() + 1
          << " words, [position]):\n"
          << check.report << check.errors << " errors, " << check.withPrecedent << " with a precedent, "
          << check.againstPrecedent << " where " << *precedentsPath
          << " annotates the same words as predicted\nscores if " << *dataPath << " followed it there:\n";
      srp::language::SpertScores consistent;
      consistent.types = check.ifConsistent;
      out << srp::language::formatScoreTable(consistent);
    }
  });
}
const srp::app::CommandRegistrar kReg{"eval-language", "Score the instruction model on a SpERT corpus (P/R/F1 per type)",
                                      22, setupEvalLanguage};
}  // namespace
