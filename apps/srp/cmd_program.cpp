// srp program: instruction + demonstration -> task model (libs/programming).
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <iomanip>
#include <iostream>

#include "CommandRegistry.h"
#include "CommonOptions.h"
#include "ProgressLine.h"
#include "srp/calib/CameraExtrinsics.h"
#include "srp/calib/CameraFiles.h"
#include "srp/core/Error.h"
#include "srp/core/ExitCode.h"
#include "srp/core/OutputFile.h"
#include "srp/programming/ProgrammingPipeline.h"
#include "srp/taskdb/TaskDatabase.h"

namespace {

struct ProgramArgs {
  std::string instruction, demo, kb, calib, db = srp::app::defaultTaskDatabase(), name = "task", report,
      hand = "auto", scene, extrinsics;
  bool json = false, allowTruncated = false, allowPartial = false, overwrite = false;
};

void setupProgram(CLI::App& cmd) {
  auto a = std::make_shared<ProgramArgs>();
  cmd.add_option("-i,--instruction", a->instruction, "The instruction, e.g. \"Pick up the cuboid from the blue box "
                                                     "and place it in the gray box.\"")->required();
  // Recording is its own command (srp record demo.rawlog): programming reads a finished recording,
  // so a failed recording can never leave a half-programmed task.
  cmd.add_option("--demo", a->demo, "Demonstration rawlog (srp record / srp import / srp synth-demo)")->required();
  cmd.add_option("--kb", a->kb, "Knowledge base catalogue (default: the shipped datasets/kb/catalogue.json of srp's data folder)");
  cmd.add_option("--scene", a->scene,
                 "The demo's scene JSON (srp synth-demo --scene; for a recording, one listing its instances and "
                 "their colours): a class it holds several times is perceived per instance, and the instruction's "
                 "phrases ('the red cuboid') are grounded to instances (stored as InstanceId)");
  cmd.add_option(
      "--intrinsics", a->calib,
      "Camera file (ViSP XML, ROS/OpenCV YAML or JSON, e.g. calib/camera.xml) overriding the rawlog's intrinsics");
  srp::app::addDeprecatedOption(cmd, "--calib", a->calib, "--intrinsics");
  cmd.add_option("--db", a->db, std::string("Task database to store the task model in: ") + srp::app::kTaskDatabaseHelp);
  cmd.add_option("--name", a->name, "Task model name; an existing name gets a new version")->capture_default_str();
  cmd.add_option("-o,--out", a->report,
                 "Folder for the report: PNG figures, contact_sheet.png (what perception saw on the recording), "
                 "scene.json (the scene the demonstration showed, the one 'srp execute' runs in without --scene) and "
                 "summary.md; written whole or not at all, only when the task model is stored; an existing one needs "
                 "-w and is replaced only when it holds nothing but a report");
  srp::app::addDeprecatedOption(cmd, "--report", a->report, "--out");
  cmd.add_option("--extrinsics", a->extrinsics,
                 "Camera-to-robot extrinsics of the demonstration's camera ('srp calibrate extrinsics' or 'hand-eye' "
                 "write it, ./extrinsics.json by default), stored with the task model: execution places the robot from it "
                 "(without: at the table edge opposite the camera)")
      ->check(CLI::ExistingFile);
  cmd.add_option("--hand", a->hand,
                 "Hand detector: auto (the glove's AprilTag when the recording shows it, else the bare hand), marker "
                 "(AprilTag on the glove) or marker-free")
      ->check(CLI::IsMember({"auto", "marker", "marker-free"}))
      ->capture_default_str();
  cmd.add_flag("--allow-truncated", a->allowTruncated,
               "Use the frames before the damage of a damaged demonstration rawlog (default: fail, store nothing)");
  cmd.add_flag("--allow-partial", a->allowPartial,
               "Store the task model even when a step of the plan has no grasp or no release in the demonstration "
               "(default: fail naming the step, store nothing); exits 3 when it did");
  cmd.add_flag("--json", a->json, "Print the result as JSON");
  srp::app::addOverwriteFlag(cmd, a->overwrite);
  cmd.callback([a] {
    using srp::core::PathRole;
    const std::vector<PathRole> inputs = {
        {"--demo", a->demo}, {"--kb", a->kb}, {"--scene", a->scene}, {"--intrinsics", a->calib}};
    srp::core::checkOutputPaths({{"--db", a->db}}, inputs, true);  // the database is added to, never replaced
    srp::core::checkOutputPaths({{"--out", a->report}}, inputs, a->overwrite);
    srp::programming::ProgrammingOptions o;
    o.instruction = a->instruction;
    o.demoPath = a->demo;
    o.cataloguePath = a->kb;
    o.scenePath = a->scene;
    if (!a->calib.empty()) o.intrinsics = srp::calib::loadCameraFile(a->calib).camera.intrinsics;
    o.dbPath = a->db;
    o.name = a->name;
    o.reportDir = a->report;
    o.allowTruncated = a->allowTruncated;
    o.allowPartial = a->allowPartial;
    if (!a->extrinsics.empty()) {
      o.X_base_camera = srp::calib::CameraExtrinsics::load(a->extrinsics).X_base_camera;
      o.extrinsicsSource = a->extrinsics;
    }
    using Hand = srp::programming::ProgrammingOptions::Hand;
    o.hand = a->hand == "marker-free" ? Hand::MarkerFree : a->hand == "marker" ? Hand::Marker : Hand::Auto;
    // One line per stage on a terminal, redrawn at most every 100 ms; silent otherwise.
    srp::app::ProgressLine bar(srp::app::progressWanted(a->json), std::chrono::milliseconds(100));
    o.progress = [&bar](const std::string& s, std::size_t d, std::size_t t) { bar.show(s, d, t, t ? "" : "frames"); };
    const srp::programming::ProgramResult r = srp::programming::programTask(o);
    if (!r.problems.empty()) srp::app::commandExitCode() = srp::core::toInt(srp::core::ExitCode::Partial);
    if (a->json) {
      std::cout << srp::programming::toJsonText(r) << "\n";
      return;
    }
    std::cout << "Stored task model " << r.taskModelId << " ('" << r.name << "' version " << r.version << ") in "
              << srp::taskdb::TaskDatabase::displayName(a->db) << "\n\nPlan:\n";
    for (std::size_t i = 0; i < r.planLines.size(); ++i) std::cout << "  " << i + 1 << ". " << r.planLines[i] << "\n";
    std::cout << "\nDemonstration: " << r.frames << " frames, hand (" << r.handDetector << ") detected in "
              << r.handDetectedFrames << "; camera "
              << (r.cameraMoved ? "moved (trajectories kept in the first frame's camera)" : "fixed") << "\n";
    for (const auto& n : r.discoveryNotes) std::cout << "Found in the demonstration: " << n << "\n";
    std::cout << "\n";
    std::cout << std::left << std::setw(16) << "object" << std::setw(8) << "grasp" << std::setw(9) << "release"
              << std::setw(12) << "reach λ" << std::setw(12) << "move λ" << "note\n";
    for (const auto& ob : r.objects)
      std::cout << std::setw(16) << (ob.instanceId.empty() ? ob.name : ob.instanceId) << std::setw(8) << ob.graspFrame << std::setw(9) << ob.releaseFrame
                << std::setw(12) << std::setprecision(3) << ob.reachLambda << std::setw(12) << ob.moveLambda << ob.note
                << "\n";
    std::cout << "\n" << r.skillCount << " skills learned (Reach/Move as DMPs). Timing:";
    for (const auto& t : r.timings) std::cout << " " << t.stage << " " << std::setprecision(3) << t.wall_s << " s;";
    std::cout << " peak memory " << static_cast<long>(r.peakResidentMemory_MB + 0.5) << " MB\n";
    if (r.sceneStored) std::cout << "Perceived scene stored with the task model; robot base: " << r.robotBase << "\n";
    for (const auto& w : r.warnings) std::cout << "warning: " << w << "\n";
    for (const auto& p : r.problems) std::cout << "incomplete (--allow-partial): " << p << "\n";
    if (!r.reportFiles.empty()) std::cout << "Report: " << a->report << "/summary.md\n";
  });
}

const srp::app::CommandRegistrar kProgram{
    "program", "Program a task: instruction + RGB-D demonstration -> task model in the database", 40, setupProgram};

}  // namespace
