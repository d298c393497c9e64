#pragma once
/// \file OutputFile.h
/// \brief The one way srp writes a file a user asked for: atomically, never over
/// an input, never over another output of the same command, and over an existing
/// file only when the user said so.
///
/// Every command that writes goes through these helpers:
/// - **Atomic.** Bytes go to a temporary file in the target's folder
///   (`.<name>.srp-tmp-<pid>-<n><ext>`, the target's extension kept for writers
///   that choose the format by it), which is flushed, fsync'ed and renamed over
///   the target; the folder is fsync'ed after the rename. A crash, a kill or a
///   full disk at any point leaves the previous file (or no file) as it was, and
///   at most a stray temporary that no reader mistakes for the output.
/// - **Together.** writeFilesTogether() writes several outputs as one: every
///   temporary is complete before the first rename, and a failed rename restores
///   the outputs already renamed (a URScript program and its ROS 2 trajectory:
///   both or neither).
/// - **Non-destructive.** checkOutputPaths() refuses an output that is one of the
///   command's inputs or another of its outputs (same canonical path, or the same
///   file through another name: a hard link, a symlink), and an existing output
///   unless the command was given `-w/--overwrite`.
///
/// \code
///   using srp::core::PathRole;
///   srp::core::checkOutputPaths({PathRole{"--urscript", scriptPath}},
///                               {PathRole{"--db", dbPath}}, overwrite);
///   srp::core::writeFileAtomically(scriptPath, scriptText);
///
///   srp::core::AtomicOutputFile out(reportPath);   // a writer that needs a path
///   cv::imwrite(out.temporaryPath().string(), image);
///   out.commit();                                   // not committed: nothing changes
/// \endcode

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace srp::core {

/// A path together with the option or role that named it ("--urscript",
/// "--db", "input folder"), so an error can say which two collide.
struct PathRole {
  std::string role;
  std::filesystem::path path;
};

/// True when `a` and `b` name the same file: the same inode when both exist,
/// else the same weakly-canonical path.
bool isSameFile(const std::filesystem::path& a, const std::filesystem::path& b);

/// Refuses (InvalidInputError, naming both roles and paths) an output that is
/// one of `inputs`, or the same file as another output, or, unless
/// `overwrite`, an existing file. An input that is a folder also protects every
/// file below it; an output that is an existing folder holding an input is
/// refused too (replacing the folder would remove the input).
void checkOutputPaths(const std::vector<PathRole>& outputs, const std::vector<PathRole>& inputs, bool overwrite);

/// Refuses (InvalidInputError naming `role`, the folder and up to three of the
/// files) an existing output folder that holds anything but `names`: an
/// AtomicOutputFolder replaces the whole folder, so a folder given by mistake
/// (the home folder, a data folder) must not be replaced, -w or not. A name
/// ending in '*' stands for every name starting with the rest ("frame_*"), one
/// starting with '*' for every name ending with the rest ("*_skills.png"). A
/// missing folder passes.
void checkFolderHoldsOnly(const std::filesystem::path& folder, const std::vector<std::string>& names,
                          const std::string& role);

/// One output file written atomically. Write through stream() / write(), or let
/// another library write temporaryPath(); then commit(). Destroyed uncommitted,
/// the temporary is removed and the target is untouched.
class AtomicOutputFile {
 public:
  /// Creates the temporary file in `target`'s folder (which must exist). Throws
  /// FileError naming the target when the folder is missing or not writable.
  explicit AtomicOutputFile(std::filesystem::path target);
  AtomicOutputFile(const AtomicOutputFile&) = delete;
  AtomicOutputFile& operator=(const AtomicOutputFile&) = delete;
  AtomicOutputFile(AtomicOutputFile&& other) noexcept;
  AtomicOutputFile& operator=(AtomicOutputFile&&) = delete;
  ~AtomicOutputFile();

  const std::filesystem::path& target() const { return target_; }
  const std::filesystem::path& temporaryPath() const { return temporary_; }

  /// Appends bytes to the temporary; throws FileError naming the target on a
  /// short write (a full disk).
  void write(std::string_view bytes);

  /// fsync of the temporary, rename over the target, fsync of the folder.
  /// Throws FileError (and leaves the target as it was) on failure.
  void commit();

  /// Everything but the rename (flush + fsync): writeFilesTogether() prepares
  /// every file before renaming any.
  void prepare();

 private:
  friend void writeFilesTogether(const std::vector<std::pair<std::filesystem::path, std::string>>& files);
  void renameOverTarget(bool syncFolder = true);
  void closeFd();

  std::filesystem::path target_, temporary_;
  int fd_ = -1;
  bool prepared_ = false, committed_ = false;
};

/// An output folder (a report, exported frames) built in a temporary folder
/// beside the target and renamed into place by commit(): a failed command
/// leaves no half-made folder, and a replaced folder keeps no stale files of the
/// previous run. Destroyed uncommitted, the temporary folder is removed.
class AtomicOutputFolder {
 public:
  /// Creates `.<name>.srp-tmp-<pid>-<n>/` beside `target` (whose parent must exist).
  explicit AtomicOutputFolder(std::filesystem::path target);
  AtomicOutputFolder(const AtomicOutputFolder&) = delete;
  AtomicOutputFolder& operator=(const AtomicOutputFolder&) = delete;
  ~AtomicOutputFolder();

  const std::filesystem::path& target() const { return target_; }
  /// Where the files go until commit().
  const std::filesystem::path& temporaryPath() const { return temporary_; }

  /// Replaces `target` (an existing folder is moved aside, then removed) with
  /// the temporary folder. Throws FileError, leaving the target as it was.
  void commit();

 private:
  std::filesystem::path target_, temporary_;
  bool committed_ = false;
};

/// Writes `contents` to `target` atomically (AtomicOutputFile).
void writeFileAtomically(const std::filesystem::path& target, std::string_view contents);

/// Writes every (path, contents) pair, all or none: all temporaries are written
/// and fsync'ed before the first rename; if a later rename fails, the targets
/// already replaced get their previous contents back (or are removed when they
/// did not exist) and FileError is thrown.
void writeFilesTogether(const std::vector<std::pair<std::filesystem::path, std::string>>& files);

/// Test hook: the next writes fail (as on a full disk, errno ENOSPC) once
/// `bytes` more bytes have been written through AtomicOutputFile; a negative
/// value switches the failure off. Process-wide; for tests only.
void injectOutputWriteFailureAfter(std::int64_t bytes);

}  // namespace srp::core
