#include "srp/core/OutputFile.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstring>

#include "srp/core/Error.h"

namespace srp::core {
namespace fs = std::filesystem;

namespace {

std::atomic<std::int64_t> gFailAfterBytes{-1};  // < 0: off
std::atomic<unsigned> gTemporaryCounter{0};

// `.<name>.srp-<kind>-<pid>-<n><extension>`: the target's extension is kept, so a
// library that picks its format by the extension (cv::imwrite, cv::VideoWriter)
// writes the temporary as it would the target.
fs::path temporarySibling(const fs::path& target, const char* kind) {
  const fs::path parent = target.has_parent_path() ? target.parent_path() : fs::path(".");
  return parent / ("." + target.filename().string() + ".srp-" + kind + "-" + std::to_string(::getpid()) + "-" +
                   std::to_string(gTemporaryCounter.fetch_add(1)) + target.extension().string());
}

fs::path normalised(const fs::path& p) {
  std::error_code ec;
  fs::path c = fs::weakly_canonical(fs::absolute(p), ec);  // "./x" and "x" alike, also when x does not exist
  return (ec ? fs::absolute(p) : c).lexically_normal();
}

void fsyncFolder(const fs::path& folder) {
  const int fd = ::open(folder.empty() ? "." : folder.c_str(), O_RDONLY | O_DIRECTORY);
  if (fd < 0) return;  // best effort: the rename itself is atomic
  ::fsync(fd);
  ::close(fd);
}

bool isBelow(const fs::path& file, const fs::path& folder) {
  const fs::path f = normalised(file), d = normalised(folder);
  auto fi = f.begin();
  for (auto di = d.begin(); di != d.end(); ++di, ++fi)
    if (fi == f.end() || *fi != *di) return false;
  return fi != f.end();
}

std::string describe(const PathRole& p) { return p.role + " '" + p.path.string() + "'"; }

}  // namespace

bool isSameFile(const fs::path& a, const fs::path& b) {
  std::error_code ec;
  if (fs::exists(a, ec) && fs::exists(b, ec)) {
    const bool same = fs::equivalent(a, b, ec);
    if (!ec) return same;
  }
  return normalised(a) == normalised(b);
}

void checkOutputPaths(const std::vector<PathRole>& outputs, const std::vector<PathRole>& inputs, bool overwrite) {
  for (std::size_t i = 0; i < outputs.size(); ++i) {
    const PathRole& out = outputs[i];
    if (out.path.empty()) continue;
    for (const PathRole& in : inputs) {
      if (in.path.empty()) continue;
      std::error_code ec;
      const bool inputIsFolder = fs::is_directory(in.path, ec);
      if (isSameFile(out.path, in.path) || (inputIsFolder && isBelow(out.path, in.path)))
        throw InvalidInputError("the output " + describe(out) + " is the input " + describe(in) +
                                (inputIsFolder ? " or inside it" : "") +
                                ": writing it would destroy the input; choose another output path");
      if (fs::is_directory(out.path, ec) && isBelow(in.path, out.path))
        throw InvalidInputError("the output folder " + describe(out) + " holds the input " + describe(in) +
                                ": replacing the folder would destroy the input; choose another output folder");
    }
    for (std::size_t j = 0; j < i; ++j)
      if (!outputs[j].path.empty() && isSameFile(out.path, outputs[j].path))
        throw InvalidInputError("the outputs " + describe(outputs[j]) + " and " + describe(out) +
                                " are the same file; give each its own path");
    std::error_code ec;
    if (!overwrite && fs::exists(out.path, ec))
      throw InvalidInputError("the output " + describe(out) +
                              " exists already; pass -w/--overwrite to replace it, or choose another path");
  }
}

void checkFolderHoldsOnly(const fs::path& folder, const std::vector<std::string>& names, const std::string& role) {
  std::error_code ec;
  if (!fs::is_directory(folder, ec)) return;
  std::string foreign;
  int count = 0;
  for (const auto& entry : fs::directory_iterator(folder, ec)) {
    const std::string name = entry.path().filename().string();
    const auto matches = [&name](const std::string& pattern) {
      if (!pattern.empty() && pattern.back() == '*') return name.rfind(pattern.substr(0, pattern.size() - 1), 0) == 0;
      if (!pattern.empty() && pattern.front() == '*')
        return name.size() >= pattern.size() - 1 && name.compare(name.size() - (pattern.size() - 1), std::string::npos,
                                                                 pattern, 1, std::string::npos) == 0;
      return name == pattern;
    };
    if (std::any_of(names.begin(), names.end(), matches)) continue;
    if (++count <= 3) foreign += (foreign.empty() ? "'" : ", '") + name + "'";
  }
  if (count > 0)
    throw InvalidInputError("the output folder " + role + " '" + folder.string() + "' holds " + std::to_string(count) +
                            " file(s) this command did not write (" + foreign + (count > 3 ? ", ..." : "") +
                            "), which replacing it would delete; choose a new or empty folder");
}

// ---------------------------------------------------------------------------------------------------------------

AtomicOutputFile::AtomicOutputFile(fs::path target) : target_(std::move(target)) {
  if (target_.empty()) throw FileError("", "empty output path");
  std::error_code ec;
  if (fs::is_directory(target_, ec))
    throw FileError(target_.string(), "is a folder; give a file name for this output");
  const fs::path parent = target_.has_parent_path() ? target_.parent_path() : fs::path(".");
  if (!fs::is_directory(parent, ec))
    throw FileError(target_.string(), "its folder '" + parent.string() + "' does not exist; create it first");
  temporary_ = temporarySibling(target_, "tmp");
  fd_ = ::open(temporary_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
  if (fd_ < 0)
    throw FileError(target_.string(), std::string("cannot create a file in its folder (") + std::strerror(errno) +
                                          "); is the folder writable?");
}

AtomicOutputFile::AtomicOutputFile(AtomicOutputFile&& o) noexcept
    : target_(std::move(o.target_)),
      temporary_(std::move(o.temporary_)),
      fd_(o.fd_),
      prepared_(o.prepared_),
      committed_(o.committed_) {
  o.fd_ = -1;
  o.committed_ = true;  // the moved-from object owns nothing to clean up
  o.temporary_.clear();
}

AtomicOutputFile::~AtomicOutputFile() {
  closeFd();
  if (!committed_ && !temporary_.empty()) {
    std::error_code ec;
    fs::remove(temporary_, ec);
  }
}

void AtomicOutputFile::closeFd() {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
}

void AtomicOutputFile::write(std::string_view bytes) {
  if (fd_ < 0) throw FileError(target_.string(), "written after commit (a bug in srp)");
  const char* p = bytes.data();
  std::size_t left = bytes.size();
  while (left > 0) {
    std::size_t chunk = left;
    const std::int64_t budget = gFailAfterBytes.load();
    if (budget >= 0 && static_cast<std::int64_t>(chunk) > budget) chunk = static_cast<std::size_t>(budget);
    if (chunk == 0) {
      errno = ENOSPC;
      throw FileError(target_.string(), std::string("write failed (") + std::strerror(ENOSPC) +
                                            "); the previous file, if any, is unchanged");
    }
    const ssize_t n = ::write(fd_, p, chunk);
    if (n < 0) {
      if (errno == EINTR) continue;
      throw FileError(target_.string(), std::string("write failed (") + std::strerror(errno) +
                                            "); the previous file, if any, is unchanged");
    }
    if (budget >= 0) gFailAfterBytes.store(budget - n);
    p += n;
    left -= static_cast<std::size_t>(n);
  }
}

void AtomicOutputFile::prepare() {
  if (prepared_) return;
  if (fd_ >= 0 && ::fsync(fd_) != 0)
    throw FileError(target_.string(), std::string("fsync failed (") + std::strerror(errno) + ")");
  closeFd();
  prepared_ = true;
}

void AtomicOutputFile::renameOverTarget(bool syncFolder) {
  if (::rename(temporary_.c_str(), target_.c_str()) != 0)
    throw FileError(target_.string(), std::string("cannot replace it (") + std::strerror(errno) + ")");
  committed_ = true;
  if (syncFolder) fsyncFolder(target_.has_parent_path() ? target_.parent_path() : fs::path("."));
}

void AtomicOutputFile::commit() {
  if (committed_) return;
  prepare();
  renameOverTarget();
}

void writeFileAtomically(const fs::path& target, std::string_view contents) {
  AtomicOutputFile out(target);
  out.write(contents);
  out.commit();
}

void writeFilesTogether(const std::vector<std::pair<fs::path, std::string>>& files) {
  std::vector<AtomicOutputFile> outs;
  outs.reserve(files.size());
  for (const auto& [path, contents] : files) {
    outs.emplace_back(path);
    outs.back().write(contents);
  }
  for (auto& o : outs) o.prepare();
  // Keep each existing target under a hard link, so a failed later rename can put it back.
  std::vector<fs::path> backups(outs.size());
  for (std::size_t i = 0; i < outs.size(); ++i) {
    std::error_code ec;
    if (!fs::exists(outs[i].target(), ec)) continue;
    backups[i] = temporarySibling(outs[i].target(), "old");
    fs::create_hard_link(outs[i].target(), backups[i], ec);
    if (ec) {
      for (const auto& b : backups)
        if (!b.empty()) fs::remove(b, ec);
      throw FileError(outs[i].target().string(), "cannot keep a backup of the previous file (" + ec.message() + ")");
    }
  }
  // The renames back to back (the folders are fsync'ed after the last one), so
  // that the moment in which a kill could leave one new and one previous file
  // is as short as two system calls.
  std::size_t renamed = 0;
  try {
    for (; renamed < outs.size(); ++renamed) outs[renamed].renameOverTarget(false);
  } catch (...) {
    std::error_code ec;
    for (std::size_t i = 0; i < renamed; ++i) {
      if (!backups[i].empty())
        fs::rename(backups[i], outs[i].target(), ec);
      else
        fs::remove(outs[i].target(), ec);
    }
    for (std::size_t i = renamed; i < outs.size(); ++i)
      if (!backups[i].empty()) fs::remove(backups[i], ec);
    throw;
  }
  for (const auto& o : outs) fsyncFolder(o.target().has_parent_path() ? o.target().parent_path() : fs::path("."));
  std::error_code ec;
  for (const auto& b : backups)
    if (!b.empty()) fs::remove(b, ec);
}

void injectOutputWriteFailureAfter(std::int64_t bytes) { gFailAfterBytes.store(bytes < 0 ? -1 : bytes); }

// ---------------------------------------------------------------------------------------------------------------

AtomicOutputFolder::AtomicOutputFolder(fs::path target) : target_(std::move(target)) {
  if (target_.empty()) throw FileError("", "empty output folder path");
  const fs::path parent = target_.has_parent_path() ? target_.parent_path() : fs::path(".");
  std::error_code ec;
  if (!fs::is_directory(parent, ec))
    throw FileError(target_.string(), "its folder '" + parent.string() + "' does not exist; create it first");
  if (fs::exists(target_, ec) && !fs::is_directory(target_, ec))
    throw FileError(target_.string(), "exists and is not a folder");
  temporary_ = temporarySibling(target_, "tmp");
  if (!fs::create_directory(temporary_, ec) || ec)
    throw FileError(target_.string(), "cannot create a folder beside it (" + ec.message() + "); is " +
                                          parent.string() + " writable?");
}

AtomicOutputFolder::~AtomicOutputFolder() {
  if (committed_) return;
  std::error_code ec;
  fs::remove_all(temporary_, ec);
}

void AtomicOutputFolder::commit() {
  if (committed_) return;
  std::error_code ec;
  fs::path old;
  if (fs::exists(target_, ec)) {
    old = temporarySibling(target_, "old");
    fs::rename(target_, old, ec);
    if (ec) throw FileError(target_.string(), "cannot move the previous folder aside (" + ec.message() + ")");
  }
  fs::rename(temporary_, target_, ec);
  if (ec) {
    std::error_code ec2;
    if (!old.empty()) fs::rename(old, target_, ec2);
    throw FileError(target_.string(), "cannot move the new folder into place (" + ec.message() + ")");
  }
  committed_ = true;
  fsyncFolder(target_.has_parent_path() ? target_.parent_path() : fs::path("."));
  if (!old.empty()) fs::remove_all(old, ec);
}

}  // namespace srp::core
