// srp train-language: trains the Language Module's entity/relation model on the
// corpus and writes the model file that `srp parse` loads.
#include <chrono>
#include <iostream>
#include <set>
#include <vector>

#include "CommandRegistry.h"
#include "srp/core/Json.h"
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
  auto cvFolds = std::make_shared<int>(0);
  auto cvThreads = std::make_shared<int>(2);
  auto cvPredictions = std::make_shared<std::string>();
  app.add_option("--cv", *cvFolds, "only cross-validate on the training corpus with this many folds (no model written)");
  app.add_option("--cv-threads", *cvThreads, "folds trained in parallel")->capture_default_str();
  app.add_option("--cv-predictions", *cvPredictions, "write the out-of-fold predictions (SpERT JSON) here");
  auto cvErrors = std::make_shared<bool>(false);
  auto errorTypes = std::make_shared<std::vector<std::string>>();
  app.add_flag("--errors", *cvErrors, "with --cv: also print the out-of-fold entity errors");
  app.add_option("--error-types", *errorTypes, "entity types of the error dump (default: all)")->delimiter(',');
  app.callback([=] {
    const auto corpus = srp::language::readSpertCorpus(*trainPath);
    if (*cvFolds > 0) {
      std::cerr << *cvFolds << "-fold cross-validation on " << corpus.size() << " sentences...\n";
      const auto cv = srp::language::crossValidate(corpus, *options, *cvFolds, *cvThreads);
      if (!cvPredictions->empty()) {
        nlohmann::json out = nlohmann::json::array();
        for (const auto& s : cv.predictions) out.push_back(srp::language::toJson(s));
        srp::core::writeJsonFile(*cvPredictions, out);
      }
      std::cout << *cvFolds << "-fold cross-validation (" << *trainPath << "):\n"
                << srp::language::formatScoreTable(cv.scores);
      if (*cvErrors)
        std::cout << srp::language::formatEntityErrors(corpus, cv.predictions,
                                                       std::set<std::string>(errorTypes->begin(), errorTypes->end()));
      return;
    }
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
