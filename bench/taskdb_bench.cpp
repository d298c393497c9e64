// Task database write/read speed: a 60 s, 30 FPS demo with 50 objects is
// ~100 000 ProductPose rows, written in one transaction (target < 1 s).
#include <benchmark/benchmark.h>

#include <filesystem>

#include "srp/taskdb/TaskModelStore.h"

namespace {

srp::taskdb::TaskModel bulkModel(int frames, int objects) {
  srp::taskdb::TaskModel m;
  m.info.name = "bench";
  for (int c = 0; c < objects; ++c) m.groundedProducts.push_back({c, "object" + std::to_string(c), {}, {}, {}});
  for (int t = 0; t < frames; ++t) m.handPositions.push_back({t, {0.001 * t, 0.2, 0.5}, true});
  for (int c = 0; c < objects; ++c)
    for (int t = 0; t < frames; ++t) {
      srp::taskdb::ProductPoseRow r;
      r.classId = c;
      r.timeId = t;
      r.p_m = {0.01 * c, 0.0001 * t, 0.55};
      r.confidence = 0.9;
      m.productPoses.push_back(r);
    }
  return m;
}

const std::string kPath = (std::filesystem::temp_directory_path() / "srp_taskdb_bench.db").string();

void removeDb() {
  for (const char* s : {"", "-wal", "-shm"}) std::filesystem::remove(kPath + s);
}

void BM_WriteTaskModel100kPoses(benchmark::State& state) {
  const auto model = bulkModel(2000, 50);  // 100 000 pose rows + 2000 hand rows
  for (auto _ : state) {
    state.PauseTiming();
    removeDb();
    auto db = srp::taskdb::TaskDatabase::open(kPath);
    state.ResumeTiming();
    srp::taskdb::TaskModelStore(db).write(model);
  }
  state.counters["rows/s"] = benchmark::Counter(102000.0 * static_cast<double>(state.iterations()),
                                                benchmark::Counter::kIsRate);
  removeDb();
}
BENCHMARK(BM_WriteTaskModel100kPoses)->Unit(benchmark::kMillisecond)->Iterations(5);

void BM_ReadTaskModel100kPoses(benchmark::State& state) {
  removeDb();
  auto db = srp::taskdb::TaskDatabase::open(kPath);
  const int id = srp::taskdb::TaskModelStore(db).write(bulkModel(2000, 50));
  for (auto _ : state) benchmark::DoNotOptimize(srp::taskdb::TaskModelStore(db).read(id));
  removeDb();
}
BENCHMARK(BM_ReadTaskModel100kPoses)->Unit(benchmark::kMillisecond)->Iterations(5);

}  // namespace

BENCHMARK_MAIN();
