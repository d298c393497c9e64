// srp db: create, inspect, import and export task databases (libs/taskdb).
#include <iomanip>
#include <iostream>
#include <sstream>

#include "CommandRegistry.h"
#include "CommonOptions.h"
#include "srp/core/Error.h"
#include "srp/core/Json.h"
#include "srp/core/OutputFile.h"
#include "srp/taskdb/TaskModelReport.h"
#include "srp/taskdb/TaskModelStore.h"

namespace {

using namespace srp::taskdb;

struct DbOptions {
  std::string db = srp::app::defaultTaskDatabase();
  int id = 0;
  bool json = false;
  std::string format = "appendix-c";
  std::string out;
  std::string file;
  std::string from;
  std::vector<int> ids;
  int maxRows = 0;
  bool overwrite = false;
};

void addDbOption(CLI::App& c, DbOptions& o) {
  c.add_option("--db", o.db, std::string("Task database: ") + srp::app::kTaskDatabaseHelp);
}

/// `--task ID` (the positional ID of earlier releases still works, with a warning).
void addTaskOption(CLI::App& c, int& id) {
  c.add_option("--task", id, "TaskModelId (see 'srp db list')")->check(srp::app::kDecimalId);
  srp::app::addDeprecatedPositional(c, "id", id, "--task")->check(srp::app::kDecimalId);
}

void requireTask(const CLI::App& c) { srp::app::requireOneOf(c, "--task", "id"); }

void setupDb(CLI::App& app) {
  auto o = std::make_shared<DbOptions>();
  app.require_subcommand(1);

  auto* init = app.add_subcommand("init", "Create an empty task database (or migrate an older one)");
  init->add_option("--db", o->db, std::string("Task database to create: ") + srp::app::kTaskDatabaseHelp);
  srp::app::addDeprecatedPositional(*init, "file", o->db, "--db");
  init->callback([o] {
    auto db = TaskDatabase::open(o->db);
    std::cout << "task database '" << db.path() << "' ready (schema version " << db.schemaVersion() << ")\n";
  });

  auto* list = app.add_subcommand("list", "List the task models");
  addDbOption(*list, *o);
  list->add_flag("--json", o->json, "Print JSON");
  list->callback([o] {
    auto db = TaskDatabase::open(o->db, TaskDatabase::Mode::ReadOnly);
    const auto models = TaskModelStore(db).list();
    if (o->json) {
      nlohmann::json j = nlohmann::json::array();
      for (const auto& m : models) j.push_back(toJson(m));
      std::cout << j.dump(2) << "\n";
      return;
    }
    if (models.empty()) {
      std::cout << "no task models in '" << db.path() << "' (program one with 'srp program')\n";
      return;
    }
    std::cout << std::left << std::setw(5) << "id" << std::setw(24) << "name" << std::setw(9) << "version"
              << std::setw(22) << "created (UTC)" << "instruction\n";
    for (const auto& m : models) {
      std::string text = m.instruction.size() > 60 ? m.instruction.substr(0, 57) + "..." : m.instruction;
      std::cout << std::setw(5) << m.id << std::setw(24) << m.name << std::setw(9) << m.version << std::setw(22)
                << m.createdUtc << text << "\n";
    }
  });

  auto* show = app.add_subcommand("show", "Show one task model: plan, grounded objects, skills");
  addTaskOption(*show, o->id);
  addDbOption(*show, *o);
  show->add_flag("--json", o->json, "Print the whole task model as JSON (the form 'srp db import' reads)");
  show->callback([o, show] {
    requireTask(*show);
    auto db = TaskDatabase::open(o->db, TaskDatabase::Mode::ReadOnly);
    const TaskModel m = TaskModelStore(db).read(o->id);
    if (o->json) std::cout << toJson(m).dump(2) << "\n";
    else printTaskModel(m, std::cout);
  });

  auto* exp = app.add_subcommand("export", "Export a task model in another layout");
  addTaskOption(*exp, o->id);
  addDbOption(*exp, *o);
  exp->add_option("--format", o->format, "Layout: appendix-c (the thesis' Appendix C tables) or json")
      ->check(CLI::IsMember({"appendix-c", "json"}))
      ->capture_default_str();
  exp->add_option("-o,--out", o->out, "Output file (default: standard output); written whole or not at all");
  exp->add_option("--max-rows", o->maxRows, "Abbreviate long tables to this many rows with '...' (0: all)");
  srp::app::addOverwriteFlag(*exp, o->overwrite);
  exp->callback([o, exp] {
    requireTask(*exp);
    srp::core::checkOutputPaths({{"--out", o->out}}, {{"--db", o->db}}, o->overwrite);
    auto db = TaskDatabase::open(o->db, TaskDatabase::Mode::ReadOnly);
    const TaskModel m = TaskModelStore(db).read(o->id);
    std::ostringstream out;
    if (o->format == "json") out << toJson(m).dump(2) << "\n";
    else writeAppendixC(m, out, o->maxRows);
    if (o->out.empty()) std::cout << out.str();
    else srp::core::writeFileAtomically(o->out, out.str());
  });

  auto* imp = app.add_subcommand(
      "import", "Store a task model from its JSON form as a new task model, or copy task models from another task "
                "database (--from: an SQLite file to a server, or back)");
  auto* file = imp->add_option("file", o->file, "Task model JSON (e.g. datasets/examples/appendix_c_instruction1.json)")
                   ->check(CLI::ExistingFile);
  auto* from = imp->add_option("--from", o->from,
                               "Copy every task model (or the --id ones) of this task database (an SQLite file or a "
                               "postgresql:// URI) into --db, with every row, name, version and creation time, in one "
                               "transaction");
  imp->add_option("--id", o->ids, "With --from: copy only these TaskModelIds (repeatable)")->needs(from);
  file->excludes(from);
  addDbOption(*imp, *o);
  imp->callback([o] {
    if (!o->from.empty()) {
      auto source = TaskDatabase::open(o->from, TaskDatabase::Mode::ReadOnly);
      auto target = TaskDatabase::open(o->db);
      const auto copied = copyTaskModels(source, target, o->ids);
      std::cout << "copied " << copied.size() << " task model" << (copied.size() == 1 ? "" : "s") << " from '"
                << source.path() << "' to '" << target.path() << "'";
      for (const auto& [was, now] : copied) std::cout << (was == copied.front().first ? ": " : ", ") << was << " -> " << now;
      std::cout << "\n";
      return;
    }
    if (o->file.empty())
      throw srp::core::InvalidInputError("give a task model JSON file or --from DATABASE (see 'srp db import --help')");
    const TaskModel m = taskModelFromJson(srp::core::readJsonFile(o->file), o->file);
    auto db = TaskDatabase::open(o->db);
    const int id = TaskModelStore(db).write(m);
    std::cout << "stored '" << m.info.name << "' as task model " << id << " in '" << db.path() << "'\n";
  });

  auto* del = app.add_subcommand("delete", "Delete a task model and all its rows");
  addTaskOption(*del, o->id);
  addDbOption(*del, *o);
  del->callback([o, del] {
    requireTask(*del);
    auto db = TaskDatabase::open(o->db);
    TaskModelStore(db).remove(o->id);
    std::cout << "deleted task model " << o->id << "\n";
  });
}

const srp::app::CommandRegistrar kDb{"db", "Create, inspect, import and export task databases", 90, setupDb};

}  // namespace
