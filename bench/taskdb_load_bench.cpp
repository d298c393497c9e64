// Many writers and readers on one task database: N writer processes each store
// K copies of a task model under one name while M reader processes read the
// latest model in a loop; then every stored model is checked complete (row
// counts equal to the source's) and the versions 1..N*K without duplicates;
// last, a writer killed with SIGKILL in the middle of its transaction must
// leave the library as it was. Not a test (timings depend on the machine):
//
//   taskdb_load_bench --source own.db --id 1 --db /tmp/load.db --writers 8 --readers 2
//   srp_pg_sandbox sh -c 'taskdb_load_bench --source own.db --id 1 --db "$SRP_DB" --writers 32 --readers 8'
//
// Prints one JSON object (stores per second, p50/p95 store latency, checks).
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "srp/taskdb/TaskModelStore.h"

namespace {

using Clock = std::chrono::steady_clock;
using srp::taskdb::TaskDatabase;
using srp::taskdb::TaskModel;
using srp::taskdb::TaskModelStore;

struct Args {
  std::string source, db, out = "/tmp";
  int id = 1, writers = 1, readers = 0, perWriter = 2;
};

std::size_t rows(const TaskModel& m) {
  return m.products.size() + m.sourceLocations.size() + m.targetLocations.size() + m.targetObjectIds.size() +
         m.groundedProducts.size() + m.productPoses.size() + m.handPositions.size() + m.skills.size() +
         (m.scene ? 1 + m.scene->objects.size() + m.scene->observedClasses.size() : 0);
}

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[static_cast<std::size_t>(p * static_cast<double>(v.size() - 1) + 0.5)];
}

}  // namespace

int main(int argc, char** argv) {
  Args a;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string k = argv[i], v = argv[i + 1];
    if (k == "--source") a.source = v;
    else if (k == "--id") a.id = std::stoi(v);
    else if (k == "--db") a.db = v;
    else if (k == "--writers") a.writers = std::stoi(v);
    else if (k == "--readers") a.readers = std::stoi(v);
    else if (k == "--per-writer") a.perWriter = std::stoi(v);
    else if (k == "--tmp") a.out = v;
    else {
      std::cerr << "unknown option " << k << "\n";
      return 2;
    }
  }
  if (a.source.empty() || a.db.empty()) {
    std::cerr << "usage: taskdb_load_bench --source DB --id N --db TARGET [--writers N] [--readers M] [--per-writer K]\n";
    return 2;
  }
  TaskModel model;
  {
    auto src = TaskDatabase::open(a.source, TaskDatabase::Mode::ReadOnly);
    model = TaskModelStore(src).read(a.id);
  }
  model.info.name = "load";
  const std::size_t modelRows = rows(model);
  { auto db = TaskDatabase::open(a.db); }  // schema before the clock starts

  const std::string latencies = a.out + "/srp_load_" + std::to_string(::getpid()) + "_";
  const auto start = Clock::now();
  std::vector<pid_t> writers, readers;
  for (int w = 0; w < a.writers; ++w) {
    const pid_t pid = ::fork();
    if (pid == 0) {
      std::ofstream out(latencies + std::to_string(w));
      try {
        auto db = TaskDatabase::open(a.db);
        for (int k = 0; k < a.perWriter; ++k) {
          const auto t0 = Clock::now();
          TaskModelStore(db).write(model);
          out << std::chrono::duration<double>(Clock::now() - t0).count() << "\n";
        }
      } catch (const std::exception& e) {
        std::cerr << "writer " << w << ": " << e.what() << "\n";
        ::_exit(1);
      }
      out.close();  // _exit runs no destructors
      ::_exit(0);
    }
    writers.push_back(pid);
  }
  for (int r = 0; r < a.readers; ++r) {
    const pid_t pid = ::fork();
    if (pid == 0) {
      try {
        auto db = TaskDatabase::open(a.db, TaskDatabase::Mode::ReadOnly);
        for (;;) {
          TaskModelStore store(db);
          const auto list = store.list();
          if (!list.empty() && rows(store.read(list.back().id)) != modelRows) {
            std::cerr << "reader " << r << ": torn read\n";
            ::_exit(1);
          }
        }
      } catch (const std::exception& e) {
        std::cerr << "reader " << r << ": " << e.what() << "\n";
        ::_exit(1);
      }
    }
    readers.push_back(pid);
  }
  int failedWriters = 0;
  for (const pid_t p : writers) {
    int st = 0;
    ::waitpid(p, &st, 0);
    failedWriters += !(WIFEXITED(st) && WEXITSTATUS(st) == 0);
  }
  const double wall_s = std::chrono::duration<double>(Clock::now() - start).count();
  int failedReaders = 0;
  for (const pid_t p : readers) {
    ::kill(p, SIGTERM);
    int st = 0;
    ::waitpid(p, &st, 0);
    failedReaders += WIFEXITED(st) && WEXITSTATUS(st) != 0;
  }
  std::vector<double> lat;
  for (int w = 0; w < a.writers; ++w) {
    std::ifstream in(latencies + std::to_string(w));
    for (double x; in >> x;) lat.push_back(x);
    std::filesystem::remove(latencies + std::to_string(w));
  }

  // Every model complete, versions 1..N*K, no duplicates.
  auto db = TaskDatabase::open(a.db, TaskDatabase::Mode::ReadOnly);
  TaskModelStore store(db);
  std::set<int> versions;
  int stored = 0, incomplete = 0;
  for (const auto& info : store.list()) {
    if (info.name != "load") continue;
    ++stored;
    versions.insert(info.version);
    incomplete += rows(store.read(info.id)) != modelRows;
  }
  const int expected = a.writers * a.perWriter;
  const bool versionsOk = static_cast<int>(versions.size()) == stored && stored == expected &&
                          (versions.empty() || (*versions.begin() == 1 && *versions.rbegin() == expected));

  // SIGKILL of a writer in the middle of its transaction: nothing of it stays.
  const pid_t victim = ::fork();
  if (victim == 0) {
    auto vdb = TaskDatabase::open(a.db);
    TaskModelStore(vdb).write(model, [](std::size_t done, std::size_t total) {
      if (2 * done >= total) ::raise(SIGKILL);
    });
    ::_exit(0);
  }
  int vst = 0;
  ::waitpid(victim, &vst, 0);
  const bool killed = WIFSIGNALED(vst) && WTERMSIG(vst) == SIGKILL;
  auto after = TaskDatabase::open(a.db, TaskDatabase::Mode::ReadOnly);
  const bool unchangedAfterKill = TaskModelStore(after).list().size() == store.list().size();

  nlohmann::json j = {{"target", TaskDatabase::displayName(a.db)},
                      {"backend", after.isPostgres() ? "postgresql" : "sqlite"},
                      {"writers", a.writers},
                      {"readers", a.readers},
                      {"stores_per_writer", a.perWriter},
                      {"rows_per_model", modelRows},
                      {"wall_s", wall_s},
                      {"stores_per_s", static_cast<double>(lat.size()) / wall_s},
                      {"store_p50_s", percentile(lat, 0.5)},
                      {"store_p95_s", percentile(lat, 0.95)},
                      {"stored", stored},
                      {"expected", expected},
                      {"incomplete", incomplete},
                      {"versions_distinct_1_to_n", versionsOk},
                      {"failed_writers", failedWriters},
                      {"failed_readers", failedReaders},
                      {"writer_killed_mid_transaction", killed},
                      {"library_unchanged_after_kill", unchangedAfterKill}};
  std::cout << j.dump() << "\n";
  return (failedWriters == 0 && failedReaders == 0 && incomplete == 0 && versionsOk && killed && unchangedAfterKill) ? 0 : 1;
}
