#include "srp/language/CapabilitySuites.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "srp/core/DataPaths.h"
#include "srp/core/Error.h"

namespace srp::language {

namespace {
const std::vector<std::string> kEntityTypes{"Action", "Trajector", "SpatialIndicator", "GoalIndicator", "Color"};
const std::vector<std::string> kRelationTypes{"Spatial", "Transition"};

TypeScore sumOf(const SpertScores& scores, const std::vector<std::string>& types) {
  TypeScore sum;
  for (const auto& t : types) {
    auto it = scores.types.find(t);
    if (it == scores.types.end()) continue;
    sum.truePositives += it->second.truePositives;
    sum.falsePositives += it->second.falsePositives;
    sum.falseNegatives += it->second.falseNegatives;
  }
  return sum;
}
}  // namespace

std::string CapabilitySuites::defaultFolder() {
  return core::DataPaths::file("datasets/language/capabilities").string();
}

CapabilitySuites CapabilitySuites::load(const std::string& folder) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::is_directory(folder, ec))
    throw core::FileError(folder, "is not a folder of capability suites (expected <name>.json files in SpERT format)");
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(folder, ec))
    if (entry.is_regular_file() && entry.path().extension() == ".json") files.push_back(entry.path());
  if (files.empty()) throw core::FileError(folder, "holds no capability suite (<name>.json in SpERT format)");
  std::sort(files.begin(), files.end());
  CapabilitySuites out;
  for (const auto& f : files) out.suites_.push_back({f.stem().string(), readSpertCorpus(f.string())});
  return out;
}

CapabilitySuites::Result CapabilitySuites::summarise(const std::string& name, int sentences, const SpertScores& scores) {
  return {name, sentences, scores, sumOf(scores, kEntityTypes), sumOf(scores, kRelationTypes)};
}

std::vector<CapabilitySuites::Result> CapabilitySuites::score(const LanguageModel& model) const {
  std::vector<Result> out;
  for (const auto& s : suites_)
    out.push_back(summarise(s.name, static_cast<int>(s.sentences.size()), evaluateModel(model, s.sentences)));
  return out;
}

std::string CapabilitySuites::formatTable(const std::vector<Result>& results, const std::vector<Result>& before) {
  const bool compare = !before.empty();
  core::require(!compare || before.size() == results.size(),
                "capability tables of different suites cannot be compared; score both models on the same folder");
  char line[256];
  std::string out = compare ? "suite               sentences  entity F1 (before, diff)    relation F1 (before, diff)\n"
                            : "suite               sentences  entity P      R     F1  relation P      R     F1\n";
  for (size_t i = 0; i < results.size(); ++i) {
    const auto& r = results[i];
    if (compare) {
      const auto& b = before[i];
      core::require(b.name == r.name, "capability tables list different suites: " + b.name + " vs " + r.name);
      std::snprintf(line, sizeof line, "%-19s %9d  %6.2f (%6.2f, %+6.2f)     %6.2f (%6.2f, %+6.2f)\n", r.name.c_str(),
                    r.sentences, 100 * r.entities.f1(), 100 * b.entities.f1(),
                    100 * (r.entities.f1() - b.entities.f1()), 100 * r.relations.f1(), 100 * b.relations.f1(),
                    100 * (r.relations.f1() - b.relations.f1()));
    } else {
      std::snprintf(line, sizeof line, "%-19s %9d  %8.2f %6.2f %6.2f  %10.2f %6.2f %6.2f\n", r.name.c_str(), r.sentences,
                    100 * r.entities.precision(), 100 * r.entities.recall(), 100 * r.entities.f1(),
                    100 * r.relations.precision(), 100 * r.relations.recall(), 100 * r.relations.f1());
    }
    out += line;
  }
  return out;
}

nlohmann::json CapabilitySuites::toJson(const std::vector<Result>& results) {
  nlohmann::json j = nlohmann::json::object();
  for (const auto& r : results)
    j[r.name] = {{"sentences", r.sentences},
                 {"entity_f1", r.entities.f1()},
                 {"relation_f1", r.relations.f1()},
                 {"types", srp::language::toJson(r.scores)["types"]}};
  return j;
}

}  // namespace srp::language
