// srp train-language: trains the Language Module's entity/relation model on the
// corpus and writes the model file that `srp parse` loads.
#include <chrono>
#include <iostream>

#include "CommandRegistry.h"
#include "srp/language/LanguageModel.h"
#include "srp/language/SpertEvaluation.h"

namespace {
void setupTrainLanguage(CLI::App& app) {
  auto trainPath = std::make_shared<std::string>(std::string(SRP_DATASETS_DIR) + "/language/train.json");
  auto valPath = std::make_shared<std::string>(std::string(SRP_DATASETS_DIR) + "/language/val.json");
  auto outPath = std::make_shared<std::string>(srp::language::defaultModelPath());
  app.add_option("--train", *trainPath, "SpERT training corpus")->capture_default_str();
  app.add_option("--val", *valPath, "SpERT validation corpus, scored after training")->capture_default_str();
  app.add_option("--out", *outPath, "model file to write")->capture_default_str();
  auto options = std::make_shared<srp::language::LanguageTrainingOptions>();
  app.add_option("--entity-c", options->entityC, "entity tagger SVM C")->capture_default_str();
  app.add_option("--relation-c", options->relationC, "relation classifier SVM C")->capture_default_str();
  app.add_option("--min-feature-count", options->minFeatureCount, "drop rarer entity features")->capture_default_str();
  app.callback([=] {
    const auto corpus = srp::language::readSpertCorpus(*trainPath);
    std::cerr << "training on " << corpus.size() << " sentences...\n";
    const auto t0 = std::chrono::steady_clock::now();
    const auto model = srp::language::LanguageModel::train(corpus, *options);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    model.save(*outPath);
    std::cout << "trained in " << seconds << " s, wrote " << *outPath << "\n";
    if (!valPath->empty()) {
      std::cout << "validation (" << *valPath << "):\n"
                << srp::language::formatScoreTable(
                       srp::language::evaluateModel(model, srp::language::readSpertCorpus(*valPath)));
    }
  });
}
const srp::app::CommandRegistrar kReg{"train-language", "Train the instruction entity/relation model on the corpus", 21,
                                      setupTrainLanguage};
}  // namespace
