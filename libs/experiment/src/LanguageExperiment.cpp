// `srp experiment language`: the Language Module against SpERT (thesis tables
// 5.7, D.1-D.3) on the validation split, per source corpus, and the plans of the
// five Appendix A test instructions (section 8.2).
#include <algorithm>
#include <map>

#include "srp/core/Error.h"
#include "srp/core/Json.h"
#include "srp/experiment/Experiments.h"
#include "srp/experiment/ExperimentSupport.h"
#include "srp/language/InstructionParser.h"
#include "srp/language/LanguageModel.h"
#include "srp/language/SpertEvaluation.h"

namespace srp::experiment {
namespace {

/// SpERT's published precision, recall, F1 [%] for one type.
struct SpertRow
{
  double precision, recall, f1;
};

/// Our type name, the thesis' row name.
const std::vector<std::pair<std::string, std::string>> kTypes{
    {"Action", "action"},          {"Trajector", "trajector"}, {"SpatialIndicator", "spatial indicator"},
    {"GoalIndicator", "goal indicator"}, {"Color", "color"},  {"Spatial", "spatial relation"},
    {"Transition", "move relation"}};

// Thesis table 5.7 (validation, combined corpus) and tables D.1-D.3 (validation per corpus).
const std::map<std::string, SpertRow> kTable57{
    {"Action", {99.13, 99.13, 99.13}},          {"Trajector", {86.76, 81.94, 84.29}},
    {"SpatialIndicator", {82.28, 83.33, 82.80}}, {"GoalIndicator", {81.82, 90.00, 85.71}},
    {"Color", {94.86, 97.19, 96.01}},           {"Spatial", {73.75, 76.62, 75.16}},
    {"Transition", {80.30, 86.89, 83.46}}};
const std::map<std::string, SpertRow> kTableD1SemEval{
    {"Action", {99.31, 98.62, 98.96}},          {"Trajector", {87.80, 94.74, 91.14}},
    {"SpatialIndicator", {90.70, 92.86, 91.76}}, {"GoalIndicator", {94.25, 98.80, 96.47}},
    {"Color", {97.85, 99.13, 98.40}},           {"Spatial", {82.22, 90.24, 86.05}},
    {"Transition", {89.53, 91.67, 90.59}}};
const std::map<std::string, SpertRow> kTableD2HuRIC{
    {"Action", {98.08, 100.0, 99.03}},          {"Trajector", {85.00, 80.95, 82.93}},
    {"SpatialIndicator", {89.66, 100.0, 94.55}}, {"GoalIndicator", {100.0, 95.24, 97.56}},
    {"Spatial", {73.33, 84.62, 78.57}},         {"Transition", {95.00, 90.48, 92.68}}};
const std::map<std::string, SpertRow> kTableD3HuRCM{
    {"Action", {99.14, 99.14, 99.14}},          {"Trajector", {89.13, 95.35, 92.13}},
    {"SpatialIndicator", {81.82, 93.75, 87.38}}, {"Color", {93.68, 94.77, 94.22}},
    {"Spatial", {79.25, 87.50, 83.17}}};

std::string percent(double value) { return formatNumber(value, 2); }

ResultTable scoreTable(const std::string& title, const language::SpertScores& ours,
                       const std::map<std::string, SpertRow>& thesis, const std::string& note)
{
  ResultTable table;
  table.title = title;
  table.columns = {"type", "SpERT P", "SpERT R", "SpERT F1", "ours P", "ours R", "ours F1", "support"};
  for (const auto& [type, thesisName] : kTypes) {
    const auto it = ours.types.find(type);
    const language::TypeScore score = it == ours.types.end() ? language::TypeScore{} : it->second;
    const auto th = thesis.find(type);
    const bool hasThesis = th != thesis.end();
    if (score.support() == 0 && score.falsePositives == 0 && !hasThesis) continue;  // type absent from this corpus
    const bool scored = score.support() + score.falsePositives > 0;
    table.rows.push_back({thesisName + " (" + type + ")", hasThesis ? percent(th->second.precision) : "—",
                          hasThesis ? percent(th->second.recall) : "—", hasThesis ? percent(th->second.f1) : "—",
                          scored ? percent(100.0 * score.precision()) : "—",
                          scored ? percent(100.0 * score.recall()) : "—", scored ? percent(100.0 * score.f1()) : "—",
                          std::to_string(score.support())});
  }
  table.note = note;
  return table;
}

nlohmann::json scoresJson(const language::SpertScores& scores) { return language::toJson(scores); }

/// Sentence ranges of val.json per source corpus (datasets/language/val_origin.json).
std::vector<std::pair<std::string, std::pair<int, int>>> corpusRanges(
    const std::filesystem::path& originPath, const std::vector<language::AnnotatedSentence>& gold)
{
  const nlohmann::json origin = core::readJsonFile(originPath.string());
  std::vector<std::pair<std::string, std::pair<int, int>>> ranges;
  int covered = 0;
  for (const auto& r : core::requireField(origin, "ranges", originPath.string())) {
    const std::string corpus = r.at("corpus").get<std::string>();
    const int first = r.at("first").get<int>(), last = r.at("last").get<int>();
    if (first < 0 || last >= static_cast<int>(gold.size()) || first > last ||
        r.at("first_tokens").get<std::vector<std::string>>() != gold[static_cast<size_t>(first)].tokens)
      throw core::InvalidInputError(originPath.string() + ": range of " + corpus +
                                    " does not match val.json (sentence " + std::to_string(first) +
                                    "); update the ranges when val.json changes");
    covered += last - first + 1;
    ranges.push_back({corpus, {first, last}});
  }
  if (covered != static_cast<int>(gold.size()))
    throw core::InvalidInputError(originPath.string() + ": the ranges cover " + std::to_string(covered) + " of " +
                                  std::to_string(gold.size()) + " val.json sentences; give every sentence one corpus");
  return ranges;
}

/// Table 5.7 beside the pooled cross-validation of the shipped configuration (`cv`: cv_scores.json);
/// `beaten` counts the types where ours is above SpERT; metrics["cv"] receives ours.
ResultTable crossValidationTable(const nlohmann::json& cv, const nlohmann::json& cvBaseline, int& beaten,
                                 nlohmann::json& metrics)
{
  ResultTable cvTable;
  cvTable.title = "Table 5.7: entities and relations, pooled cross-validation of train+val (" +
                  std::to_string(cv.at("folds").get<int>()) + " folds x " + std::to_string(cv.at("seeds").get<int>()) +
                  " seeds), F1 %";
  cvTable.columns = {"type", "SpERT F1 (val)", "ours F1 (CV mean)", "ours F1 std"};
  for (const auto& [type, thesisName] : kTypes) {
    if (!cvBaseline.contains(type)) continue;
    const double mean = 100.0 * cvBaseline.at(type).at("f1_mean").get<double>();
    const double spert = kTable57.at(type).f1;
    beaten += mean > spert;
    cvTable.rows.push_back({thesisName + " (" + type + ")", percent(spert), percent(mean),
                            percent(100.0 * cvBaseline.at(type).at("f1_std").get<double>())});
    metrics["cv"][type] = {{"f1_mean", mean / 100.0}, {"f1_std", cvBaseline.at(type).at("f1_std")}};
  }
  cvTable.note =
      "SpERT: thesis table 5.7 (fine-tuned BERT, validation split). Ours: the shipped configuration cross-validated "
      "on the 1165 pooled sentences (datasets/language/model/cv_scores.json, written by 'srp train-language --cv'); "
      "SpERT scoring (exact span + type; relation = type + both entities).";
  return cvTable;
}

/// Section 8.2: the plans the parser gives for Appendix A's test instructions against the expected ones;
/// `instructionsRight` counts the plans right; metrics["appendix_a"] receives each.
ResultTable appendixPlansTable(const std::string& modelPath, const std::string& appendixPath, int& instructionsRight,
                               nlohmann::json& metrics)
{
  const language::InstructionParser parser(modelPath);
  const nlohmann::json appendix = core::readJsonFile(appendixPath);
  ResultTable plans;
  plans.title = "Section 8.2: plans of the Appendix A test instructions (steps with object / source / target right)";
  plans.columns = {"instruction", "steps expected", "steps found", "objects", "sources", "targets", "thesis", "ours"};
  int index = 0;
  for (const auto& item : core::requireField(appendix, "instructions", appendixPath)) {
    ++index;
    const auto plan = parser.parse(item.at("instruction").get<std::string>());
    // The expected steps are in the plan's own JSON step format.
    const auto expected = language::taskPlanFromJson({{"steps", item.at("expected_steps")}}).steps;
    int objects = 0, sources = 0, targets = 0;
    for (size_t s = 0; s < expected.size() && s < plan.steps.size(); ++s) {
      objects += plan.steps[s].object == expected[s].object;
      sources += plan.steps[s].source == expected[s].source;
      targets += plan.steps[s].target == expected[s].target;
    }
    const int n = static_cast<int>(expected.size());
    const bool right = static_cast<int>(plan.steps.size()) == n && objects == n && sources == n && targets == n;
    instructionsRight += right;
    const auto frac = [n](int k) { return std::to_string(k) + "/" + std::to_string(n); };
    plans.rows.push_back({std::to_string(index), std::to_string(n), std::to_string(plan.steps.size()), frac(objects),
                          frac(sources), frac(targets), "right", right ? "right" : "wrong"});
    metrics["appendix_a"].push_back({{"instruction", index},
                                            {"steps_expected", n},
                                            {"steps_found", plan.steps.size()},
                                            {"objects_right", objects},
                                            {"sources_right", sources},
                                            {"targets_right", targets},
                                            {"plan_right", right},
                                            {"plan", language::toJson(plan)}});
  }
  plans.note =
      "Thesis section 8.2: \"the syntactic dependency parser achieves complete accuracy\" on these instructions (its "
      "table 8.1 scores SpERT's entities on them against an annotation that was not published, so it is not "
      "reproduced here). Expected plans: datasets/language/appendix_a.json.";
  return plans;
}

}  // namespace

ExperimentResult runLanguageExperiment(const ExperimentOptions& options)
{
  const WallClock clock;
  ExperimentResult result;
  result.name = "language";
  const auto data = datasetsDirOf(options) / "language";
  const auto valPath = data / "val.json";
  const auto originPath = data / "val_origin.json";
  const auto modelPath = data / "model" / "language_model.dat";
  const auto appendixPath = data / "appendix_a.json";
  requireDataset(valPath, "it is the SpERT validation split shipped in the repo (datasets/language/README.md); restore it from git");
  requireDataset(originPath, "it lists the source corpus of each val.json sentence; restore it from git");
  requireDataset(modelPath, "train the model with 'srp train-language' (about 10 s)");
  requireDataset(appendixPath, "it holds the thesis' Appendix A instructions and their plans; restore it from git");
  const auto cvPath = data / "model" / "cv_scores.json";
  requireDataset(cvPath, "it is the pooled cross-validation of the shipped configuration; write it with 'srp "
                         "train-language --cv 5 --cv-seeds 3 --cv-json datasets/language/model/cv_scores.json'");

  reportProgress(options, "language: scoring val.json", 0.0);
  const auto model = language::LanguageModel::load(modelPath.string());
  const auto gold = language::readSpertCorpus(valPath.string());
  std::vector<language::AnnotatedSentence> predicted;
  predicted.reserve(gold.size());
  for (const auto& s : gold) predicted.push_back(model.annotate(s.tokens));
  const auto all = language::scoreSpert(gold, predicted);

  // The shipped model is trained on train+val, so its own score on val.json is a training score: the figure
  // to set beside SpERT's validation row is the pooled cross-validation (libs/language/README.md, Protocol).
  const nlohmann::json cv = core::readJsonFile(cvPath.string());
  const nlohmann::json& cvBaseline = core::requireField(cv.at("variants"), "baseline", cvPath.string());
  int beaten = 0;
  result.tables.push_back(crossValidationTable(cv, cvBaseline, beaten, result.metrics));
  result.tables.push_back(scoreTable(
      "Training-set check: the shipped model on val.json (" + std::to_string(gold.size()) +
          " sentences, part of its training data; not a validation figure), %",
      all, kTable57, "SpERT: thesis table 5.7 (validation). Ours: the shipped model on sentences it was trained on."));
  result.metrics["val_training_set"] = scoresJson(all);

  const std::map<std::string, std::pair<const std::map<std::string, SpertRow>*, std::string>> perCorpusThesis{
      {"SemEval", {&kTableD1SemEval, "Table D.1: SemEval-2014 Task 6"}},
      {"HuRIC", {&kTableD2HuRIC, "Table D.2: HuRIC"}},
      {"HuRCM", {&kTableD3HuRCM, "Table D.3: HuRCM"}}};
  const auto firstCorpusTable = result.tables.size();
  for (const auto& [corpus, range] : corpusRanges(originPath, gold)) {
    const auto first = gold.begin() + range.first, last = gold.begin() + range.second + 1;
    const std::vector<language::AnnotatedSentence> g(first, last);
    const std::vector<language::AnnotatedSentence> p(predicted.begin() + range.first,
                                                     predicted.begin() + range.second + 1);
    const auto scores = language::scoreSpert(g, p);
    const auto th = perCorpusThesis.at(corpus);
    result.tables.push_back(scoreTable(
        th.second + ", validation sentences of this corpus (" + std::to_string(g.size()) + "), %", scores, *th.first,
        "SpERT: thesis " + th.second.substr(0, th.second.find(':')) +
            " (SpERT trained and validated on this corpus alone; ours: the one model trained on the pooled "
            "corpus, scored on this corpus' part of val.json, which is in its training data: a training-set check, "
            "datasets/language/val_origin.json)."));
    result.metrics["per_corpus"][corpus] = scoresJson(scores);
    result.metrics["per_corpus"][corpus]["sentences"] = g.size();
  }
  // In the thesis' order: D.1 SemEval, D.2 HuRIC, D.3 HuRCM.
  std::sort(result.tables.begin() + static_cast<std::ptrdiff_t>(firstCorpusTable), result.tables.end(),
            [](const ResultTable& a, const ResultTable& b) { return a.title < b.title; });
  reportProgress(options, "language: Appendix A plans", 0.8);

  // Section 8.2: the syntactic stage on the five test instructions of Appendix A.
  int instructionsRight = 0;
  result.tables.push_back(appendixPlansTable(modelPath.string(), appendixPath.string(), instructionsRight, result.metrics));
  result.metrics["appendix_a_right"] = instructionsRight;

  const auto f1 = [&](const char* type) { return 100.0 * cvBaseline.at(type).at("f1_mean").get<double>(); };
  result.summary = "Pooled-CV F1 above SpERT's validation F1 for " + std::to_string(beaten) + " of 7 types (Trajector " +
                   formatNumber(f1("Trajector"), 1) + " vs 84.3, SpatialIndicator " +
                   formatNumber(f1("SpatialIndicator"), 1) + " vs 82.8, Spatial relation " +
                   formatNumber(f1("Spatial"), 1) + " vs 75.2); Appendix A plans right: " +
                   std::to_string(instructionsRight) + "/5.";
  result.wallTime_s = clock.seconds();
  return result;
}

}  // namespace srp::experiment
