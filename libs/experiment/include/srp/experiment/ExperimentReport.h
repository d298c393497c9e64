#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "srp/experiment/ExperimentResult.h"

namespace srp::experiment {

/// What one experiment of a run gave: its result, or the error that stopped it.
struct ExperimentOutcome
{
  std::string name;
  bool succeeded = false;
  std::string error;       ///< the exception's message when it failed
  ExperimentResult result; ///< valid when succeeded
  double wallTime_s = 0.0;
};

/// Writes `<options.outDir>/<name>/result.json` and `report.md` (figures linked
/// relative to that folder); returns the two paths. Throws core::FileError.
std::vector<std::filesystem::path> writeExperimentFiles(const ExperimentResult& result, const ExperimentOptions& options);

/// Runs the experiment called `name` (Experiments.h), catches its error, writes
/// its files when it succeeded. Throws InvalidInputError for an unknown name
/// (the message lists the valid ones).
ExperimentOutcome runExperiment(const std::string& name, const ExperimentOptions& options);

/// One Markdown report of several outcomes: a summary table (experiment,
/// status, headline, wall time), then every experiment's section; failures
/// with their error. Figures linked relative to `relativeTo`.
std::string combinedMarkdown(const std::vector<ExperimentOutcome>& outcomes, const std::filesystem::path& relativeTo,
                             double totalWallTime_s);

/// {"experiments": [...], "failed": [...], "wall_time_s"}.
nlohmann::json combinedJson(const std::vector<ExperimentOutcome>& outcomes, double totalWallTime_s);

/// The valid names of `srp experiment`, comma-separated, with "all".
std::string experimentNamesList();

}  // namespace srp::experiment
