// srp_pg_sandbox: runs commands against a throw-away PostgreSQL server
// (tests/PgCluster.h). For the command-line tests and the load benchmark.
//
//   srp_pg_sandbox CMD ARGS...
//       starts a cluster, creates an empty database, runs CMD with SRP_DB set
//       to its URI, stops the cluster.
//   srp_pg_sandbox --start STATE      starts a cluster that outlives the call
//                                     (its folder and port in the file STATE)
//   srp_pg_sandbox --stop STATE       stops it and removes its folder
//   srp_pg_sandbox --cluster STATE --database NAME [--fresh] [--] CMD ARGS...
//       runs CMD with SRP_DB set to database NAME of that cluster (created if
//       missing; dropped and created again with --fresh).
//
// Exits with CMD's exit code, or 77 (CTest's SKIP_RETURN_CODE) when the
// machine has no server binary.
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <iostream>
#include <string>

#include "PgCluster.h"

namespace {

constexpr int kSkipped = 77;

using srp::taskdb::test::PgCluster;

int runWithDb(const std::string& uri, char** argv) {
  ::setenv("SRP_DB", uri.c_str(), 1);
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::execvp(argv[0], argv);
    std::cerr << "srp_pg_sandbox: cannot run " << argv[0] << "\n";
    ::_exit(127);
  }
  int status = 0;
  ::waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

// Skipped (77) without a server binary, 1 when the cluster is not there.
int unavailable(const PgCluster& cluster) {
  if (cluster.noBinary()) {
    std::cerr << "srp_pg_sandbox: skipped: " << cluster.problem() << "\n";
    return kSkipped;
  }
  std::cerr << "srp_pg_sandbox: " << cluster.problem() << "\n";
  return 1;
}

int usage() {
  std::cerr << "usage: srp_pg_sandbox CMD ARGS...              (CMD with SRP_DB of a throw-away server)\n"
               "       srp_pg_sandbox --start STATE | --stop STATE\n"
               "       srp_pg_sandbox --cluster STATE --database NAME [--fresh] [--] CMD ARGS...\n";
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) return usage();
  const std::string first = argv[1];
  try {
    if (first == "--start" || first == "--stop") {
      if (argc != 3) return usage();
      if (first == "--stop") {
        std::cout << (PgCluster::stopShared(argv[2]) ? "cluster stopped\n" : "no cluster was running\n");
        return 0;
      }
      auto& cluster = PgCluster::startShared(argv[2]);
      if (!cluster.available()) return unavailable(cluster);
      std::cout << "cluster started: " << cluster.adminUri() << "\n";
      return 0;
    }
    if (first == "--cluster") {
      std::string state, database;
      bool fresh = false;
      int i = 1;
      for (; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--cluster" && i + 1 < argc) state = argv[++i];
        else if (a == "--database" && i + 1 < argc) database = argv[++i];
        else if (a == "--fresh") fresh = true;
        else if (a == "--") {
          ++i;
          break;
        } else break;
      }
      if (state.empty() || database.empty() || i >= argc) return usage();
      auto& cluster = PgCluster::attach(state);
      if (!cluster.available()) return unavailable(cluster);
      return runWithDb(cluster.createNamedDatabase(database, fresh), argv + i);
    }
    auto& cluster = PgCluster::instance();
    if (!cluster.available()) return unavailable(cluster);
    return runWithDb(cluster.createDatabase("sandbox"), argv + 1);
  } catch (const std::exception& e) {
    std::cerr << "srp_pg_sandbox: " << e.what() << "\n";
    return 1;
  }
}
