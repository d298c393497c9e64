#pragma once
/// \file ExitCode.h
/// \brief The exit codes of every `srp` command (listed in `srp --help`).
///
/// A script can rely on them: 0 only when the command did all of its job.

namespace srp::core {

enum class ExitCode : int {
  Done = 0,     ///< the command did all of its job
  Error = 1,    ///< it could not do its job (bad input, a failed step); nothing half-made is left behind
  Usage = 2,    ///< the command line is wrong (unknown option, missing argument)
  Partial = 3,  ///< it finished, but some steps were refused or skipped (the report says which and why)
};

/// The code as the process exit status.
constexpr int toInt(ExitCode c) { return static_cast<int>(c); }

}  // namespace srp::core
