#include "CommonOptions.h"

#include <unistd.h>

#include "srp/core/Error.h"
#include "srp/core/Log.h"

namespace srp::app {

bool& quietFlag() {
  static bool quiet = false;
  return quiet;
}

bool progressWanted(bool json) { return !json && !quietFlag() && isatty(STDERR_FILENO) != 0; }

void warnDeprecated(const std::string& oldSpelling, const std::string& newSpelling) {
  core::Log::write("srp", core::Log::Level::Warning,
                   "'" + oldSpelling + "' is deprecated and will be removed; use '" + newSpelling + "'");
}

void addVerbosityOptions(CLI::App& cmd) {
  std::string categories;
  for (const auto& [name, what] : core::Log::categories()) categories += (categories.empty() ? "" : ", ") + name;
  if (!cmd.get_option_no_throw("--quiet"))
    cmd.add_flag_callback(
        "-q,--quiet",
        [] {
          quietFlag() = true;
          core::Log::setLevels("warning");
        },
        "No progress lines; only warnings and errors on stderr");
  if (!cmd.get_option_no_throw("--verbose"))
    cmd.add_flag_callback(
        "-v,--verbose", [] { core::Log::setLevels("debug"); }, "Debug lines of every log category (--log-level debug)");
  if (!cmd.get_option_no_throw("--log-level"))
    cmd.add_option_function<std::string>(
           "--log-level",
           [](const std::string& spec) {
             try {
               core::Log::setLevels(spec);
             } catch (const core::Error& e) {
               throw CLI::ValidationError("--log-level", e.what());  // a usage error: exit 2
             }
           },
           "trace, debug, info (default), warning, error or off, and/or CATEGORY=LEVEL pairs, comma-separated; "
           "categories: " +
               categories)
        ->type_name("SPEC");
  for (CLI::App* sub : cmd.get_subcommands([](CLI::App*) { return true; })) addVerbosityOptions(*sub);
}

}  // namespace srp::app
