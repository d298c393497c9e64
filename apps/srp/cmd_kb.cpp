// `srp kb`: the knowledge base (object classes and their CAD meshes).
#include <cstdio>
#include <filesystem>
#include <iostream>

#include <nlohmann/json.hpp>

#include "CommandRegistry.h"
#include "CommonOptions.h"
#include "srp/core/Error.h"
#include "srp/core/ObjectCatalogue.h"
#include "srp/core/OutputFile.h"
#include "srp/kb/KnowledgeBase.h"
#include "srp/kb/MeshValidator.h"
#include "srp/perception/ObjectDiscovery.h"

namespace {

void setupKb(CLI::App& cmd) {
  auto cataloguePath = std::make_shared<std::string>();  // empty: the shipped catalogue
  auto json = std::make_shared<bool>(false);
  cmd.require_subcommand(1);
  const auto catalogueOrShipped = [cataloguePath] {
    return cataloguePath->empty() ? srp::core::ObjectCatalogue::defaultPath() : *cataloguePath;
  };

  auto* build = cmd.add_subcommand("build", "Generate the STL mesh of every catalogue class with a shape generator");
  auto outDir = std::make_shared<std::string>();
  build->add_option("--kb", *cataloguePath,
                    "catalogue JSON (default: the shipped datasets/kb/catalogue.json of srp's data folder)");
  srp::app::addDeprecatedOption(*build, "--catalogue", *cataloguePath, "--kb");
  build->add_option("-o,--out", *outDir,
                    "folder to write a copy of the catalogue and its meshes/ into (default: beside the --kb "
                    "given; with the shipped catalogue, the current folder)");
  build->footer("Example: srp kb build -o my_kb   (my_kb/catalogue.json and my_kb/meshes/*.stl, to edit and use "
                "with --kb my_kb/catalogue.json)");
  auto overwrite = std::make_shared<bool>(false);
  srp::app::addOverwriteFlag(*build, *overwrite);
  auto buildJson = std::make_shared<bool>(false);
  build->add_flag("--json", *buildJson, "print the meshes written (class, triangles, file) as JSON");
  build->callback([cataloguePath, outDir, catalogueOrShipped, overwrite, buildJson]() {
    const std::string path = catalogueOrShipped();
    const std::string dir = !outDir->empty() ? *outDir : cataloguePath->empty() ? "." : "";
    const auto catalogue = srp::kb::loadCatalogue(path);
    std::vector<srp::core::PathRole> outputs;
    for (const auto& c : catalogue.classes())
      if (srp::kb::hasShapeGenerator(c.shape))
        outputs.push_back({"mesh of '" + c.name + "'",
                           dir.empty() ? std::filesystem::path(c.meshPath)
                                       : std::filesystem::path(dir) / "meshes" / std::filesystem::path(c.meshPath).filename()});
    if (!dir.empty())
      outputs.push_back({"catalogue copy", std::filesystem::path(dir) / std::filesystem::path(path).filename()});
    srp::core::checkOutputPaths(outputs, {{"--kb", path}}, *overwrite);
    if (!dir.empty()) std::filesystem::create_directories(dir);
    nlohmann::json meshes = nlohmann::json::array();
    for (const auto& m : srp::kb::buildMeshes(catalogue, dir)) {
      if (*buildJson) meshes.push_back({{"class", m.className}, {"triangles", m.triangleCount}, {"mesh", m.path}});
      else std::cout << m.className << ": " << m.triangleCount << " triangles -> " << m.path << "\n";
    }
    const std::string copy = dir.empty() ? "" : srp::kb::copyCatalogue(path, dir).string();
    if (*buildJson)
      std::cout << nlohmann::json{{"meshes", meshes}, {"catalogue", copy.empty() ? path : copy}}.dump(2) << "\n";
    else if (!copy.empty()) std::cout << "catalogue -> " << copy << "\n";
  });

  auto* add = cmd.add_subcommand(
      "add", "Add a part or container: from its CAD file (STL, OBJ, PLY, glTF, COLLADA), or without one as a box");
  auto entry = std::make_shared<srp::kb::MeshClassEntry>();
  auto rgb = std::make_shared<std::vector<double>>();
  auto mass = std::make_shared<double>(0.0);
  auto shape = std::make_shared<std::string>();
  auto size = std::make_shared<std::vector<double>>();
  add->add_option("--kb", *cataloguePath, "catalogue JSON to add to (created when missing)");
  srp::app::addDeprecatedOption(*add, "--catalogue", *cataloguePath, "--kb");
  add->add_option("name,--name", entry->name, "class name, unique in the catalogue")->required();
  auto* mesh = add->add_option("--mesh", entry->meshPath,
                               "CAD file in metres; its frame becomes the class's object frame (+z up when the part rests)")
                   ->check(CLI::ExistingFile);
  auto* box = add->add_option("--shape", *shape, "a part without a CAD file: box (catalogue shape \"cuboid\"), with --size")
                  ->check(CLI::IsMember({"box"}));
  add->add_option("--size", *size, "box sides x y z in metres, each from 0.001 to 2 (x the longest horizontal side)")
      ->expected(3)
      ->needs(box);
  mesh->excludes(box);
  auto demo = std::make_shared<std::string>();
  auto at = std::make_shared<std::vector<double>>();
  auto frame = std::make_shared<int>(0);
  auto* fromDemo = add->add_option("--from-demo", *demo,
                                   "a part or container without a CAD file, measured in a recording (rawlog): the box "
                                   "of what stands on the table at --at in --frame (x its longer side)")
                       ->check(CLI::ExistingFile)
                       ->excludes(mesh)
                       ->excludes(box);
  auto* atOption = add->add_option("--at", *at, "U,V: a pixel of the object in that frame (srp replay --export shows "
                                                "the frames)")
                       ->expected(2)
                       ->delimiter(',')
                       ->needs(fromDemo);
  fromDemo->needs(atOption);
  add->add_option("--frame", *frame, "the frame to measure it in, counted from 0")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber)
      ->needs(fromDemo);
  add->add_option("--id", entry->classId, "class_id (default: the next free one)");
  add->add_option("--noun", entry->noun, "head noun in instructions (default: the name)");
  add->add_option("--kind", entry->kind, "part or container")->check(CLI::IsMember({"part", "container"}))->capture_default_str();
  add->add_option("--rgb", *rgb, "linear RGB in [0, 1] when the colour identifies the part (default: none)")->expected(3);
  add->add_option("--mass", *mass, "mass [kg] (default: the mesh's or the box's volume at 1000 kg/m^3; --from-demo: "
                                   "at 150 kg/m^3, a container 0.3 kg)");
  auto units = std::make_shared<std::string>("m");
  add->add_option("--units", *units, "length unit of the CAD file: m, cm, mm or in (the part must be 1 mm - 2 m)")
      ->check(CLI::IsMember({"m", "cm", "mm", "in"}))
      ->capture_default_str()
      ->excludes(box);
  add->add_option("--scale", entry->scale, "metres per file unit, instead of --units (e.g. 0.001)")
      ->excludes("--units")
      ->excludes(box)
      ->check(CLI::PositiveNumber);
  add->add_flag("--flat", entry->flat, "a flat part (a sheet, a label): its mesh need not enclose a volume")
      ->excludes(box);
  add->add_flag("--json", *json, "machine-readable output");
  add->footer(
      "Examples:\n  srp kb add --kb my_parts.json --name cube --mesh cube.obj\n"
      "  srp kb add toy --kb my_parts.json --shape box --size 0.12 0.08 0.06 --rgb 0.1 0.2 0.7\n"
      "  srp kb add toy --kb my_parts.json --from-demo demo.rawlog --at 410,260");
  add->callback([add, cataloguePath, entry, rgb, mass, shape, size, json, units, demo, at, frame]() {
    srp::app::requireOneOf(*add, "--kb", "--catalogue");
    if (rgb->size() == 3) entry->rgb = Eigen::Vector3d((*rgb)[0], (*rgb)[1], (*rgb)[2]);
    if (add->count("--mass")) entry->mass_kg = *mass;
    if (!add->count("--scale")) entry->scale = srp::kb::unitScale(*units);
    if (entry->meshPath.empty() && shape->empty() && demo->empty())
      throw srp::core::InvalidInputError("srp kb add: give the part's CAD file (--mesh FILE) or, without one, its box "
                                         "(--shape box --size X Y Z, metres, or --from-demo REC --at U,V)");
    std::vector<std::string> warnings;
    srp::core::ObjectClass c;
    std::optional<srp::perception::ObjectDiscovery::Measured> measured;
    if (!demo->empty())
      measured = srp::perception::ObjectDiscovery::measureInRecording(*demo, *frame, {(*at)[0], (*at)[1]},
                                                                      srp::perception::ObjectDiscovery::Options{});
    if (!shape->empty() || measured) {
      if (!measured && size->size() != 3)
        throw srp::core::InvalidInputError("srp kb add: --shape box needs --size X Y Z (metres)");
      srp::kb::BoxClassEntry b;
      b.name = entry->name;
      b.classId = entry->classId;
      b.noun = entry->noun;
      b.kind = entry->kind;
      b.size_m = measured ? measured->size_m : Eigen::Vector3d((*size)[0], (*size)[1], (*size)[2]);
      b.rgb = entry->rgb || !measured ? entry->rgb : std::optional<Eigen::Vector3d>(measured->rgb);
      b.mass_kg = entry->mass_kg;
      if (measured && !b.mass_kg) {  // an object seen, of unknown material: as the demonstration's discovery weighs it
        const srp::perception::ObjectDiscovery::Options seen;
        b.mass_kg = b.kind == "container" ? seen.containerMass_kg : b.size_m.prod() * seen.partDensity_kg_m3;
      }
      c = srp::kb::addBoxClass(*cataloguePath, b);
    } else {
      c = srp::kb::addMeshClass(*cataloguePath, *entry, &warnings);
    }
    for (const auto& w : warnings) std::cerr << "srp kb add: warning: " << w << "\n";
    const Eigen::Vector3d& d = c.dimensions_m;
    std::string from = c.meshPath.empty() ? "a box without a mesh" : "mesh " + c.meshPath;
    if (measured)
      from += ", measured at (" + std::to_string(static_cast<int>((*at)[0])) + ", " +
              std::to_string(static_cast<int>((*at)[1])) + ") of frame " + std::to_string(*frame) + " of " + *demo +
              " (" + std::to_string(measured->points) + " points, mostly " + measured->colourWord + ")";
    if (*json) {
      std::cout << nlohmann::json{{"catalogue", *cataloguePath}, {"name", c.name}, {"class_id", c.classId},
                                  {"kind", srp::core::toString(c.kind)}, {"shape", c.shape}, {"mesh", c.meshPath},
                                  {"dimensions_m", {d.x(), d.y(), d.z()}}, {"mass_kg", c.mass_kg},
                                  {"measured_from", measured ? nlohmann::json{{"rawlog", *demo}, {"frame", *frame},
                                                                              {"at_px", *at},
                                                                              {"colour", measured->colourWord},
                                                                              {"points", measured->points}}
                                                             : nlohmann::json()},
                                  {"warnings", warnings}}
                       .dump(2)
                << "\n";
      return;
    }
    std::printf("added '%s' (class_id %d, %s) to %s: %.4f x %.4f x %.4f m, %.3f kg, %s\n", c.name.c_str(), c.classId,
                srp::core::toString(c.kind).c_str(), cataloguePath->c_str(), d.x(), d.y(), d.z(), c.mass_kg,
                from.c_str());
  });

  auto* list = cmd.add_subcommand("list", "List the catalogue classes");
  list->add_option("--kb", *cataloguePath,
                   "catalogue JSON (default: the shipped datasets/kb/catalogue.json of srp's data folder)");
  srp::app::addDeprecatedOption(*list, "--catalogue", *cataloguePath, "--kb");
  list->add_flag("--json", *json, "machine-readable output");
  list->callback([catalogueOrShipped, json]() {
    const auto catalogue = srp::kb::loadCatalogue(catalogueOrShipped());
    nlohmann::json out = nlohmann::json::array();
    for (const auto& c : catalogue.classes()) {
      if (*json) {
        out.push_back({{"name", c.name}, {"class_id", c.classId}, {"kind", srp::core::toString(c.kind)},
                       {"shape", c.shape}, {"dimensions_m", {c.dimensions_m.x(), c.dimensions_m.y(), c.dimensions_m.z()}},
                       {"mesh", c.meshPath}});
      } else {
        std::cout << c.classId << "  " << c.name << "  (" << (c.shape.empty() ? "mesh" : c.shape) << ", " << c.dimensions_m.x() << " x "
                  << c.dimensions_m.y() << " x " << c.dimensions_m.z() << " m)  " << c.meshPath << "\n";
      }
    }
    if (*json) std::cout << out.dump(2) << "\n";
  });
}

const srp::app::CommandRegistrar kReg{"kb", "Knowledge base: list classes, add a CAD part, generate meshes", 15, setupKb};

}  // namespace
