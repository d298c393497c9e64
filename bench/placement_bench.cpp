// Placement planning speed: one core's CPU time of JointPlacementPlanner::plan (every
// step's placement planned together, before anything moves) per step of an instruction,
// on the default scene (sim/scenes/default.json). The whole step's planning (placement,
// paths, IK, safety for both grasp turns) is `planning_ms_per_step` of execution_bench.
//   InstructionOne   Appendix A instruction 1 (4 steps; each step alone would do too)
//   LeftOfTheFirst   the cuboid in the gray box, then the star left of it in the gray box
//   BetweenTheFirst  the cuboid and the star in the gray box, then the octagon between them
//   BothSides        the octagon in the gray box, the cuboid left of it, the star right of it
// Counters: cpu_ms_per_step (mean over the iterations) and median_ms_per_step.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <vector>

#include "ThreadCpuTime.h"
#include "srp/execution/JointPlacementPlanner.h"

using namespace srp::execution;

namespace {

SpatialRelation rel(const char* r, const char* landmark, std::optional<std::string> colour = {}) {
  return {r, {landmark, colour}, {}, ""};
}

ExecutionStep step(const char* object, std::vector<SpatialRelation> target) {
  ExecutionStep s;
  s.object = {object, {}};
  s.target = std::move(target);
  return s;
}

ExecutionPlan planOf(int which) {
  const SpatialRelation gray = rel("in", "box", "gray");
  ExecutionPlan p;
  switch (which) {
    case 0:
      p.steps.push_back(step("cuboid", {gray}));
      p.steps.back().source.push_back(rel("from", "box", "blue"));
      p.steps.push_back(step("star", {rel("next to", "cuboid"), gray}));
      p.steps.push_back(step("parallelogram", {rel("beside", "star"), gray}));
      p.steps.push_back(step("octagon", {rel("adjacent to", "parallelogram"), gray}));
      break;
    case 1:
      p.steps.push_back(step("cuboid", {gray}));
      p.steps.push_back(step("star", {rel("left of", "cuboid"), gray}));
      break;
    case 2: {
      p.steps.push_back(step("cuboid", {gray}));
      p.steps.push_back(step("star", {gray}));
      SpatialRelation between = rel("between", "cuboid");
      between.secondLandmark = ObjectReference{"star", {}};
      p.steps.push_back(step("octagon", {between, gray}));
      break;
    }
    default:
      p.steps.push_back(step("octagon", {gray}));
      p.steps.push_back(step("cuboid", {rel("left of", "octagon"), gray}));
      p.steps.push_back(step("star", {rel("right of", "octagon"), gray}));
  }
  return p;
}

void BM_JointPlacement(benchmark::State& state) {
  const CellDescription cell = CellDescription::loadScene();
  const ExecutionPlan plan = planOf(static_cast<int>(state.range(0)));
  const JointPlacementPlanner planner;
  std::vector<double> perStep_ms;
  for (auto _ : state) {
    const double t0 = srp::bench::threadCpu_s();
    const auto planned = planner.plan(cell, plan);
    perStep_ms.push_back(1000.0 * (srp::bench::threadCpu_s() - t0) / static_cast<double>(plan.steps.size()));
    for (const auto& s : planned)
      if (!s.placement.X_world_object) state.SkipWithError("a step was not placed");
  }
  double sum = 0.0;
  for (const double v : perStep_ms) sum += v;
  std::nth_element(perStep_ms.begin(), perStep_ms.begin() + perStep_ms.size() / 2, perStep_ms.end());
  state.counters["cpu_ms_per_step"] = sum / static_cast<double>(perStep_ms.size());
  state.counters["median_ms_per_step"] = perStep_ms[perStep_ms.size() / 2];
  state.counters["steps"] = static_cast<double>(plan.steps.size());
}
BENCHMARK(BM_JointPlacement)
    ->ArgName("plan")  // 0 InstructionOne, 1 LeftOfTheFirst, 2 BetweenTheFirst, 3 BothSides
    ->Arg(0)->Arg(1)->Arg(2)->Arg(3)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(10);

}  // namespace

BENCHMARK_MAIN();
