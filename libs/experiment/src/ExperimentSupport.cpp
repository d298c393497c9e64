#include "srp/experiment/ExperimentSupport.h"

#include "srp/core/Error.h"

namespace srp::experiment {

std::filesystem::path datasetsDirOf(const ExperimentOptions& options)
{
  return options.datasetsDir.empty() ? std::filesystem::path(SRP_DATASETS_DIR) : options.datasetsDir;
}

std::filesystem::path simDirOf(const ExperimentOptions& options)
{
  return options.simDir.empty() ? std::filesystem::path(SRP_SIM_DIR) : options.simDir;
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

}  // namespace srp::experiment
