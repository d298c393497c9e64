// srp: semantic robot programming. One executable, one subcommand per job;
// each subcommand is a thin front end over its module (see cmd_*.cpp).
#include <algorithm>
#include <exception>
#include <iostream>

#include "CommandRegistry.h"

int main(int argc, char** argv) {
  CLI::App app{
      "srp - teach a UR5 a multi-step pick & place task from one instruction and one RGB-D "
      "demonstration, then adapt and run it in simulation.",
      "srp"};
  app.set_version_flag("--version", std::string("srp ") + SRP_VERSION);
  app.require_subcommand(1);
  app.footer("Run 'srp <command> --help' for the options of a command.\n");

  auto& registry = srp::app::commandRegistry();
  std::stable_sort(registry.begin(), registry.end(),
                   [](const auto& a, const auto& b) { return a.order < b.order; });
  for (const auto& spec : registry) {
    CLI::App* sub = app.add_subcommand(spec.name, spec.description);
    spec.setup(*sub);
  }

  // CLI11 reports an unknown command as "A subcommand is required"; name it and the valid ones.
  const auto isCommand = [&](const std::string& name) {
    return std::any_of(registry.begin(), registry.end(), [&](const auto& spec) { return spec.name == name; });
  };
  if (argc > 1 && argv[1][0] != '-' && !isCommand(argv[1])) {
    std::string names;
    for (const auto& spec : registry) names += (names.empty() ? "" : ", ") + spec.name;
    std::cerr << "srp: unknown command '" << argv[1] << "'; the commands are: " << names
              << ". Run 'srp --help' for what each does.\n";
    return 2;
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
