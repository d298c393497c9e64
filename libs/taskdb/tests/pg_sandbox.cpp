// srp_pg_sandbox CMD ARGS...: runs a command against a throw-away PostgreSQL
// server (tests/PgCluster.h): starts a cluster, creates an empty database,
// runs CMD with SRP_DB set to its URI, stops the cluster, exits with CMD's
// exit code (77 when the machine has no server binary). For the command-line
// tests and the load benchmark.
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <iostream>

#include "PgCluster.h"

int main(int argc, char** argv) {
  if (argc < 2) {
    std::cerr << "usage: srp_pg_sandbox CMD ARGS... (runs CMD with SRP_DB=postgresql://... of a throw-away server)\n";
    return 2;
  }
  auto& cluster = srp::taskdb::test::PgCluster::instance();
  if (cluster.noBinary()) {
    std::cerr << "srp_pg_sandbox: skipped: " << cluster.problem() << "\n";
    return 77;
  }
  if (!cluster.available()) {
    std::cerr << "srp_pg_sandbox: " << cluster.problem() << "\n";
    return 1;
  }
  const std::string uri = cluster.createDatabase("sandbox");
  ::setenv("SRP_DB", uri.c_str(), 1);
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::execvp(argv[1], argv + 1);
    std::cerr << "srp_pg_sandbox: cannot run " << argv[1] << "\n";
    ::_exit(127);
  }
  int status = 0;
  ::waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}
