#include "srp/language/CapabilitySuites.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "srp/core/Error.h"

using namespace srp::language;

namespace {
namespace fs = std::filesystem;

// A fresh empty folder under the system's temporary directory, removed at the end.
struct TempFolder {
  fs::path path;
  explicit TempFolder(const std::string& name) : path(fs::temp_directory_path() / name) {
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~TempFolder() { fs::remove_all(path); }
};

void writeSuite(const fs::path& file, const std::vector<AnnotatedSentence>& sentences) {
  nlohmann::json j = nlohmann::json::array();
  for (const auto& s : sentences) j.push_back(toJson(s));
  std::ofstream(file) << j.dump();
}

AnnotatedSentence putItOnTheBox() {
  AnnotatedSentence s;
  s.tokens = {"put", "it", "on", "the", "box"};
  s.entities = {{0, 1, "Action"}, {2, 3, "GoalIndicator"}};
  s.relations = {{0, 1, "Transition"}};
  return s;
}
}  // namespace

TEST(CapabilitySuites, LoadsEveryJsonFileInNameOrder) {
  const TempFolder folder("srp_capability_suites_test");
  writeSuite(folder.path / "b_second.json", {putItOnTheBox(), putItOnTheBox()});
  writeSuite(folder.path / "a_first.json", {putItOnTheBox()});
  std::ofstream(folder.path / "notes.txt") << "not a suite";
  const auto suites = CapabilitySuites::load(folder.path.string());
  ASSERT_EQ(suites.suites().size(), 2u);
  EXPECT_EQ(suites.suites()[0].name, "a_first");
  EXPECT_EQ(suites.suites()[1].name, "b_second");
  EXPECT_EQ(suites.suites()[1].sentences.size(), 2u);
}

TEST(CapabilitySuites, MissingOrEmptyFolderNamesIt) {
  const TempFolder folder("srp_capability_suites_empty");
  for (const auto& path : {folder.path.string(), (folder.path / "missing").string()}) {
    try {
      CapabilitySuites::load(path);
      FAIL() << "no exception for " << path;
    } catch (const srp::core::FileError& e) {
      EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    }
  }
}

// The summary pools the counts of the entity types and of the relation types.
TEST(CapabilitySuites, SummaryPoolsEntityAndRelationCounts) {
  constexpr double kTol = 1e-12;
  SpertScores scores;
  scores.types["Action"] = {3, 0, 1};
  scores.types["GoalIndicator"] = {1, 1, 0};
  scores.types["Transition"] = {1, 0, 1};
  scores.types["Spatial"] = {0, 1, 0};
  const auto r = CapabilitySuites::summarise("s", 4, scores);
  EXPECT_EQ(r.entities.truePositives, 4);
  EXPECT_EQ(r.entities.falsePositives, 1);
  EXPECT_EQ(r.entities.falseNegatives, 1);
  EXPECT_NEAR(r.entities.f1(), 0.8, kTol);
  EXPECT_NEAR(r.relations.f1(), 0.5, kTol);
  const std::string table = CapabilitySuites::formatTable({r}, {r});
  EXPECT_NE(table.find("80.00 ( 80.00,  +0.00)"), std::string::npos) << table;
  EXPECT_NEAR(CapabilitySuites::toJson({r})["s"]["relation_f1"].get<double>(), 0.5, kTol);
}

// Acceptance of the capability suites (libs/language/README.md "Capability suites"):
// the shipped model reaches >= 95 % entity F1 and >= 90 % relation F1 on each suite.
TEST(CapabilitySuites, ShippedModelMeetsTheTargetOnEverySuite) {
  constexpr double kMinEntityF1 = 0.95;
  constexpr double kMinRelationF1 = 0.90;
  const auto suites = CapabilitySuites::load(CapabilitySuites::defaultFolder());
  EXPECT_EQ(suites.suites().size(), 5u);
  const auto results = suites.score(LanguageModel::load(defaultModelPath()));
  for (const auto& r : results) {
    SCOPED_TRACE(r.name);
    EXPECT_GE(r.sentences, 30);
    EXPECT_GE(r.entities.f1(), kMinEntityF1);
    EXPECT_GE(r.relations.f1(), kMinRelationF1);
  }
}
