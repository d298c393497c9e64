#include "srp/experiment/ExperimentReport.h"

#include <fstream>
#include <sstream>

#include "srp/core/Error.h"
#include "srp/core/Json.h"
#include "srp/experiment/ExperimentSupport.h"
#include "srp/experiment/Experiments.h"

namespace srp::experiment {
namespace {

void writeText(const std::filesystem::path& path, const std::string& text)
{
  const auto tmp = path.string() + ".tmp";
  {
    std::ofstream out(tmp);
    if (!out) throw core::FileError(path.string(), "cannot write the report; check the --out folder");
    out << text;
  }
  std::filesystem::rename(tmp, path);
}

}  // namespace

std::string experimentNamesList()
{
  std::string names;
  for (const auto& e : experiments()) names += e.name + ", ";
  return names + "all";
}

std::vector<std::filesystem::path> writeExperimentFiles(const ExperimentResult& result, const ExperimentOptions& options)
{
  const auto dir = experimentDirOf(options, result.name);
  const auto json = dir / "result.json", md = dir / "report.md";
  core::writeJsonFile(json.string(), result.toJson());
  writeText(md, "# Experiment: " + result.name + "\n\n" + result.toMarkdown(std::filesystem::absolute(dir)));
  return {json, md};
}

ExperimentOutcome runExperiment(const std::string& name, const ExperimentOptions& options)
{
  const auto info = findExperiment(name);
  if (!info)
    throw core::InvalidInputError("unknown experiment '" + name + "'; valid names: " + experimentNamesList());
  ExperimentOutcome outcome;
  outcome.name = name;
  const WallClock clock;
  try {
    outcome.result = info->run(options);
    outcome.result.name = name;
    outcome.result.wallTime_s = clock.seconds();
    for (auto& f : outcome.result.figures) f = std::filesystem::absolute(f);
    writeExperimentFiles(outcome.result, options);
    outcome.succeeded = true;
  } catch (const std::exception& e) {
    outcome.error = e.what();
  }
  outcome.wallTime_s = clock.seconds();
  return outcome;
}

std::string combinedMarkdown(const std::vector<ExperimentOutcome>& outcomes, const std::filesystem::path& relativeTo,
                             double totalWallTime_s)
{
  std::ostringstream out;
  out << "# srp experiments: thesis chapter 8 reproduced\n\n"
      << "Every table shows the thesis' number beside ours; ours were measured in this run.\n\n";
  ResultTable overview;
  overview.title = "Overview";
  overview.columns = {"experiment", "status", "summary", "wall time [s]"};
  for (const auto& o : outcomes)
    overview.rows.push_back({o.name, o.succeeded ? "done" : "FAILED", o.succeeded ? o.result.summary : o.error,
                             formatNumber(o.wallTime_s, 1)});
  overview.note = "Total wall time " + formatNumber(totalWallTime_s, 1) + " s.";
  out << overview.toMarkdown() << '\n';
  for (const auto& o : outcomes) {
    if (o.succeeded)
      out << o.result.toMarkdown(relativeTo) << '\n';
    else
      out << "## " << o.name << "\n\n**Failed:** " << o.error << "\n\n";
  }
  return out.str();
}

nlohmann::json combinedJson(const std::vector<ExperimentOutcome>& outcomes, double totalWallTime_s)
{
  nlohmann::json j{{"schema_version", 1}, {"experiments", nlohmann::json::array()}, {"failed", nlohmann::json::array()},
                   {"wall_time_s", totalWallTime_s}};
  for (const auto& o : outcomes) {
    if (o.succeeded)
      j["experiments"].push_back(o.result.toJson());
    else
      j["failed"].push_back({{"name", o.name}, {"error", o.error}, {"wall_time_s", o.wallTime_s}});
  }
  return j;
}

}  // namespace srp::experiment
