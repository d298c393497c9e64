// `srp kb`: the knowledge base (object classes and their CAD meshes).
#include <iostream>

#include <nlohmann/json.hpp>

#include "CommandRegistry.h"
#include "srp/core/ObjectCatalogue.h"
#include "srp/kb/KnowledgeBase.h"

namespace {

void setupKb(CLI::App& cmd) {
  auto cataloguePath = std::make_shared<std::string>(srp::core::ObjectCatalogue::defaultPath());
  auto json = std::make_shared<bool>(false);
  cmd.require_subcommand(1);

  auto* build = cmd.add_subcommand("build", "Generate the STL mesh of every catalogue class with a shape generator");
  build->add_option("--catalogue", *cataloguePath, "catalogue JSON (default: the bundled one)");
  build->callback([cataloguePath]() {
    const auto catalogue = srp::core::ObjectCatalogue::load(*cataloguePath);
    for (const auto& m : srp::kb::buildMeshes(catalogue))
      std::cout << m.className << ": " << m.triangleCount << " triangles -> " << m.path << "\n";
  });

  auto* list = cmd.add_subcommand("list", "List the catalogue classes");
  list->add_option("--catalogue", *cataloguePath, "catalogue JSON (default: the bundled one)");
  list->add_flag("--json", *json, "machine-readable output");
  list->callback([cataloguePath, json]() {
    const auto catalogue = srp::core::ObjectCatalogue::load(*cataloguePath);
    nlohmann::json out = nlohmann::json::array();
    for (const auto& c : catalogue.classes()) {
      if (*json) {
        out.push_back({{"name", c.name}, {"class_id", c.classId}, {"kind", srp::core::toString(c.kind)},
                       {"shape", c.shape}, {"dimensions_m", {c.dimensions_m.x(), c.dimensions_m.y(), c.dimensions_m.z()}},
                       {"mesh", c.meshPath}});
      } else {
        std::cout << c.classId << "  " << c.name << "  (" << c.shape << ", " << c.dimensions_m.x() << " x "
                  << c.dimensions_m.y() << " x " << c.dimensions_m.z() << " m)  " << c.meshPath << "\n";
      }
    }
    if (*json) std::cout << out.dump(2) << "\n";
  });
}

const srp::app::CommandRegistrar kReg{"kb", "Knowledge base: list classes, generate their CAD meshes", 15, setupKb};

}  // namespace
