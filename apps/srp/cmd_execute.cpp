// srp execute: run a stored task model on the simulated UR5 cell (libs/execution).
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>

#include "CommandRegistry.h"
#include "CommonOptions.h"
#include "srp/calib/CameraExtrinsics.h"
#include "srp/core/Error.h"
#include "srp/core/ExitCode.h"
#include "srp/core/OutputFile.h"
#include "srp/core/ViewFrame.h"
#include "srp/execution/ExecutionSession.h"
#include "srp/execution/RosTrajectoryExporter.h"
#include "srp/execution/UrScriptExporter.h"

namespace {

struct ExecuteOptions {
  std::string db = srp::app::defaultTaskDatabase();
  int task = 0;
  std::string instruction;
  std::string scene;
  std::string extrinsics;
  std::string kb;
  std::string out = "execution";
  int framePeriod = 10;
  bool json = false;
  std::string urscript;
  std::string trajectoryYaml;
  srp::execution::UrScriptExporter::Options ur;
  srp::execution::RosTrajectoryExporter::Options ros;
  double velocityFraction = 1.0;
  double maxAcceleration_radps2 = srp::execution::SafetyLimits{}.maxAcceleration_radps2;
  bool safetySpheres = false;
  std::string view = "demonstrator";
  bool overwrite = false;
};

void setupExecute(CLI::App& app) {
  auto o = std::make_shared<ExecuteOptions>();
  app.add_option("--db", o->db, std::string("Task database, opened read-only: ") + srp::app::kTaskDatabaseHelp);
  app.add_option("--task", o->task, "Task model id (see 'srp db list')")->required();
  app.add_option("--instruction", o->instruction, "A new instruction that re-plans the task (Language Module)");
  app.add_option("--scene", o->scene,
                 "Current scene JSON (default: the scene of the task model's own demonstration, as 'srp program' "
                 "perceived it, with parts seen without a CAD file as their observed box or hull; "
                 "sim/scenes/default.json for a task model that stores none)");
  app.add_option("--extrinsics", o->extrinsics,
                 "Camera-to-robot extrinsics JSON of the demonstration's camera ('srp calibrate extrinsics' or "
                 "'hand-eye' write it, ./extrinsics.json by default): places the robot base in the demonstration's scene (default: "
                 "the calibration stored with the task model, else the table edge opposite the camera, said in the "
                 "report) and turns the demonstrated offsets into a --scene file's frame")
      ->check(CLI::ExistingFile);
  app.add_option("--kb", o->kb,
                 "Knowledge base of the demonstration's scene (default: the catalogue the task model was programmed "
                 "with)")
      ->check(CLI::ExistingFile);
  app.add_option("-o,--out", o->out,
                 "Output folder: report.json, report.txt, joints.csv, final_scene.json (the scene after execution, for "
                 "--scene of the next run), frames/*.png; written whole or not at all (an existing one needs -w, and "
                 "is replaced only when it holds nothing else)")
      ->capture_default_str();
  app.add_option("--frame-period", o->framePeriod, "Render every n-th 20 ms snapshot (0: no frames)")
      ->capture_default_str();
  app.add_flag("--json", o->json, "Print the report as JSON on stdout");
  app.add_flag("--safety-spheres", o->safetySpheres, "Frames: overlay the safety checker's arm spheres on the UR5 meshes");
  app.add_option("--urscript", o->urscript,
                 "Write the checked joint trajectory as one URScript program (servoj at 125 Hz, gripper on a tool "
                 "digital output); nothing is written when a step was refused or failed");
  app.add_option("--trajectory-yaml", o->trajectoryYaml,
                 "Write the checked joint trajectory as a ROS 2 trajectory_msgs/msg/JointTrajectory YAML "
                 "(ros2 topic pub --yaml-file); nothing is written when a step was refused or failed");
  app.add_option("--gripper-do", o->ur.gripperDigitalOut, "URScript: tool digital output of the gripper (0 or 1; True = grasp)")
      ->capture_default_str();
  app.add_option("--gripper-wait", o->ur.gripperWait_s, "URScript: seconds to wait after switching the gripper")
      ->capture_default_str();
  app.add_option("--servo-lookahead", o->ur.servoLookahead_s, "URScript: servoj lookahead_time [s] (0.03-0.2)")
      ->capture_default_str();
  app.add_option("--servo-gain", o->ur.servoGain, "URScript: servoj gain (100-2000)")->capture_default_str();
  app.add_option("--ros-point-period", o->ros.pointPeriod_s,
                 "ROS YAML: keep trajectory knots at least this many seconds apart (0: every 10 ms knot); the "
                 "spline through the kept knots is checked again (limits, and within --ros-max-deviation of the "
                 "checked trajectory), else nothing is written")
      ->capture_default_str();
  app.add_option("--ros-max-deviation", o->ros.maxThinningDeviation_rad,
                 "ROS YAML with --ros-point-period: largest joint difference [rad] allowed between the thinned and "
                 "the checked trajectory")
      ->capture_default_str()
      ->check(CLI::Range(1e-6, 0.1));
  srp::app::addOverwriteFlag(app, o->overwrite);
  app.add_option("--velocity-fraction", o->velocityFraction,
                 "Safety check: allow this fraction of the URDF joint speed limits (e.g. 0.5 for a first run on the "
                 "real cell); paths are slowed down to fit, up to 4x, else the step is refused")
      ->capture_default_str()
      ->check(CLI::Range(0.01, 1.0));
  app.add_option("--max-acceleration", o->maxAcceleration_radps2,
                 "Safety check: largest joint acceleration [rad/s^2], every joint, on the spline that is exported "
                 "(default: Universal Robots' MoveIt limit for UR arms, ur_moveit_config joint_limits.yaml); paths "
                 "are slowed down to fit, up to 4x with the speeds, else the step is refused")
      ->capture_default_str()
      ->check(CLI::Range(0.1, 40.0));
  app.add_option("--view", o->view,
                 "Frame of left/right/front/behind and of 'the second ...' (counted left to right): demonstrator "
                 "(the camera's image axes on the table) or robot (standing at the robot base)")
      ->capture_default_str();
  app.callback([o] {
    // Bad exporter options and outputs that would destroy an input or an existing file
    // fail before the (long) execution.
    const srp::execution::UrScriptExporter urExporter(o->ur);
    const srp::execution::RosTrajectoryExporter rosExporter(o->ros);
    using srp::core::PathRole;
    srp::core::checkOutputPaths({{"--urscript", o->urscript}, {"--trajectory-yaml", o->trajectoryYaml}, {"--out", o->out}},
                                {{"--db", o->db}, {"--scene", o->scene}, {"--extrinsics", o->extrinsics}, {"--kb", o->kb}},
                                o->overwrite);
    srp::execution::ExecuteRequest request;
    request.databasePath = o->db;
    request.taskModelId = o->task;
    request.scenePath = o->scene;
    request.cataloguePath = o->kb;
    if (!o->extrinsics.empty()) {
      request.X_base_camera = srp::calib::CameraExtrinsics::load(o->extrinsics).X_base_camera;
      request.extrinsicsSource = o->extrinsics;
    }
    request.instruction = o->instruction;
    request.outputFolder = o->out;
    request.framePeriod = o->framePeriod;
    request.drawSafetySpheres = o->safetySpheres;
    request.options.safety.velocityFraction = o->velocityFraction;
    request.options.safety.maxAcceleration_radps2 = o->maxAcceleration_radps2;
    request.options.placement.grounding.viewpoint = srp::core::viewpointFromString(o->view);
    if (!srp::app::quietFlag()) request.progress = [](const std::string& line) { std::cerr << line << "\n"; };
    const auto result = srp::execution::executeTask(request);
    if (o->json)
      std::cout << result.report.toJson().dump(2) << "\n";
    else
      std::cout << result.report.toText() << "outputs in " << o->out << "/\n";
    // 0 every step done with its relations, 3 steps skipped or refused, 1 a step failed.
    srp::app::commandExitCode() = srp::core::toInt(result.report.exitCode());
    if (o->urscript.empty() && o->trajectoryYaml.empty()) return;
    if (const auto why = result.executed.whyNotExportable()) {
      for (const std::string& path : {o->urscript, o->trajectoryYaml})
        if (!path.empty() && std::filesystem::remove(path))  // never leave an older program where this one was asked
          std::cerr << "srp execute: removed " << path << " (from an earlier run)\n";
      std::cerr << "srp execute: no URScript / trajectory YAML written: " << *why << "\n";
      if (srp::app::commandExitCode() == 0) srp::app::commandExitCode() = srp::core::toInt(srp::core::ExitCode::Error);
      return;
    }
    // Both files or neither: a program never sits beside a trajectory of another run.
    std::vector<std::pair<std::filesystem::path, std::string>> files;
    if (!o->urscript.empty()) files.emplace_back(o->urscript, urExporter.toScript(result.executed));
    if (!o->trajectoryYaml.empty()) files.emplace_back(o->trajectoryYaml, rosExporter.toYaml(result.executed));
    srp::core::writeFilesTogether(files);
    if (!o->urscript.empty()) (o->json ? std::cerr : std::cout) << "URScript program: " << o->urscript << "\n";
    if (!o->trajectoryYaml.empty())
      (o->json ? std::cerr : std::cout) << "ROS 2 JointTrajectory YAML: " << o->trajectoryYaml << "\n";
  });
}

const srp::app::CommandRegistrar kExecute{
    "execute", "Run a stored task model on the simulated UR5 (plan, safety checks, Simbody), with report and frames",
    60, setupExecute};

}  // namespace
