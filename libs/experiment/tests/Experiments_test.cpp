#include "srp/experiment/Experiments.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "srp/core/Error.h"
#include "srp/core/Json.h"
#include "srp/experiment/DemoCache.h"
#include "srp/experiment/ExperimentReport.h"
#include "srp/experiment/ExperimentSupport.h"
#include "srp/language/LanguageModel.h"
#include "srp/language/SpertEvaluation.h"

using namespace srp::experiment;

namespace {

constexpr double kF1Tol_percent = 0.005;  // cells are printed with 2 decimals

std::filesystem::path testOut(const std::string& name)
{
  const auto dir = std::filesystem::path(SRP_BINARY_DIR) / "experiment_test_out" / name;
  std::filesystem::remove_all(dir);
  return dir;
}

const ResultTable& tableStartingWith(const ExperimentResult& r, const std::string& prefix)
{
  for (const auto& t : r.tables)
    if (t.title.rfind(prefix, 0) == 0) return t;
  throw std::runtime_error("no table '" + prefix + "'");
}

}  // namespace

TEST(Experiments, ListsTheSevenChapterEightExperimentsInReportOrder)
{
  std::vector<std::string> names;
  for (const auto& e : experiments()) names.push_back(e.name);
  EXPECT_EQ(names, (std::vector<std::string>{"language", "hand", "objects", "depth", "segmentation", "dmp", "execution"}));
  EXPECT_TRUE(findExperiment("dmp"));
  EXPECT_FALSE(findExperiment("all"));
  EXPECT_EQ(experimentNamesList(), "language, hand, objects, depth, segmentation, dmp, execution, all");
}

TEST(Experiments, UnknownNameListsTheValidOnes)
{
  ExperimentOptions options;
  options.outDir = testOut("unknown");
  try {
    runExperiment("nosuch", options);
    FAIL() << "no exception";
  } catch (const srp::core::InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("unknown experiment 'nosuch'; valid names: language, hand"), std::string::npos)
        << e.what();
  }
}

TEST(LanguageExperiment, MissingDatasetNamesTheFileAndHowToRestoreIt)
{
  ExperimentOptions options;
  options.outDir = testOut("missing");
  options.datasetsDir = testOut("empty_datasets");
  try {
    runLanguageExperiment(options);
    FAIL() << "no exception";
  } catch (const srp::core::FileError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("val.json"), std::string::npos) << m;
    EXPECT_NE(m.find("restore it from git"), std::string::npos) << m;
  }
  // The same failure inside a run is reported, not thrown.
  const auto outcome = runExperiment("language", options);
  EXPECT_FALSE(outcome.succeeded);
  EXPECT_NE(outcome.error.find("val.json"), std::string::npos);
  const std::string md = combinedMarkdown({outcome}, options.outDir, 1.0);
  EXPECT_NE(md.find("| language | FAILED |"), std::string::npos) << md;
}

// Our F1 in the table is the evaluator's (srp eval-language), SpERT's beside it.
TEST(LanguageExperiment, TablesShowTheEvaluatorsScoresBesideSpert)
{
  ExperimentOptions options;
  options.outDir = testOut("language");
  const auto outcome = runExperiment("language", options);
  ASSERT_TRUE(outcome.succeeded) << outcome.error;
  const ExperimentResult& r = outcome.result;

  const auto model = srp::language::LanguageModel::load(srp::language::defaultModelPath());
  const auto gold = srp::language::readSpertCorpus(std::string(SRP_DATASETS_DIR) + "/language/val.json");
  const auto scores = srp::language::evaluateModel(model, gold);

  // Table 5.7 sets the pooled cross-validation (cv_scores.json) beside SpERT's validation row.
  const nlohmann::json cv = srp::core::readJsonFile(std::string(SRP_DATASETS_DIR) + "/language/model/cv_scores.json");
  const ResultTable& t57 = tableStartingWith(r, "Table 5.7");
  ASSERT_EQ(t57.rows.size(), 7u);
  for (const auto& row : t57.rows) {
    const std::string type = row[0].substr(row[0].find('(') + 1, row[0].find(')') - row[0].find('(') - 1);
    EXPECT_NEAR(std::stod(row[2]), 100.0 * cv.at("variants").at("baseline").at(type).at("f1_mean").get<double>(),
                kF1Tol_percent) << type;
  }
  EXPECT_EQ(t57.rows[0][1], "99.13");  // SpERT's action F1, thesis table 5.7
  EXPECT_EQ(t57.rows[6][1], "83.46");  // move relation
  // The training-set check on val.json is labelled as such and matches an evaluation of the model.
  const ResultTable& check = tableStartingWith(r, "Training-set check");
  for (const auto& row : check.rows) {
    const std::string type = row[0].substr(row[0].find('(') + 1, row[0].find(')') - row[0].find('(') - 1);
    ASSERT_TRUE(scores.types.count(type)) << type;
    EXPECT_NEAR(std::stod(row[6]), 100.0 * scores.types.at(type).f1(), kF1Tol_percent) << type;
  }

  // The three corpora split val.json: their supports add up to the whole.
  int actionSupport = 0;
  for (const char* corpus : {"SemEval", "HuRIC", "HuRCM"})
    actionSupport += r.metrics.at("per_corpus").at(corpus).at("types").at("Action").at("support").get<int>();
  EXPECT_EQ(actionSupport, scores.types.at("Action").support());
  EXPECT_EQ(r.metrics.at("per_corpus").at("HuRCM").at("sentences").get<int>() +
                r.metrics.at("per_corpus").at("SemEval").at("sentences").get<int>() +
                r.metrics.at("per_corpus").at("HuRIC").at("sentences").get<int>(),
            static_cast<int>(gold.size()));
  EXPECT_EQ(tableStartingWith(r, "Table D.1").rows.front()[3], "98.96");

  // Appendix A: five rows; the count of right plans matches the rows.
  const ResultTable& plans = tableStartingWith(r, "Section 8.2");
  ASSERT_EQ(plans.rows.size(), 5u);
  int right = 0;
  for (const auto& row : plans.rows) right += row.back() == "right";
  EXPECT_EQ(right, r.metrics.at("appendix_a_right").get<int>());

  EXPECT_TRUE(std::filesystem::exists(options.outDir / "language" / "result.json"));
  EXPECT_TRUE(std::filesystem::exists(options.outDir / "language" / "report.md"));
}

TEST(DemoCache, KeyDependsOnEveryFieldOfTheRequest)
{
  const DemoCache cache(testOut("cache"));
  ExperimentOptions options;
  const DemoRequest a = standardDemoRequest(options, 0);
  DemoRequest b = a;
  EXPECT_EQ(cache.keyOf(a), cache.keyOf(b));
  EXPECT_EQ(cache.keyOf(a).size(), 16u);
  b.seed = a.seed + 1;
  EXPECT_NE(cache.keyOf(a), cache.keyOf(b));
  EXPECT_EQ(standardDemoRequest(options, 2).seed, options.firstSeed + 2);
  options.quick = true;
  const DemoRequest q = standardDemoRequest(options, 0);
  EXPECT_EQ(q.width_px, 320);
  EXPECT_EQ(q.plan.at("steps").size(), 1u);
  EXPECT_NE(cache.keyOf(a), cache.keyOf(q));
  DemoRequest missing = a;
  missing.scenePath = "/nonexistent/scene.json";
  EXPECT_THROW(cache.keyOf(missing), srp::core::FileError);
}

TEST(ExperimentSupport, ProgramBuildIdentityIsTheExecutablesSizeAndTime)
{
  // Cached perception and programming results are keyed by it: it must name this build.
  const std::string& identity = programBuildIdentity();
  const auto exe = std::filesystem::read_symlink("/proc/self/exe");
  EXPECT_EQ(identity.rfind(std::to_string(std::filesystem::file_size(exe)) + "-", 0), 0u) << identity;
  EXPECT_EQ(&identity, &programBuildIdentity()) << "computed once";
}
