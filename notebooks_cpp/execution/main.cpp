// Notebook: the UR5 executing a learned task in simulation (cf. thesis fig. 8.9)
// ==============================================================================
//
// What the figure shows
//   Thesis fig. 8.9 shows the ROS Gazebo cell (table, boxes, parts, UR5) in
//   which the learned task model was executed. srp simulates the cell with
//   Simbody; this notebook runs the whole execution side and tiles eight
//   rendered frames of it into one picture: the start, the first pick & place
//   (grasp, carrying, release of the cuboid), the star, parallelogram and
//   octagon being carried, and the end, with every part in the gray box.
//   The UR5 is drawn from its URDF link meshes (sim/ur5) at each simulated
//   joint configuration, with the suction gripper on its flange and the parts
//   with their catalogue meshes (CellRenderer; the safety spheres are off).
//
// The steps, as `srp motion` + `srp execute --instruction` run them:
//   1. Skills: a 4-object pick & place demonstration (srp::motion's synthetic
//      hand and object trajectories with detector-like noise and dropouts) is
//      segmented and its Reach/Move segments learned as DMPs (srp::motion).
//   2. The task model with its skills goes into an SQLite task database and is
//      read back: execution only sees the database (srp::taskdb).
//   3. Thesis instruction 1 is parsed by the Language Module into a plan.
//   4. The task planner (thesis fig. 7.11) executes it on the simulated UR5:
//      each Reach and Move is the learned DMP re-targeted to the part's actual
//      pose and its target place (srp::execution).
//
// Output (folder = first argument, default out/notebooks/execution)
//   execution.png (copied to notebooks_cpp/execution/figure.png), the eight
//   frames frame_*.png, execution.txt (the execution report), task.db.
//
// Run
//   cmake --build build --target notebook_execution
//   build/notebooks_cpp/notebook_execution [out_dir]
//   (CTest: ctest --test-dir build -R notebook.execution; 2 s of CPU, 7-10 s wall.)
//
// Checks (exit 1 otherwise): every step done with its relations verified on
// the simulated result, every step on learned DMP paths, the PNG written.

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <string>
#include <vector>

#include "../common/Notebook.h"
#include "srp/core/Error.h"
#include "srp/core/Scene.h"
#include "srp/execution/CellRenderer.h"
#include "srp/execution/DmpPathGenerator.h"
#include "srp/execution/ExecutionSession.h"
#include "srp/execution/PlanConversion.h"
#include "srp/execution/TaskExecutor.h"
#include "srp/kb/KnowledgeBase.h"
#include "srp/language/InstructionParser.h"
#include "srp/motion/Segmenter.h"
#include "srp/motion/SkillLearner.h"
#include "srp/motion/SyntheticPickPlace.h"
#include "srp/programming/MotionRows.h"
#include "srp/taskdb/TaskModelStore.h"

namespace {

namespace ex = srp::execution;

const char* kInstruction =
    "Begin by picking up the cuboid from the blue box and placing it in the gray box. Next, carefully lift the star "
    "and position it next to the cuboid in the gray box. Then, move the parallelogram, placing it beside the star in "
    "the gray box. Finally, pick up the octagon and place it adjacent to the parallelogram in the gray box.";

// A frame of the figure: the simulated state and its caption.
struct Tile {
  ex::CellSnapshot snapshot;
  std::string caption;
};

int run(int argc, char** argv) {
  const std::filesystem::path out = srp::notebook::outputFolder(argc, argv, "execution");

  // Step 1: learn the skills. The demonstration's hand and object
  // trajectories (camera frame) are segmented per object in plan order and
  // each Reach and Move segment is learned as a DMP.
  const auto demo = srp::motion::SyntheticPickPlaceGenerator().generate();
  srp::taskdb::TaskModel learned = srp::programming::taskModelFromTracks(demo, "notebook-execution", demo.instruction());
  srp::programming::learnSkills(learned);

  // Step 2: the task database. A fresh file each run; execution reads the
  // task model back from it, as `srp execute --db` does.
  const std::string dbPath = (out / "task.db").string();
  std::filesystem::remove(dbPath);
  int taskModelId = 0;
  srp::taskdb::TaskModel model;
  {
    auto db = srp::taskdb::TaskDatabase::open(dbPath);
    srp::taskdb::TaskModelStore store(db);
    taskModelId = store.write(learned);
    model = store.read(taskModelId);
  }

  // Step 3: the cell and the plan. The scene is the thesis' (two boxes, four
  // parts in the blue box); the DMPs were learned in the camera frame, so
  // start and goal go into it with X_world_camera. The instruction becomes
  // the plan; the demo's final poses say on which side "next to" places a part.
  const auto scene = srp::core::Scene::load(std::string(SRP_SIM_DIR) + "/scenes/default.json");
  const auto catalogue = srp::kb::loadCatalogue(scene.cataloguePath);
  const ex::CellDescription cell = ex::CellDescription::fromScene(scene, catalogue);
  const srp::core::Pose3 X_world_camera =
      model.info.X_base_camera ? srp::core::Pose3(scene.X_world_base * *model.info.X_base_camera) : scene.X_world_camera;
  const srp::language::TaskPlan parsed = srp::language::InstructionParser().parse(kInstruction);
  ex::ExecutionPlan plan = ex::planFromLanguage(parsed);
  ex::attachDemoOffsets(plan, model, X_world_camera);

  // Step 4: execute. The executor plans each step (placement, IK, safety
  // checks) before the arm moves, then the Simbody cell tracks the joint
  // trajectory; the part is welded to the tool between Grasp and Release.
  // Every logged state (50 Hz) is kept to choose the frames afterwards.
  const ex::RobotModel robot = ex::RobotModel::defaultUr5();
  const ex::JointVector home = ex::TaskExecutor::defaultHome(robot, cell.X_world_base, ex::defaultHomeTcp(cell));
  auto dmpPaths = std::make_shared<ex::DmpPathGenerator>(ex::DmpPathGenerator::fromTaskModel(model, X_world_camera));
  ex::TaskExecutor executor(robot, cell, home, dmpPaths);
  std::vector<ex::CellSnapshot> states;
  executor.simulator().setSnapshotCallback([&](const ex::CellSnapshot& s) { states.push_back(s); });
  std::cerr << "executing " << plan.steps.size() << " steps ...\n";
  const ex::ExecutionReport report = executor.run(plan);
  std::cout << report.toText();
  std::ofstream(out / "execution.txt") << "instruction: " << kInstruction << "\n" << report.toText();
  if (states.empty()) throw srp::core::Error("the simulator logged no state");

  // Step 5: choose the frames: the start; grasp, carrying (half-way between
  // grasp and release) and release of the first part; each other part
  // carried; the end.
  std::vector<Tile> tiles;
  const auto caption = [](const ex::CellSnapshot& s, const std::string& what) {
    char buf[128];
    std::snprintf(buf, sizeof buf, "t = %.1f s: %s", s.t_s, what.c_str());
    return std::string(buf);
  };
  tiles.push_back({states.front(), caption(states.front(), "start, parts in the blue box")});
  for (std::size_t i = 0; i < states.size();) {
    if (!states[i].graspedPart) { ++i; continue; }
    std::size_t j = i;  // the held interval [i, j]
    while (j + 1 < states.size() && states[j + 1].graspedPart == states[i].graspedPart) ++j;
    const std::string part = *states[i].graspedPart;
    const ex::CellSnapshot& middle = states[(i + j) / 2];
    if (tiles.size() == 1) {
      tiles.push_back({states[i], caption(states[i], "grasp " + part)});
      tiles.push_back({middle, caption(middle, "move " + part)});
      tiles.push_back({states[j], caption(states[j], "release " + part)});
    } else {
      tiles.push_back({middle, caption(middle, "move " + part)});
    }
    i = j + 1;
  }
  tiles.push_back({states.back(), caption(states.back(), "end, all parts in the gray box")});

  // Step 6: render them off-screen (MRPT, EGL) and tile them 4 x 2 with captions.
  ex::CellRenderer::Options view;
  view.width_px = 480;
  view.height_px = 360;
  view.distance_m = 1.6;  // closer than the default 1.9 m: the parts show better, the arm still fits
  Eigen::Vector3d containers_m = Eigen::Vector3d::Zero();
  int containerCount = 0;
  for (const auto& o : cell.objects)
    if (o.kind == ex::CellObjectKind::Container) containers_m += o.X_world_object.translation(), ++containerCount;
  if (containerCount > 0) view.lookAt_world_m = containers_m / containerCount + Eigen::Vector3d(0.0, -0.08, 0.16);
  ex::CellRenderer renderer(robot, cell, view);
  constexpr int kColumns = 4, kCaption_px = 28;
  const int rows = static_cast<int>((tiles.size() + kColumns - 1) / kColumns);
  cv::Mat sheet(rows * (view.height_px + kCaption_px), kColumns * view.width_px, CV_8UC3, cv::Scalar(255, 255, 255));
  for (std::size_t k = 0; k < tiles.size(); ++k) {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%02zu.png", k);
    const std::string framePath = (out / name).string();
    renderer.renderPng(tiles[k].snapshot, framePath);
    const cv::Mat frame = cv::imread(framePath, cv::IMREAD_COLOR);
    if (frame.empty()) throw srp::core::FileError(framePath, "rendered frame could not be read back");
    const int x = static_cast<int>(k % kColumns) * view.width_px;
    const int y = static_cast<int>(k / kColumns) * (view.height_px + kCaption_px);
    cv::putText(sheet, tiles[k].caption, cv::Point(x + 8, y + 20), cv::FONT_HERSHEY_SIMPLEX, 0.55, cv::Scalar(0, 0, 0),
                1, cv::LINE_AA);
    cv::Mat target = sheet(cv::Rect(x, y + kCaption_px, view.width_px, view.height_px));
    cv::resize(frame, target, target.size());
  }
  const std::string png = (out / "execution.png").string();
  if (!cv::imwrite(png, sheet)) throw srp::core::FileError(png, "cannot write the PNG");
  std::cout << "wrote " << png << " (" << tiles.size() << " frames of " << states.size() << " logged states)\n";

  // Step 7: checks.
  srp::notebook::Checks checks;
  checks.pngWritten(png);
  checks.require(report.steps.size() == 4, "the instruction gives 4 steps");
  checks.require(report.allSucceeded(), "every step done, its relations verified on the simulated result");
  for (const auto& s : report.steps) checks.require(s.pathSource == "dmp", s.object + " moved on learned DMP paths");
  return checks.exitCode();
}

}  // namespace

int main(int argc, char** argv) { return srp::notebook::run("execution", argc, argv, run); }
