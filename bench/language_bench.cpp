// Language Module timing: model load, and instruction parsing per sentence
// (tokenise + entities/relations + plan) after the model is loaded.
// Targets (issue 3): median < 2 ms per sentence on one core; model load < 1 s.
// Run on one core: taskset -c 0 build/bench/language_bench
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>

#include "srp/language/InstructionParser.h"

namespace {
const std::string kInstruction1 =
    "Begin by picking up the cuboid from the blue box and placing it in the gray box. Next, carefully lift the star "
    "and position it next to the cuboid in the gray box. Then, move the parallelogram, placing it beside the star in "
    "the gray box. Finally, pick up the octagon and place it adjacent to the parallelogram in the gray box.";

std::vector<std::string> valSentences() {
  std::vector<std::string> out;
  for (const auto& s : srp::language::readSpertCorpus(std::string(SRP_DATASETS_DIR) + "/language/val.json")) {
    std::string text;
    for (const auto& t : s.tokens) text += (text.empty() ? "" : " ") + t;
    out.push_back(text);
  }
  return out;
}

const srp::language::InstructionParser& parser() {
  static const srp::language::InstructionParser p;
  return p;
}
}  // namespace

static void BM_ModelLoad(benchmark::State& state) {
  for (auto _ : state) {
    srp::language::InstructionParser p;
    benchmark::DoNotOptimize(&p);
  }
}
BENCHMARK(BM_ModelLoad)->Unit(benchmark::kMillisecond)->Iterations(5);

// One pass over the 206 validation sentences; counters give the per-sentence median and 90th percentile.
static void BM_ParseValSentences(benchmark::State& state) {
  const auto texts = valSentences();
  std::vector<double> ms;
  for (auto _ : state) {
    for (const auto& t : texts) {
      const auto t0 = std::chrono::steady_clock::now();
      auto plan = parser().parse(t);
      ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
      benchmark::DoNotOptimize(plan);
    }
  }
  std::sort(ms.begin(), ms.end());
  state.counters["median_ms_per_sentence"] = ms[ms.size() / 2];
  state.counters["p90_ms_per_sentence"] = ms[ms.size() * 9 / 10];
  state.counters["sentences"] = static_cast<double>(texts.size());
}
BENCHMARK(BM_ParseValSentences)->Unit(benchmark::kMillisecond);

static void BM_ParseAppendixAInstruction(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(parser().parse(kInstruction1));
}
BENCHMARK(BM_ParseAppendixAInstruction)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
