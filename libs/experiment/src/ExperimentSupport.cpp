#include "srp/experiment/ExperimentSupport.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <system_error>

#include "srp/core/DataPaths.h"
#include "srp/core/Error.h"

namespace srp::experiment {

std::filesystem::path datasetsDirOf(const ExperimentOptions& options)
{
  return options.datasetsDir.empty() ? core::DataPaths::file("datasets") : options.datasetsDir;
}

std::filesystem::path simDirOf(const ExperimentOptions& options)
{
  return options.simDir.empty() ? core::DataPaths::file("sim") : options.simDir;
}

std::filesystem::path experimentDirOf(const ExperimentOptions& options, const std::string& name)
{
  const auto dir = options.outDir / name;
  std::filesystem::create_directories(dir);
  return dir;
}

void requireDataset(const std::filesystem::path& path, const std::string& howToMake)
{
  if (!std::filesystem::exists(path))
    throw core::FileError(path.string(), "missing dataset; " + howToMake);
}

void reportProgress(const ExperimentOptions& options, const std::string& what, double fraction)
{
  if (options.progress) options.progress(what, fraction);
}

double medianOf(std::vector<double> values)
{
  if (values.empty()) return NAN;
  std::sort(values.begin(), values.end());
  const size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

const std::string& programBuildIdentity()
{
  static const std::string identity = [] {
    std::error_code ec;
    const auto exe = std::filesystem::read_symlink("/proc/self/exe", ec);
    if (ec) return std::string("unknown");
    const auto size = std::filesystem::file_size(exe, ec);
    if (ec) return std::string("unknown");
    const auto mtime = std::filesystem::last_write_time(exe, ec);
    if (ec) return std::string("unknown");
    return std::to_string(size) + "-" + std::to_string(mtime.time_since_epoch().count());
  }();
  return identity;
}

}  // namespace srp::experiment
