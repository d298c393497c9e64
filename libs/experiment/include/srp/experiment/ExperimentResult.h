#pragma once

#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "srp/experiment/ResultTable.h"

namespace srp::experiment {

/**
 * What every experiment is given: where to write, how big to make the
 * study, how to report progress.
 *
 * Sizes default to what `srp experiment all` runs within its 15 min budget on
 * a 2-core machine; a larger study is a flag away.
 */
struct ExperimentOptions
{
  std::filesystem::path outDir = "out/experiment";  ///< PNGs and intermediate files go under outDir/<name>/
  std::filesystem::path datasetsDir;                ///< default: `datasets/` of srp's data folder (core::DataPaths)
  std::filesystem::path simDir;                     ///< default: `sim/` of srp's data folder (core::DataPaths)
  int demoCount = 5;                                ///< seeded synthetic demos (the thesis had five videos)
  unsigned firstSeed = 1;                           ///< demos use seeds firstSeed, firstSeed + 1, ...
  bool quick = false;                               ///< smallest sizes that still exercise every part (tests)
  /// Progress on long work: (what, fraction done in [0, 1]); may be empty.
  std::function<void(const std::string&, double)> progress;
};

/**
 * The outcome of one experiment: thesis-layout tables (thesis number beside
 * ours, ours measured in this run), PNG figures, and the raw numbers for
 * programs.
 */
struct ExperimentResult
{
  std::string name;                           ///< "language", "hand", ...
  std::string summary;                        ///< one or two sentences: what was measured, headline figures
  std::vector<ResultTable> tables;
  std::vector<std::filesystem::path> figures; ///< PNGs written (absolute or relative to the working dir)
  nlohmann::json metrics;                     ///< every measured number, machine-readable
  double wallTime_s = 0.0;

  /// A Markdown section: "## <name>", summary, tables, figures (linked relative to `relativeTo`).
  std::string toMarkdown(const std::filesystem::path& relativeTo) const;

  /// {"name", "summary", "tables", "figures", "metrics", "wall_time_s"}.
  nlohmann::json toJson() const;
};

/// An experiment: options in, result out. Throws srp::core exceptions on bad input
/// (a missing dataset names the file and how to make it).
using ExperimentFunction = std::function<ExperimentResult(const ExperimentOptions&)>;

}  // namespace srp::experiment
