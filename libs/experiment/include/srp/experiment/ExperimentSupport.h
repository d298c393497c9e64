#pragma once

#include <chrono>
#include <filesystem>
#include <string>
#include <vector>

#include "srp/experiment/ExperimentResult.h"

namespace srp::experiment {

/// The datasets/ of a run: `options.datasetsDir`, else `datasets/` of srp's data folder (core::DataPaths).
std::filesystem::path datasetsDirOf(const ExperimentOptions& options);

/// The sim/ of a run: `options.simDir`, else `sim/` of srp's data folder (core::DataPaths).
std::filesystem::path simDirOf(const ExperimentOptions& options);

/// `<options.outDir>/<name>`, created.
std::filesystem::path experimentDirOf(const ExperimentOptions& options, const std::string& name);

/// Throws core::FileError naming `path` and saying how to make it (`howToMake`,
/// e.g. "run 'srp train-language'") when the file does not exist.
void requireDataset(const std::filesystem::path& path, const std::string& howToMake);

/// Calls `options.progress(what, fraction)` when a callback is set.
void reportProgress(const ExperimentOptions& options, const std::string& what, double fraction);

/// Median of `values` (mean of the middle two for an even count); NaN when empty.
double medianOf(std::vector<double> values);

/// The running program's build, as "<size>-<mtime>" of its executable
/// (/proc/self/exe; "unknown" where that cannot be read). Results computed by
/// the code under study (perception, programming) are cached under it, so a
/// rebuilt program computes them again instead of reporting the old code's.
const std::string& programBuildIdentity();

/// Wall-clock seconds since construction.
class WallClock
{
public:
  WallClock() : start_(std::chrono::steady_clock::now()) {}
  double seconds() const { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count(); }

private:
  std::chrono::steady_clock::time_point start_;
};

}  // namespace srp::experiment
