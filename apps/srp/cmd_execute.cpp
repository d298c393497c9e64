// srp execute: run a stored task model on the simulated UR5 cell (libs/execution).
#include <iostream>
#include <nlohmann/json.hpp>

#include "CommandRegistry.h"
#include "srp/core/Error.h"
#include "srp/core/ViewFrame.h"
#include "srp/execution/ExecutionSession.h"

namespace {

struct ExecuteOptions {
  std::string db = "task.db";
  int task = 0;
  std::string instruction;
  std::string scene;
  std::string out = "execution";
  int framePeriod = 10;
  bool json = false;
  std::string view = "demonstrator";
};

void setupExecute(CLI::App& app) {
  auto o = std::make_shared<ExecuteOptions>();
  app.add_option("--db", o->db, "Task database file (opened read-only)")->capture_default_str();
  app.add_option("--task", o->task, "Task model id (see 'srp db list')")->required();
  app.add_option("--instruction", o->instruction, "A new instruction that re-plans the task (Language Module)");
  app.add_option("--scene", o->scene, "Current scene JSON (default: sim/scenes/default.json)");
  app.add_option("--out", o->out, "Output folder: report.json, report.txt, joints.csv, final_scene.json (the scene after execution, for --scene of the next run), frames/*.png")
      ->capture_default_str();
  app.add_option("--frame-period", o->framePeriod, "Render every n-th 20 ms snapshot (0: no frames)")
      ->capture_default_str();
  app.add_flag("--json", o->json, "Print the report as JSON on stdout");
  app.add_option("--view", o->view,
                 "Frame of left/right/front/behind and of 'the second ...' (counted left to right): demonstrator "
                 "(the camera's image axes on the table) or robot (standing at the robot base)")
      ->capture_default_str();
  app.callback([o] {
    srp::execution::ExecuteRequest request;
    request.databasePath = o->db;
    request.taskModelId = o->task;
    request.scenePath = o->scene;
    request.instruction = o->instruction;
    request.outputFolder = o->out;
    request.framePeriod = o->framePeriod;
    request.options.placement.grounding.viewpoint = srp::core::viewpointFromString(o->view);
    request.progress = [](const std::string& line) { std::cerr << line << "\n"; };
    const auto result = srp::execution::executeTask(request);
    if (o->json)
      std::cout << result.report.toJson().dump(2) << "\n";
    else
      std::cout << result.report.toText() << "outputs in " << o->out << "/\n";
    if (!result.report.allSucceeded()) srp::app::commandExitCode() = 2;
  });
}

const srp::app::CommandRegistrar kExecute{
    "execute", "Run a stored task model on the simulated UR5 (plan, safety checks, Simbody), with report and frames",
    60, setupExecute};

}  // namespace
