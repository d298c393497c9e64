#include "srp/core/DataPaths.h"

#include <cstdlib>
#include <fstream>
#include <mutex>
#include <system_error>

#include "srp/core/Error.h"

namespace srp::core {
namespace {

namespace fs = std::filesystem;

std::mutex& overrideMutex() {
  static std::mutex m;
  return m;
}

fs::path& overrideDir() {
  static fs::path dir;
  return dir;
}

bool isFolder(const fs::path& p) {
  std::error_code ec;
  return fs::is_directory(p, ec);
}

/// The running executable (Linux: /proc/self/exe), empty when unknown.
fs::path executablePath() {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  return ec ? fs::path() : exe;
}

/// Rule 4: the first srp-data-dir.txt in the executable's folder or a parent.
std::optional<fs::path> buildTreeData(const fs::path& exe) {
  for (fs::path dir = exe.parent_path(); !dir.empty(); dir = dir.parent_path()) {
    std::ifstream in(dir / DataPaths::kBuildTreeMarker);
    std::string line;
    if (in && std::getline(in, line) && !line.empty() && isFolder(line)) return fs::path(line);
    if (dir == dir.root_path()) break;
  }
  return std::nullopt;
}

std::string dataDirHelp() {
  return "give srp's data folder with 'srp --data-dir DIR' or the environment variable SRP_DATA_DIR (an installed "
         "srp finds <prefix>/share/srp next to <prefix>/bin/srp)";
}

}  // namespace

void DataPaths::setDataDir(const fs::path& dir) {
  if (!dir.empty() && !isFolder(dir))
    throw FileError(dir.string(), "--data-dir: not a folder (" + dataDirHelp() + ")");
  std::lock_guard<std::mutex> lock(overrideMutex());
  overrideDir() = dir.empty() ? fs::path() : fs::absolute(dir).lexically_normal();
}

std::optional<DataPaths::Root> DataPaths::find() {
  {
    std::lock_guard<std::mutex> lock(overrideMutex());
    if (!overrideDir().empty()) return Root{overrideDir(), Origin::Option};
  }
  if (const char* env = std::getenv("SRP_DATA_DIR"); env != nullptr && *env != '\0')
    return isFolder(env) ? std::optional<Root>(Root{fs::absolute(env).lexically_normal(), Origin::Environment})
                         : std::nullopt;
  const fs::path exe = executablePath();
  if (exe.empty()) return std::nullopt;
  const fs::path installed = (exe.parent_path() / ".." / "share" / "srp").lexically_normal();
  if (isFolder(installed)) return Root{installed, Origin::Install};
  if (const auto source = buildTreeData(exe)) return Root{*source, Origin::BuildTree};
  return std::nullopt;
}

DataPaths::Root DataPaths::root() {
  if (auto r = find()) return *r;
  if (const char* env = std::getenv("SRP_DATA_DIR"); env != nullptr && *env != '\0')
    throw FileError(env, "SRP_DATA_DIR names no folder (" + dataDirHelp() + ")");
  const fs::path exe = executablePath();
  const std::string tried =
      exe.empty() ? std::string("the executable's folder is unknown")
                  : (exe.parent_path() / ".." / "share" / "srp").lexically_normal().string() + " and no " +
                        kBuildTreeMarker + " above " + exe.parent_path().string();
  throw FileError("srp data folder", "not found (tried " + tried + "); " + dataDirHelp());
}

fs::path DataPaths::file(const fs::path& relative) {
  const Root r = root();
  const fs::path path = r.dir / relative;
  std::error_code ec;
  if (!fs::exists(path, ec))
    throw FileError(path.string(), "not in srp's data folder " + r.dir.string() + " (chosen by " +
                                       describe(r.origin) + "); " + dataDirHelp());
  return path;
}

std::string DataPaths::describe(Origin origin) {
  switch (origin) {
    case Origin::Option: return "--data-dir";
    case Origin::Environment: return "SRP_DATA_DIR";
    case Origin::Install: return "next to the executable";
    case Origin::BuildTree: return "the source tree of the build folder";
  }
  return "?";
}

}  // namespace srp::core
