#include "srp/execution/ExecutionSession.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <nlohmann/json.hpp>
#include <sstream>

#include "srp/core/DefaultScene.h"
#include "srp/core/Error.h"
#include "srp/core/Json.h"
#include "srp/core/OutputFile.h"
#include "srp/execution/CellRenderer.h"
#include "srp/execution/DemonstrationScene.h"
#include "srp/execution/DmpPathGenerator.h"
#include "srp/execution/PlanConversion.h"
#include "srp/execution/SceneGrounder.h"
#include "srp/kb/KnowledgeBase.h"
#include "srp/language/InstructionParser.h"
#include "srp/language/PlanTables.h"
#include "srp/taskdb/TaskModelStore.h"

namespace srp::execution {

srp::core::Pose3 defaultHomeTcp(const CellDescription& cell) {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  int n = 0;
  for (const auto& o : cell.objects)
    if (o.kind == CellObjectKind::Container) centre += o.X_world_object.translation(), ++n;
  if (n > 0) centre /= n;
  srp::core::Pose3 X = srp::core::Pose3::Identity();
  X.linear() = Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitX()).toRotationMatrix();
  X.translation() = Eigen::Vector3d(centre.x(), centre.y(), 0.3);
  return X;
}

srp::core::Scene sceneAfter(const srp::core::Scene& before, const CellDescription& perceived) {
  srp::core::Scene after = before;
  for (auto& o : after.objects)
    if (const CellObject* now = perceived.find(o.id)) o.X_world_object = now->X_world_object;
  return after;
}

namespace {
/// What `srp execute --out` writes: a folder holding anything else is not replaced.
const std::vector<std::string> kOutputFolderFiles = {"report.json", "report.txt", "joints.csv", "final_scene.json",
                                                     "frames"};

/// The scene to execute in: the task model's own demonstration when it stores one and no file is given,
/// else the file given, else the default scene. `scenePath` says which; `report` where the scene and
/// the robot base came from.
srp::core::Scene executionScene(const ExecuteRequest& request, const srp::taskdb::TaskModel& model,
                                const std::optional<srp::core::Pose3>& X_base_camera, std::string& scenePath,
                                ExecutionReport& report) {
  const bool ownScene = request.scenePath.empty() && model.scene.has_value();
  scenePath = request.scenePath;
  srp::core::Scene scene;
  if (ownScene) {
    const RobotPlacement placement = RobotPlacement::of(
        *model.scene, X_base_camera,
        request.X_base_camera ? request.extrinsicsSource : X_base_camera ? "stored with the task model" : "");
    scene = demonstrationScene(model, placement);
    if (!request.cataloguePath.empty()) scene.cataloguePath = request.cataloguePath;
    if (!std::filesystem::exists(scene.cataloguePath))
      throw srp::core::FileError(scene.cataloguePath,
                                 "the knowledge base task model " + std::to_string(request.taskModelId) +
                                     " was programmed with is not there; give it with --kb FILE");
    scenePath = "(the demonstration of task model " + std::to_string(request.taskModelId) + ")";
    char what[160];
    std::snprintf(what, sizeof what, "the task model's own demonstration (perceived: table %.2f x %.2f m, %zu objects, %zu "
                  "classes seen without a CAD file)", scene.tableSize_m.x(), scene.tableSize_m.y(), scene.objects.size(),
                  scene.observedClasses.size());
    report.scene = what;
    report.robotBase = placement.description;
  } else {
    if (scenePath.empty()) {
      scenePath = core::defaultScenePath();
      if (request.progress)
        request.progress("task model " + std::to_string(request.taskModelId) +
                         " stores no perceived scene: executing in " + scenePath + " (give another with --scene FILE)");
    }
    scene = srp::core::Scene::load(scenePath);
  }
  return scene;
}

/// The plan: the one given, else the instruction's (grounded in the cell first: an ambiguous or
/// impossible noun phrase stops here), else the task model's own.
ExecutionPlan executionPlan(const ExecuteRequest& request, const srp::taskdb::TaskModel& model,
                            const CellDescription& cell, const srp::core::Pose3& X_world_camera) {
  if (request.planOverride) {
    return *request.planOverride;
  } else if (!request.instruction.empty()) {
    const srp::language::InstructionParser parser;
    const srp::language::TaskPlan parsed =
        parser.parse(request.instruction, srp::language::planStepsFromTaskModel(model));
    if (parsed.steps.empty())
      throw srp::core::InvalidInputError("the instruction gives no pick & place step: " +
                                         (parsed.warnings.empty() ? std::string("(no reason)") : parsed.warnings.front()));
    ExecutionPlan plan = planFromLanguage(parsed);
    // An ambiguous or impossible noun phrase stops here: nothing moved, nothing written.
    const std::vector<std::string> problems = groundingProblems(plan, cell, request.options.placement.grounding);
    if (!problems.empty()) {
      std::string message = "the instruction cannot be grounded in the scene, nothing was executed: ";
      for (std::size_t i = 0; i < problems.size(); ++i) message += (i ? "; " : "") + problems[i];
      throw GroundingError(message, {});
    }
    attachDemoOffsets(plan, model, X_world_camera);
    return plan;
  } else {
    return planFromTaskModel(model, X_world_camera);
  }
}

/// The report (JSON and text), the joint log and the final scene into the output folder, which is
/// then renamed into place; `result.writtenFiles` names them where they end up.
void writeExecutionOutputs(const ExecuteRequest& request, const std::string& scenePath, const srp::core::Scene& scene,
                           TaskExecutor& executor, srp::core::AtomicOutputFolder& output,
                           const std::string& outputFolder, ExecuteResult& result) {
  nlohmann::json j = result.report.toJson();
  j["task_model_id"] = request.taskModelId;
  j["scene"] = scenePath;
  srp::core::writeJsonFile(outputFolder + "/report.json", j);
  srp::core::writeFileAtomically(outputFolder + "/report.txt", result.report.toText());
  executor.writeJointLogCsv(outputFolder + "/joints.csv");
  srp::core::writeJsonFile(outputFolder + "/final_scene.json", sceneAfter(scene, executor.perceive()).toJson());
  output.commit();
  for (const char* f : {"/report.json", "/report.txt", "/joints.csv", "/final_scene.json"}) result.writtenFiles.push_back(request.outputFolder + f);
}

}  // namespace

ExecuteResult executeTask(const ExecuteRequest& request) {
  ExecuteResult result;
  if (!srp::taskdb::TaskDatabase::isServerUri(request.databasePath) && !std::filesystem::exists(request.databasePath))
    throw srp::core::FileError(request.databasePath, "no such task database (create one with 'srp program' or 'srp db')");
  auto db = srp::taskdb::TaskDatabase::open(request.databasePath, srp::taskdb::TaskDatabase::Mode::ReadOnly);
  const srp::taskdb::TaskModelStore store(db);
  const srp::taskdb::TaskModel model = store.read(request.taskModelId);

  // The scene: the file given, else the task model's own demonstration, else the default.
  const bool ownScene = request.scenePath.empty() && model.scene.has_value();
  const std::optional<srp::core::Pose3> X_base_camera =
      request.X_base_camera ? request.X_base_camera : model.info.X_base_camera;
  std::string scenePath;
  const srp::core::Scene scene = executionScene(request, model, X_base_camera, scenePath, result.report);
  const srp::core::ObjectCatalogue catalogue = srp::kb::loadCatalogue(scene.cataloguePath);
  const CellDescription cell = CellDescription::fromScene(scene, catalogue);
  // Demonstration offsets: the camera as calibrated (or stored with the task model), else the scene's.
  const srp::core::Pose3 X_world_camera =
      ownScene ? scene.X_world_camera
               : X_base_camera ? srp::core::Pose3(scene.X_world_base * *X_base_camera) : scene.X_world_camera;
  result.plan = executionPlan(request, model, cell, X_world_camera);
  if (result.plan.steps.empty())
    throw srp::core::InvalidInputError("task model " + std::to_string(request.taskModelId) +
                                       " has no target objects to execute");

  const RobotModel robot = RobotModel::defaultUr5();
  const JointVector home = TaskExecutor::defaultHome(robot, cell.X_world_base, defaultHomeTcp(cell));
  // Learned Reach/Move DMPs where the task model has Skills rows, minimum-jerk otherwise;
  // a Move, learned or not, crosses high enough for the tallest part to clear the tallest wall.
  const double carry_m = cell.carryHeight_m();
  MinimumJerkPathGenerator::Options fallback;
  fallback.clearanceHeight_m = std::max(fallback.clearanceHeight_m, carry_m);
  auto generator = std::make_shared<DmpPathGenerator>(
      DmpPathGenerator::fromTaskModel(model, X_world_camera, fallback, DmpPathGenerator::kDefaultEndHeight_m,
                                      std::max(DmpPathGenerator::kDefaultEndHeight_m, carry_m)));
  TaskExecutor executor(robot, cell, home, generator, request.options);

  std::unique_ptr<CellRenderer> renderer;
  std::string framesFolder;
  int snapshotCount = 0;
  // The output folder is built beside its target and renamed into place at the end:
  // a failed run leaves no half-made folder and a previous one as it was.
  std::optional<srp::core::AtomicOutputFolder> output;
  std::string outputFolder;  // where the files go until the commit
  if (!request.outputFolder.empty()) {
    srp::core::checkFolderHoldsOnly(request.outputFolder, kOutputFolderFiles, "--out");
    output.emplace(request.outputFolder);
    outputFolder = output->temporaryPath().string();
    if (request.framePeriod > 0) {
      framesFolder = outputFolder + "/frames";
      std::filesystem::create_directories(framesFolder);
      CellRenderer::Options view;
      view.drawSafetySpheres = request.drawSafetySpheres;
      renderer = std::make_unique<CellRenderer>(robot, cell, view);
      executor.simulator().setSnapshotCallback([&](const CellSnapshot& s) {
        if (snapshotCount++ % request.framePeriod != 0) return;
        std::ostringstream name;
        name << framesFolder << "/frame_" << std::setw(5) << std::setfill('0') << snapshotCount / request.framePeriod
             << ".png";
        renderer->renderPng(s, name.str());
        result.writtenFiles.push_back(request.outputFolder + name.str().substr(outputFolder.size()));
      });
    }
  }

  // All placements are planned together before the first step moves; one progress line per step.
  ExecutionReport report = executor.run(result.plan, [&](const StepReport& step) {
    if (!request.progress) return;
    ExecutionReport one;
    one.steps.push_back(step);
    const std::string text = one.toText();
    request.progress(text.substr(0, text.find('\n')));
  });
  report.scene = result.report.scene;  // where the scene and the robot base came from (set above)
  report.robotBase = result.report.robotBase;
  result.report = std::move(report);

  result.executed = ExecutedTask::fromSimulation(robot, request.options.safety, executor.simulator(), result.report);
  result.executed.taskName = model.info.name;
  result.executed.taskModelId = request.taskModelId;
  result.executed.instruction = request.instruction.empty() ? model.info.instruction : request.instruction;
  result.executed.scene = scenePath;

  if (output) writeExecutionOutputs(request, scenePath, scene, executor, *output, outputFolder, result);
  return result;
}

}  // namespace srp::execution
