// srp eval-language: scores the language model on a SpERT corpus (precision,
// recall, F1 and support per entity and relation type; time per sentence).
#include <fstream>
#include <iostream>

#include "CommandRegistry.h"
#include "srp/core/Json.h"
#include "srp/language/LanguageModel.h"
#include "srp/language/SpertEvaluation.h"

namespace {
void setupEvalLanguage(CLI::App& app) {
  auto dataPath = std::make_shared<std::string>();
  auto modelPath = std::make_shared<std::string>(srp::language::defaultModelPath());
  auto predictionsPath = std::make_shared<std::string>();
  auto json = std::make_shared<bool>(false);
  app.add_option("--data", *dataPath, "SpERT corpus to score (e.g. datasets/language/val.json)")
      ->required()
      ->check(CLI::ExistingFile);
  app.add_option("--model", *modelPath, "language model file")->capture_default_str();
  app.add_option("--predictions", *predictionsPath, "also write the predicted sentences (SpERT JSON) here");
  app.add_flag("--json", *json, "print {\"types\": {...}, \"ms_per_sentence\": x}");
  app.callback([=] {
    const auto model = srp::language::LanguageModel::load(*modelPath);
    const auto gold = srp::language::readSpertCorpus(*dataPath);
    const auto scores = srp::language::evaluateModel(model, gold);
    if (!predictionsPath->empty()) {
      nlohmann::json out = nlohmann::json::array();
      for (const auto& s : gold) out.push_back(srp::language::toJson(model.annotate(s.tokens)));
      srp::core::writeJsonFile(*predictionsPath, out);
    }
    if (*json)
      std::cout << srp::language::toJson(scores).dump(2) << "\n";
    else
      std::cout << gold.size() << " sentences of " << *dataPath << "\n" << srp::language::formatScoreTable(scores);
  });
}
const srp::app::CommandRegistrar kReg{"eval-language", "Score the instruction model on a SpERT corpus (P/R/F1 per type)",
                                      22, setupEvalLanguage};
}  // namespace
