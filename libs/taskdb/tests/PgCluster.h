#pragma once
// A throw-away PostgreSQL cluster for the tests: initdb + pg_ctl on a free
// local port under a temporary folder, started once per test binary (on first
// use) and stopped at exit; or started by one program and used by others
// (startShared / attach / stopShared through a state file: the command-line
// tests start one cluster for the whole CTest run). The server refuses to run
// as root, so under root (CI) every server command runs as `nobody` through
// runuser.
#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <pwd.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <pqxx/pqxx>

#include <algorithm>
#include <atomic>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace srp::taskdb::test {

class PgCluster {
 public:
  /// The one cluster of this process (started on first call).
  static PgCluster& instance() {
    static PgCluster cluster;
    return cluster;
  }
  bool available() const { return running_; }
  /// Why there is no server (for GTEST_SKIP / failures).
  const std::string& problem() const { return problem_; }
  /// True when the machine has no server binary at all (the only reason to skip).
  bool noBinary() const { return binDir_.empty(); }
  /// URI of the cluster's maintenance database.
  std::string adminUri() const { return uri("postgres"); }
  std::string uri(const std::string& database) const {
    return "postgresql://srp@127.0.0.1:" + std::to_string(port_) + "/" + database;
  }
  /// Creates a new empty database and returns its URI.
  std::string createDatabase(const std::string& hint) {
    std::string name = "t" + std::to_string(++databases_) + "_";
    for (const char c : hint) name += std::isalnum(static_cast<unsigned char>(c)) ? static_cast<char>(std::tolower(c)) : '_';
    return createNamedDatabase(name, false);
  }
  /// Creates database `name` (letters, digits, '_'; dropped first when `fresh`,
  /// kept when it exists otherwise) and returns its URI.
  std::string createNamedDatabase(std::string name, bool fresh) {
    for (auto& c : name) c = std::isalnum(static_cast<unsigned char>(c)) ? static_cast<char>(std::tolower(c)) : '_';
    name = name.substr(0, 60);
    pqxx::connection c(adminUri());
    pqxx::nontransaction n(c);
    if (fresh) n.exec("DROP DATABASE IF EXISTS " + c.quote_name(name) + " WITH (FORCE)");
    if (n.exec_params("SELECT 1 FROM pg_database WHERE datname = $1", name).empty()) {
      try {
        n.exec("CREATE DATABASE " + c.quote_name(name));
      } catch (const pqxx::sql_error& e) {
        if (e.sqlstate() != "42P04") throw;  // created by a concurrent test: fine
      }
    }
    return uri(name);
  }

  /// Starts a cluster that outlives this process; its folder and port go to
  /// `stateFile` (a cluster left there by an earlier run is stopped first).
  static PgCluster& startShared(const std::string& stateFile) {
    stopShared(stateFile);
    static PgCluster cluster(true);
    if (cluster.running_) {
      std::ofstream out(stateFile);
      out << cluster.dir_ << "\n" << cluster.port_ << "\n";
    } else if (cluster.noBinary()) {
      std::ofstream(stateFile) << "no-binary\n";
    }
    return cluster;
  }
  /// The cluster startShared left in `stateFile`: available() false (and
  /// problem() saying why) when there is none or the machine has no server.
  static PgCluster& attach(const std::string& stateFile) {
    static PgCluster cluster(stateFile);
    return cluster;
  }
  /// Stops the cluster of `stateFile` and removes its folder; true if one ran.
  static bool stopShared(const std::string& stateFile) {
    std::ifstream in(stateFile);
    std::string dir;
    int port = 0;
    if (!(in >> dir >> port)) {
      std::error_code ec;
      std::filesystem::remove(stateFile, ec);
      return false;
    }
    PgCluster c(stateFile);
    c.stop();
    std::error_code ec;
    std::filesystem::remove(stateFile, ec);
    return true;
  }

  ~PgCluster() {
    if (shared_) return;
    stop();
  }

 private:
  PgCluster() : PgCluster(false) {}

  // Attaches to a running shared cluster.
  explicit PgCluster(const std::string& stateFile) : shared_(true) {
    binDir_ = findBinDir();
    if (binDir_.empty()) {
      problem_ = kNoBinary;
      return;
    }
    std::ifstream in(stateFile);
    if (!(in >> dir_ >> port_)) {
      problem_ = "no shared PostgreSQL cluster (" + stateFile + " missing: its CTest fixture did not start one)";
      return;
    }
    if (::geteuid() == 0) asUser_ = {"runuser", "-u", "nobody", "--"};
    running_ = true;
  }

  void stop() {
    if (running_) run({binDir_ + "/pg_ctl", "-D", dir_ + "/data", "-m", "immediate", "-w", "stop"});
    running_ = false;
    if (!dir_.empty()) {
      std::error_code ec;
      std::filesystem::remove_all(dir_, ec);
    }
  }

  static constexpr const char* kNoBinary =
      "no PostgreSQL server binary (initdb, pg_ctl) under /usr/lib/postgresql/*/bin; install the "
      "'postgresql' package (scripts/install-deps.sh) to run the PostgreSQL tests";

  explicit PgCluster(bool shared) : shared_(shared) {
    binDir_ = findBinDir();
    if (binDir_.empty()) {
      problem_ = kNoBinary;
      return;
    }
    char tmpl[] = "/tmp/srp_pg_XXXXXX";
    if (!::mkdtemp(tmpl)) {
      problem_ = "cannot create a temporary folder for the cluster";
      return;
    }
    dir_ = tmpl;
    if (::geteuid() == 0) {
      const passwd* pw = ::getpwnam("nobody");
      if (!pw || ::chown(dir_.c_str(), pw->pw_uid, pw->pw_gid) != 0) {
        problem_ = "running as root and cannot hand " + dir_ + " to user nobody";
        return;
      }
      asUser_ = {"runuser", "-u", "nobody", "--"};
    }
    port_ = freePort();
    if (run({binDir_ + "/initdb", "-D", dir_ + "/data", "-U", "srp", "--auth=trust", "-E", "UTF8", "--no-locale",
             "--no-sync"}) != 0) {
      problem_ = "initdb failed (log: " + dir_ + "/server.log)";
      return;
    }
    const std::string options = "-p " + std::to_string(port_) + " -k " + dir_ +
                                " -c listen_addresses=127.0.0.1 -c fsync=off -c full_page_writes=off"
                                " -c max_connections=200";
    if (run({binDir_ + "/pg_ctl", "-D", dir_ + "/data", "-l", dir_ + "/server.log", "-w", "-t", "60", "-o", options,
             "start"}) != 0) {
      problem_ = "pg_ctl start failed (log: " + dir_ + "/server.log)";
      return;
    }
    running_ = true;
  }

  static std::string findBinDir() {
    std::vector<std::string> dirs;
    std::error_code ec;
    for (const auto& e : std::filesystem::directory_iterator("/usr/lib/postgresql", ec)) {
      const auto bin = e.path() / "bin";
      if (std::filesystem::exists(bin / "initdb") && std::filesystem::exists(bin / "pg_ctl")) dirs.push_back(bin);
    }
    if (dirs.empty()) return {};
    std::sort(dirs.begin(), dirs.end(), [](const std::string& a, const std::string& b) {
      return a.size() != b.size() ? a.size() < b.size() : a < b;
    });
    return dirs.back();  // the newest version
  }

  static int freePort() {
    const int s = ::socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    a.sin_port = 0;
    socklen_t len = sizeof a;
    int port = 0;
    if (::bind(s, reinterpret_cast<sockaddr*>(&a), sizeof a) == 0 &&
        ::getsockname(s, reinterpret_cast<sockaddr*>(&a), &len) == 0)
      port = ntohs(a.sin_port);
    ::close(s);
    return port;
  }

  // Runs a server command (as nobody under root) in the cluster folder; its
  // output goes to server.log's neighbour, commands.log.
  int run(std::vector<std::string> argv) const {
    argv.insert(argv.begin(), asUser_.begin(), asUser_.end());
    const pid_t pid = ::fork();
    if (pid == 0) {
      if (::chdir(dir_.c_str()) != 0) ::_exit(126);
      const int log = ::open((dir_ + "/commands.log").c_str(), O_WRONLY | O_CREAT | O_APPEND, 0666);
      if (log >= 0) {
        ::dup2(log, 1);
        ::dup2(log, 2);
      }
      std::vector<char*> args;
      for (auto& a : argv) args.push_back(a.data());
      args.push_back(nullptr);
      ::execvp(args[0], args.data());
      ::_exit(127);
    }
    int status = 0;
    ::waitpid(pid, &status, 0);
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128;
  }

  std::string binDir_, dir_, problem_;
  std::vector<std::string> asUser_;
  int port_ = 0;
  bool running_ = false;
  bool shared_ = false;
  std::atomic<int> databases_{0};
};

}  // namespace srp::taskdb::test
