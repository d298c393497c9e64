// srp motion: segment a stored task model's demo into skills, learn the Reach
// and Move DMPs, store them in its Skills table, and plot each object (libs/motion).
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <optional>
#include <nlohmann/json.hpp>

#include "CommandRegistry.h"
#include "CommonOptions.h"
#include "srp/core/Error.h"
#include "srp/core/OutputFile.h"
#include "srp/core/SafeText.h"
#include "srp/motion/SkillLearner.h"
#include "srp/motion/SkillPlots.h"
#include "srp/motion/SyntheticPickPlace.h"
#include "srp/programming/MotionRows.h"
#include "srp/taskdb/TaskModelStore.h"

namespace {

struct MotionOptions {
  int id = 0;
  std::string db = srp::app::defaultTaskDatabase();
  std::string outDir;
  bool json = false;
  bool noPlots = false;
  bool syntheticDemo = false;
  bool overwrite = false;
};

void runMotion(const MotionOptions& o) {
  using namespace srp;
  // The plot folder is checked before anything is stored, and built beside its target.
  const std::string dir = o.outDir.empty() ? "motion_" + std::to_string(o.id) : o.outDir;
  std::optional<core::AtomicOutputFolder> plots;
  if (!o.noPlots && !o.syntheticDemo) {
    core::checkOutputPaths({{"--out", dir}}, {{"--db", o.db}}, o.overwrite);
    core::checkFolderHoldsOnly(dir, {"*.png"}, "--out");
    plots.emplace(std::filesystem::path(dir).lexically_normal());
  }
  auto db = taskdb::TaskDatabase::open(o.db);
  taskdb::TaskModelStore store(db);
  int id = o.id;
  if (o.syntheticDemo) {
    const auto demo = motion::SyntheticPickPlaceGenerator().generate();
    id = store.write(programming::taskModelFromTracks(demo, "synthetic-demo", demo.instruction()));
    if (!app::quietFlag()) std::cerr << "srp motion: stored a synthetic 4-object demo as task model " << id << "\n";
  } else if (id <= 0) {
    throw core::InvalidInputError("give --task ID (see 'srp db list') or --synthetic-demo");
  }
  const taskdb::TaskModel model = store.read(id);
  if (!app::quietFlag())
    std::cerr << "srp motion: task model " << id << " '" << model.info.name << "': segmenting "
              << model.handPositions.size() << " hand positions\n";
  const programming::MotionInputs inputs = programming::motionInputsFromTaskModel(model);
  if (!app::quietFlag()) std::cerr << "srp motion: segmenting and learning DMPs\n";
  const motion::LearnedSkills learned = motion::learnSkills(inputs);
  const auto& seg = learned.segmentation;
  const auto& skills = learned.skills;
  const auto rows = programming::skillRows(skills, inputs);
  programming::storeSkills(db, id, skills, inputs);  // one transaction, after everything above succeeded

  std::vector<std::string> pngs;
  if (!o.noPlots) {
    if (!plots) {  // --synthetic-demo: the id is known only now
      const std::string out = o.outDir.empty() ? "motion_" + std::to_string(id) : o.outDir;
      core::checkOutputPaths({{"--out", out}}, {{"--db", o.db}}, o.overwrite);
      core::checkFolderHoldsOnly(out, {"*.png"}, "--out");
      plots.emplace(std::filesystem::path(out).lexically_normal());
    }
    const std::string staged = plots->temporaryPath().string();
    for (const auto& s : skills)
      for (const auto& obj : seg.objects)
        if (obj.name == s.objectName) {
          const std::string file = "/" + core::safeFileName(s.objectName) + ".png";
          motion::writeSkillFigure(staged + file, seg, obj, s);
          pngs.push_back(plots->target().string() + file);
        }
    plots->commit();
  }
  if (o.json) {
    nlohmann::json objects = nlohmann::json::array();
    for (const auto& obj : seg.objects) {
      nlohmann::json j{{"name", obj.name}, {"moved", obj.moved}};
      if (obj.moved) j["grasp_frame"] = obj.graspFrame, j["release_frame"] = obj.releaseFrame;
      for (const auto& s : skills)
        if (s.objectName == obj.name) j["reach_lambda"] = s.reach->lambda(), j["move_lambda"] = s.move->lambda();
      if (!obj.note.empty()) j["note"] = obj.note;
      objects.push_back(j);
    }
    std::cout << nlohmann::json{{"task_model_id", id}, {"skills_stored", rows.size()}, {"objects", objects},
                                {"plots", pngs}}
                     .dump(2)
              << "\n";
    return;
  }
  std::cout << std::left << std::setw(16) << "object" << std::setw(8) << "grasp" << std::setw(9) << "release"
            << std::setw(14) << "reach lambda" << "move lambda\n";
  for (const auto& obj : seg.objects) {
    std::cout << std::setw(16) << obj.name;
    if (!obj.moved) {
      std::cout << "not moved (" << obj.note << ")\n";
      continue;
    }
    std::cout << std::setw(8) << obj.graspFrame << std::setw(9) << obj.releaseFrame;
    for (const auto& s : skills)
      if (s.objectName == obj.name) std::cout << std::setw(14) << s.reach->lambda() << s.move->lambda();
    std::cout << "\n";
  }
  std::cout << rows.size() << " skills stored in task model " << id << " of '" << o.db << "'\n";
  for (const auto& p : pngs) std::cout << "wrote " << p << "\n";
}

void setupMotion(CLI::App& app) {
  auto o = std::make_shared<MotionOptions>();
  app.add_option("--task", o->id, "TaskModelId (see 'srp db list')")->check(srp::app::kDecimalId);
  srp::app::addDeprecatedPositional(app, "id", o->id, "--task")->check(srp::app::kDecimalId);
  app.add_flag("--synthetic-demo", o->syntheticDemo,
               "First store a synthetic 4-object demo (noise, dropouts, flicker) as a new task model, then process it");
  app.add_option("--db", o->db, std::string("Task database: ") + srp::app::kTaskDatabaseHelp);
  app.add_option("-o,--out", o->outDir,
                 "Directory for the PNG per object (default: motion_<id>), written whole or not at all");
  srp::app::addDeprecatedOption(app, "--out-dir", o->outDir, "--out");
  app.add_flag("--no-plots", o->noPlots, "Do not write PNGs");
  app.add_flag("--json", o->json, "Print the result as JSON");
  srp::app::addOverwriteFlag(app, o->overwrite);
  app.callback([o] { runMotion(*o); });
}

const srp::app::CommandRegistrar kReg{
    "motion", "Segment a task model's demo into Reach/Grasp/Move/Release, learn and store the DMPs, plot them", 45,
    setupMotion};

}  // namespace
