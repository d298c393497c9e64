#pragma once
/// \file CommandRegistry.h
/// \brief Self-registering subcommands of the `srp` executable.
///
/// A command file defines a setup function that adds options and a callback to
/// its CLI11 subcommand, and registers it with a static CommandRegistrar:
/// \code
///   static const srp::app::CommandRegistrar kDb{"db", "Inspect and export the task database", 10, setupDb};
/// \endcode
/// The callback throws on error; main() prints "srp <cmd>: error: <message>" and exits 1.

#include <CLI/CLI.hpp>
#include <cstdlib>
#include <functional>
#include <string>
#include <vector>

namespace srp::app {

struct CommandSpec {
  std::string name;
  std::string description;
  int order = 100;  ///< position in `srp --help`
  std::function<void(CLI::App&)> setup;
};

std::vector<CommandSpec>& commandRegistry();

struct CommandRegistrar {
  CommandRegistrar(std::string name, std::string description, int order,
                   std::function<void(CLI::App&)> setup);
};

/// A TaskModelId: decimal digits only (CLI11 would read "0x1" as 1 and "1e0" as 1).
inline const CLI::Validator kDecimalId(
    [](std::string& text) -> std::string {
      const bool digits = !text.empty() && text.size() <= 9 &&
                          text.find_first_not_of("0123456789") == std::string::npos;
      return digits ? std::string() : "'" + text + "' is not a TaskModelId (a decimal number, see 'srp db list')";
    },
    "ID");

/// The task database when --db is not given: $SRP_DB (a file or a
/// postgresql:// URI), else task.db. Options show it as "SRP_DB or task.db",
/// never the value (it may hold a password).
inline std::string defaultTaskDatabase() {
  const char* env = std::getenv("SRP_DB");
  return env && *env ? env : "task.db";
}
inline const char* kTaskDatabaseHelp =
    "an SQLite file, or a PostgreSQL server as postgresql://user@host:port/dbname (password from ~/.pgpass, "
    "PGPASSFILE or PGPASSWORD); default: $SRP_DB, else task.db";

/// `-w,--overwrite` on a command that writes files: an existing output is
/// replaced only when it is given (core::checkOutputPaths refuses it otherwise).
inline CLI::Option* addOverwriteFlag(CLI::App& cmd, bool& overwrite) {
  return cmd.add_flag("-w,--overwrite", overwrite,
                      "Replace existing output files (without it an existing output is refused, naming the file)");
}

/// Exit code a command can request (srp/core/ExitCode.h; e.g. 3 for "done, but with skipped steps").
int& commandExitCode();

}  // namespace srp::app
