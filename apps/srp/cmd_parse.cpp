// srp parse: instruction text -> task plan (readable, or --json), optionally
// stored in the task database.
#include <cstdio>
#include <iostream>

#include "CommandRegistry.h"
#include "srp/core/Error.h"
#include "srp/core/ExitCode.h"
#include "srp/core/Json.h"
#include "srp/language/InstructionParser.h"
#include "srp/language/PlanTables.h"
#include "srp/taskdb/TaskDatabase.h"

namespace {
// Index of the first byte that is not part of well-formed UTF-8 (RFC 3629), or npos.
std::size_t firstInvalidUtf8(const std::string& s) {
  std::size_t i = 0;
  while (i < s.size()) {
    const auto c = static_cast<unsigned char>(s[i]);
    std::size_t n = 0;
    unsigned min = 0, cp = 0;
    if (c < 0x80) { ++i; continue; }
    if ((c & 0xE0) == 0xC0) { n = 1; min = 0x80; cp = c & 0x1F; }
    else if ((c & 0xF0) == 0xE0) { n = 2; min = 0x800; cp = c & 0x0F; }
    else if ((c & 0xF8) == 0xF0) { n = 3; min = 0x10000; cp = c & 0x07; }
    else return i;
    for (std::size_t k = 1; k <= n; ++k) {
      if (i + k >= s.size()) return i;
      const auto t = static_cast<unsigned char>(s[i + k]);
      if ((t & 0xC0) != 0x80) return i;
      cp = (cp << 6) | (t & 0x3F);
    }
    if (cp < min || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF)) return i;
    i += n + 1;
  }
  return std::string::npos;
}

void setupParse(CLI::App& app) {
  auto text = std::make_shared<std::string>();
  auto modelPath = std::make_shared<std::string>();
  auto json = std::make_shared<bool>(false);
  auto showEntities = std::make_shared<bool>(false);
  app.add_option("text", *text, "the instruction, e.g. \"Pick up the cuboid and place it in the gray box.\"")
      ->required();
  app.add_option("--model", *modelPath,
                 "language model file (default: the shipped datasets/language/model/language_model.dat of srp's data folder)");
  app.add_flag("--json", *json, "print the plan as JSON ({\"steps\", \"sentences\", \"warnings\"})");
  auto knownPath = std::make_shared<std::string>();
  app.add_option("--known", *knownPath,
                 "plan JSON of an earlier instruction (srp parse --json), for \"back to\" and \"only the star\"")
      ->check(CLI::ExistingFile);
  auto dbPath = std::make_shared<std::string>();
  auto name = std::make_shared<std::string>("task");
  app.add_option("--db", *dbPath, "store the plan in this task database (one transaction; nothing on an empty plan)");
  app.add_option("--name", *name, "task model name for --db (re-using a name makes a new version)")->capture_default_str();
  app.add_flag("--entities", *showEntities, "also print the recognised entities and relations");
  app.callback([=] {
    if (const std::size_t bad = firstInvalidUtf8(*text); bad != std::string::npos) {
      char hex[8];
      std::snprintf(hex, sizeof hex, "0x%02X", static_cast<unsigned char>((*text)[bad]));
      throw srp::core::InvalidInputError("the instruction is not valid UTF-8 (byte " + std::to_string(bad) + " is " +
                                         hex + "); give it as UTF-8 text");
    }
    const srp::language::InstructionParser parser(modelPath->empty() ? srp::language::defaultModelPath() : *modelPath);
    std::vector<srp::language::PlanStep> known;
    if (!knownPath->empty()) known = srp::language::taskPlanFromJson(srp::core::readJsonFile(*knownPath)).steps;
    const auto plan = parser.parse(*text, known);
    if (*json) {
      std::cout << srp::language::toJson(plan).dump(2) << "\n";
    } else {
      std::cout << srp::language::describe(plan);
      if (*showEntities)
        for (const auto& s : plan.sentences) {
          for (const auto& e : s.entities) {
            std::cout << "  " << e.type << ":";
            for (int k = e.start; k < e.end; ++k) std::cout << " " << s.tokens[k];
            std::cout << "\n";
          }
          for (const auto& r : s.relations) std::cout << "  " << r.type << ": " << r.head << " -> " << r.tail << "\n";
        }
    }
    if (plan.steps.empty()) {
      if (!dbPath->empty()) std::cerr << "srp parse: nothing written to " << srp::taskdb::TaskDatabase::displayName(*dbPath) << " (the plan has no steps)\n";
      srp::app::commandExitCode() = srp::core::toInt(srp::core::ExitCode::Error);  // nothing to do is not success
    } else if (!dbPath->empty()) {
      const int id = srp::language::storePlan(plan, *dbPath, *name, *text);
      std::cerr << "stored as task model " << id << " in " << srp::taskdb::TaskDatabase::displayName(*dbPath) << "\n";
    }
  });
}
const srp::app::CommandRegistrar kReg{"parse", "Parse an instruction into a pick & place task plan", 20, setupParse};
}  // namespace
