// Execution Module speed (issue 7): simulated seconds per second for the 4-step
// task of instruction 1 on the default scene, planning time per step, and the
// pieces (IK, one physics second with resting parts).
#include <benchmark/benchmark.h>

#include <ctime>

#include "srp/execution/ExecutionSession.h"
#include "srp/execution/MinimumJerkPathGenerator.h"
#include "srp/execution/TaskExecutor.h"
#include "srp/execution/UrInverseKinematics.h"

using namespace srp::execution;

namespace {

CellDescription defaultCell() {
  const auto scene = srp::core::Scene::load(std::string(SRP_SIM_DIR) + "/scenes/default.json");
  return CellDescription::fromScene(scene, srp::core::ObjectCatalogue::load(scene.cataloguePath));
}

ExecutionPlan instruction1() {
  auto rel = [](const char* r, const char* n, std::optional<std::string> c = {}) { return SpatialRelation{r, {n, c}}; };
  const auto gray = rel("in", "box", "gray");
  ExecutionPlan p;
  p.steps.push_back({{"cuboid", {}}, {rel("from", "box", "blue")}, {gray}, {}, {}});
  p.steps.push_back({{"star", {}}, {}, {rel("next to", "cuboid"), gray}, {}, {}});
  p.steps.push_back({{"parallelogram", {}}, {}, {rel("beside", "star"), gray}, {}, {}});
  p.steps.push_back({{"octagon", {}}, {}, {rel("adjacent to", "parallelogram"), gray}, {}, {}});
  return p;
}

void BM_FourStepTask(benchmark::State& state) {
  const RobotModel model = RobotModel::defaultUr5();
  const CellDescription cell = defaultCell();
  const JointVector home = TaskExecutor::defaultHome(model, cell.X_world_base, defaultHomeTcp(cell));
  double simulated = 0, wall = 0, cpu = 0, planning = 0;
  int steps = 0;
  for (auto _ : state) {
    TaskExecutor ex(model, cell, home, std::make_shared<MinimumJerkPathGenerator>());
    const std::clock_t c0 = std::clock();
    const ExecutionReport r = ex.run(instruction1());
    cpu += double(std::clock() - c0) / CLOCKS_PER_SEC;
    simulated += r.simulated_s;
    wall += r.simulationWall_s;
    for (const auto& s : r.steps) planning += s.planning_s, ++steps;
    if (!r.allSucceeded()) state.SkipWithError("the 4-step task did not succeed");
  }
  state.counters["sim_s_per_wall_s"] = simulated / wall;
  state.counters["sim_s_per_cpu_s"] = simulated / cpu;
  state.counters["planning_ms_per_step"] = 1000.0 * planning / steps;
  state.counters["simulated_s"] = simulated / state.iterations();
}
BENCHMARK(BM_FourStepTask)->Unit(benchmark::kMillisecond)->Iterations(3);

void BM_InverseKinematicsNearest(benchmark::State& state) {
  const RobotModel model = RobotModel::defaultUr5();
  const UrInverseKinematics ik(model);
  JointVector q;
  q << 0.3, -1.2, 1.4, -1.7, -1.57, 0.4;
  const auto X = model.X_base_tcp(q);
  for (auto _ : state) benchmark::DoNotOptimize(ik.solveNearestTcp(X, q));
}
BENCHMARK(BM_InverseKinematicsNearest)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
