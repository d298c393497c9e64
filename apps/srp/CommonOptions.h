#pragma once
/// \file CommonOptions.h
/// \brief The options every `srp` command shares, and the deprecated spellings
/// of earlier releases.
///
/// Every command takes `-q,--quiet` (no progress; warnings and errors only),
/// `-v,--verbose` (debug lines of every log category) and `--log-level SPEC`
/// (srp/core/Log.h); main() adds them. Progress lines are drawn only on a
/// terminal and never with -q or --json (progressWanted()).
///
/// An option renamed for the one vocabulary (`-o/--out`, `--kb`, `--task`,
/// `--intrinsics`) keeps its old spelling for one release, hidden from --help,
/// with a warning line on stderr:
/// \code
///   srp::app::addDeprecatedOption(cmd, "--catalogue", path, "--kb");
/// \endcode

#include <CLI/CLI.hpp>
#include <string>

namespace srp::app {

/// True after -q/--quiet on the command line.
bool& quietFlag();

/// Progress lines only on a terminal, and not with -q or when the result is printed as JSON.
bool progressWanted(bool json = false);

/// Adds -q/--quiet, -v/--verbose and --log-level to `cmd` and its subcommands.
void addVerbosityOptions(CLI::App& cmd);

/// The warning line of a deprecated spelling ("srp: warning: '--catalogue' is deprecated; use '--kb'").
void warnDeprecated(const std::string& oldSpelling, const std::string& newSpelling);

/// An old option name writing the same variable as its new spelling, hidden from --help; using it warns.
template <typename T>
CLI::Option* addDeprecatedOption(CLI::App& cmd, const std::string& oldName, T& target, const std::string& newName) {
  return cmd.add_option(oldName, target)->group("")->each([oldName, newName](const std::string&) {
    warnDeprecated(oldName, newName);
  });
}

/// An old positional argument (NAME) now given as an option (e.g. -o/--out): still read, listed under
/// "Deprecated" in --help (CLI11 would print a hidden positional as "[]" in the usage line), with a warning.
template <typename T>
CLI::Option* addDeprecatedPositional(CLI::App& cmd, const std::string& name, T& target, const std::string& newName) {
  return cmd.add_option(name, target, "deprecated: give it as " + newName)
      ->group("Deprecated")
      ->each([name, newName](const std::string&) { warnDeprecated("the positional " + name, newName); });
}

/// Throws CLI11's "OPTION is required" (exit 2) when neither `option` nor the deprecated `oldName` was given.
inline void requireOneOf(const CLI::App& cmd, const std::string& option, const std::string& oldName) {
  if (cmd.count(option) + cmd.count(oldName) == 0) throw CLI::RequiredError(option);
}

}  // namespace srp::app
