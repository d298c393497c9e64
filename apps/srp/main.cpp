// srp: semantic robot programming. One executable, one subcommand per job;
// each subcommand is a thin front end over its module (see cmd_*.cpp).
#include <algorithm>
#include <exception>
#include <functional>
#include <iostream>
#include <string>

#include "CommandRegistry.h"
#include "CommonOptions.h"
#include "srp/core/DataPaths.h"
#include "srp/core/Log.h"

namespace {

/// `--data-dir DIR` on `srp` and on every command (before or after the command's name).
void addDataDirOption(CLI::App& app) {
  app.add_option_function<std::string>(
         "--data-dir", [](const std::string& dir) { srp::core::DataPaths::setDataDir(dir); },
         "srp's data folder (knowledge base, language model, scenes, UR5 model, cameras); default: SRP_DATA_DIR, "
         "else <prefix>/share/srp of an installed srp, else the source tree of a build folder")
      ->type_name("DIR");
  for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; })) addDataDirOption(*sub);
}

std::string dataFolderLine() {
  const auto root = srp::core::DataPaths::find();
  if (!root) return "Data folder: not found; give --data-dir DIR or set SRP_DATA_DIR.\n";
  return "Data folder: " + root->dir.string() + " (" + srp::core::DataPaths::describe(root->origin) + ").\n";
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "srp - teach a UR5 a multi-step pick & place task from one instruction and one RGB-D "
      "demonstration, then adapt and run it in simulation.",
      "srp"};
  app.set_version_flag("--version", std::string("srp ") + SRP_VERSION);
  app.require_subcommand(1);
  app.footer([] {
    std::string categories;
    for (const auto& [name, what] : srp::core::Log::categories())
      categories += "      " + name + std::string(name.size() < 11 ? 11 - name.size() : 1, ' ') + what + "\n";
    return "Run 'srp <command> --help' for the options of a command.\n" + dataFolderLine() +
           "\nEvery command takes:\n"
           "  -o, --out        its main output (file or folder), where it writes one\n"
           "  -w, --overwrite  replace existing outputs (refused otherwise, naming the file)\n"
           "  --json           the result as JSON on stdout, where the result is data\n"
           "  -q, --quiet      no progress lines (progress is drawn only on a terminal anyway)\n"
           "  -v, --verbose    debug lines of every log category (= --log-level debug)\n"
           "  --log-level SPEC a level (trace, debug, info, warning, error, off) and/or CATEGORY=LEVEL pairs:\n" +
           categories +
           "  --data-dir DIR   srp's data folder\n"
           "Spellings of earlier releases (--catalogue, --report, --export, --csv, --out-dir, --task-id, --calib, "
           "positional outputs and ids) still work and print a deprecation warning.\n"
           "\nExit codes:\n"
           "  0  done: the command did all of its job\n"
           "  1  error: it could not do its job (bad input, a failed step); it says which and why\n"
           "  2  usage: the command line is wrong (unknown command or option, missing argument)\n"
           "  3  finished, but some steps were skipped or refused (srp execute: the report says which and why)\n";
  });

  auto& registry = srp::app::commandRegistry();
  std::stable_sort(registry.begin(), registry.end(),
                   [](const auto& a, const auto& b) { return a.order < b.order; });
  for (const auto& spec : registry) {
    CLI::App* sub = app.add_subcommand(spec.name, spec.description);
    spec.setup(*sub);
  }
  addDataDirOption(app);
  srp::app::addVerbosityOptions(app);

  // An unknown command name: CLI11 would say only "A subcommand is required"
  // or "argument was not expected"; name it and list the commands instead.
  {
    CLI::App* level = &app;
    std::string path;
    for (int i = 1; i < argc; ++i) {
      const std::string token = argv[i];
      if (token.empty() || token[0] == '-') break;  // options (and their values) are CLI11's
      const auto subs = level->get_subcommands([](CLI::App*) { return true; });
      const auto it = std::find_if(subs.begin(), subs.end(), [&](CLI::App* s) { return s->get_name() == token; });
      if (it != subs.end()) {
        level = *it;
        path += " " + token;
        continue;
      }
      if (level->get_require_subcommand_min() > 0) {
        std::string names;
        for (const CLI::App* s : subs) names += (names.empty() ? "" : ", ") + s->get_name();
        std::cerr << "srp" << path << ": error: unknown command '" << token << "' (commands: " << names
                  << "; see 'srp" << path << " --help')\n";
        return 2;  // a usage error, like CLI11's parse errors below
      }
      break;
    }
  }

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help and --version are successes; every other parse error is a usage error (exit 2).
    const int rc = app.exit(e);
    return rc == 0 ? 0 : 2;
  } catch (const std::exception& e) {
    std::string cmd;
    for (const CLI::App* level = &app; !level->get_subcommands().empty();) {
      level = level->get_subcommands().front();
      cmd += " " + level->get_name();
    }
    std::cerr << "srp" << cmd << ": error: " << e.what() << "\n";
    return 1;
  }
  return srp::app::commandExitCode();
}
