#include "CommandRegistry.h"

namespace srp::app {

std::vector<CommandSpec>& commandRegistry() {
  static std::vector<CommandSpec> registry;
  return registry;
}

CommandRegistrar::CommandRegistrar(std::string name, std::string description, int order,
                                   std::function<void(CLI::App&)> setup) {
  commandRegistry().push_back({std::move(name), std::move(description), order, std::move(setup)});
}

int& commandExitCode() {
  static int code = 0;
  return code;
}

}  // namespace srp::app
