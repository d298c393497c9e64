// Bad input, damaged files, kills and concurrency: the database must never
// lose or half-write a task model.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <grp.h>
#include <unistd.h>

#include <SQLiteCpp/SQLiteCpp.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <random>
#include <thread>

#include "TestDb.h"
#include "srp/core/Error.h"
#include "srp/taskdb/ProductDao.h"
#include "srp/taskdb/TaskModelStore.h"

using namespace srp::taskdb;
using srp::core::FileError;

namespace {

/// Permission bits do not stop root, and CI runs as root: there the check runs in a child process that
/// has become the unprivileged user nobody (uid/gid 65534), where they apply. The check gets a folder of
/// its own, writable by whoever runs it (the temporary folder may not be: TMPDIR can name a folder only
/// root writes), removed afterwards. Returns the check's failure message ("" = passed).
std::string asOrdinaryUser(const std::function<std::string(const std::filesystem::path& folder)>& check) {
  constexpr uid_t kNobody = 65534;
  const auto folder = std::filesystem::temp_directory_path() / ("srp_taskdb_user_" + std::to_string(getpid()));
  std::filesystem::remove_all(folder);
  std::filesystem::create_directories(folder);
  struct Removed {
    std::filesystem::path p;
    ~Removed() {
      std::error_code ignored;
      std::filesystem::permissions(p, std::filesystem::perms::owner_all, ignored);
      std::filesystem::remove_all(p, ignored);
    }
  } removed{folder};
  if (geteuid() != 0) return check(folder);
  if (chown(folder.c_str(), kNobody, kNobody) != 0) return "could not give the test folder to the user nobody";
  int fds[2];
  if (pipe(fds) != 0) return "pipe failed";
  const pid_t pid = fork();
  if (pid == 0) {
    close(fds[0]);
    std::string message;
    if (setgroups(0, nullptr) != 0 || setgid(kNobody) != 0 || setuid(kNobody) != 0) {
      message = "could not become the user nobody";
    } else {
      try {
        message = check(folder);
      } catch (const std::exception& e) {
        message = std::string("exception: ") + e.what();
      }
    }
    if (!message.empty() && write(fds[1], message.data(), message.size()) < 0) message.clear();
    _exit(0);  // no gtest teardown in the child
  }
  close(fds[1]);
  std::string message;
  char buffer[512];
  for (ssize_t n; (n = read(fds[0], buffer, sizeof buffer)) > 0;) message.append(buffer, static_cast<std::size_t>(n));
  close(fds[0]);
  int status = 0;
  waitpid(pid, &status, 0);
  if (!WIFEXITED(status)) return "the unprivileged child died: " + message;
  return message;
}

std::string errorOf(const std::string& path) {
  try {
    TaskDatabase::open(path);
  } catch (const FileError& e) {
    return e.what();
  }
  return "";
}

// Everything in the database, as text, to compare before and after.
std::string dump(const std::string& path) {
  SQLite::Database db(path, SQLite::OPEN_READONLY);
  std::string out;
  for (const char* table : {"TaskModels", "Products", "SourceLocations", "TargetLocations", "TaskModelTargetObjects",
                            "GroundedProducts", "ProductPose", "HandPositions", "Skills"}) {
    SQLite::Statement st(db, std::string("SELECT * FROM ") + table + " ORDER BY 1, 2");
    out += table;
    while (st.executeStep())
      for (int c = 0; c < st.getColumnCount(); ++c) out += "|" + st.getColumn(c).getString();
    out += "\n";
  }
  return out;
}
}  // namespace

TEST(Robustness, SqlInNamesIsStoredVerbatim) {
  test::TempDbPath path("injection");
  auto db = TaskDatabase::open(path.str());
  const std::string evil = "box'); DROP TABLE Products;--";
  TaskModel m;
  m.info.name = "robert'); DROP TABLE TaskModels;--";
  m.info.instruction = "put the \"quoted\" box'); DROP TABLE Products;-- away";
  m.products = {{0, evil, {}, {}, "gr'ay", {}, {}, {}}};
  TaskModelStore store(db);
  const int id = store.write(m);
  const TaskModel back = store.read(id);
  EXPECT_EQ(back.products.at(0).objectName, evil);
  EXPECT_EQ(back.products.at(0).colour, "gr'ay");
  EXPECT_EQ(back.info.name, m.info.name);
  EXPECT_EQ(back.info.instruction, m.info.instruction);
  EXPECT_EQ(store.list().size(), 1u);
}

TEST(Robustness, TruncatedCorruptAndForeignFilesNameTheFile) {
  test::TempDbPath path("corrupt");
  {
    auto db = TaskDatabase::open(path.str());
    TaskModelStore(db).write(test::bulkModel("big", 3000, 3));
    db.connection().exec("PRAGMA wal_checkpoint(TRUNCATE)");
  }
  const auto size = std::filesystem::file_size(path.str());
  ASSERT_GT(size, 100000u);
  std::filesystem::resize_file(path.str(), size / 2);
  const std::string truncated = errorOf(path.str());
  EXPECT_NE(truncated.find(path.str()), std::string::npos) << truncated;
  EXPECT_FALSE(truncated.empty());

  std::filesystem::resize_file(path.str(), 10);
  const std::string tiny = errorOf(path.str());
  EXPECT_NE(tiny.find(path.str()), std::string::npos);
  EXPECT_NE(tiny.find("not a task database"), std::string::npos) << tiny;

  std::ofstream(path.str(), std::ios::trunc) << "ObjectId,ObjectName\n0,cuboid\n";
  EXPECT_NE(errorOf(path.str()).find("not a task database"), std::string::npos);

  // Overwrite pages in the middle of a valid file with garbage.
  std::filesystem::remove(path.str());
  {
    auto db = TaskDatabase::open(path.str());
    TaskModelStore(db).write(test::bulkModel("big", 3000, 3));
    db.connection().exec("PRAGMA wal_checkpoint(TRUNCATE)");
  }
  {
    std::fstream f(path.str(), std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(3 * 4096 + 100);
    const std::string garbage(6000, '\x5a');
    f.write(garbage.data(), static_cast<std::streamsize>(garbage.size()));
  }
  const std::string corrupt = errorOf(path.str());
  EXPECT_NE(corrupt.find(path.str()), std::string::npos) << corrupt;
  EXPECT_NE(corrupt.find("corrupt"), std::string::npos) << corrupt;
}

TEST(Robustness, NewerSchemaIsRefusedClearly) {
  test::TempDbPath path("newer");
  { TaskDatabase::open(path.str()); }
  { SQLite::Database raw(path.str(), SQLite::OPEN_READWRITE); raw.exec("PRAGMA user_version = 99"); }
  const std::string e = errorOf(path.str());
  EXPECT_NE(e.find(path.str()), std::string::npos);
  EXPECT_NE(e.find("schema version 99"), std::string::npos) << e;
}

TEST(Robustness, ExceptionMidWriteLeavesTheDatabaseAsItWas) {
  test::TempDbPath path("abort");
  auto db = TaskDatabase::open(path.str());
  TaskModelStore store(db);
  store.write(test::bulkModel("first", 200, 2));
  const std::string before = dump(path.str());
  const auto abortHalfway = [](std::size_t done, std::size_t total) {
    if (done * 2 >= total) throw std::runtime_error("disk on fire");
  };
  EXPECT_THROW(store.write(test::bulkModel("second", 3000, 4), abortHalfway), std::runtime_error);
  EXPECT_EQ(dump(path.str()), before);
}

TEST(Robustness, WriterKilledMidTransactionLeavesThePreviousModelIntact) {
  test::TempDbPath path("killed");
  int firstId = 0;
  {
    auto db = TaskDatabase::open(path.str());
    firstId = TaskModelStore(db).write(test::bulkModel("previous", 300, 2));
  }
  const std::string before = dump(path.str());
  int pipefd[2];
  ASSERT_EQ(pipe(pipefd), 0);
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    close(pipefd[0]);
    auto db = TaskDatabase::open(path.str());
    TaskModelStore(db).write(test::bulkModel("killed", 2000, 20), [&](std::size_t done, std::size_t total) {
      if (done * 2 >= total) {  // half of the rows are in the open transaction
        const char c = 'x';
        if (write(pipefd[1], &c, 1) != 1) _exit(3);
        pause();  // wait for SIGKILL
      }
    });
    _exit(2);  // not reached
  }
  close(pipefd[1]);
  char c = 0;
  ASSERT_EQ(read(pipefd[0], &c, 1), 1);
  kill(child, SIGKILL);
  int status = 0;
  waitpid(child, &status, 0);
  ASSERT_TRUE(WIFSIGNALED(status));
  close(pipefd[0]);

  auto db = TaskDatabase::open(path.str());
  TaskModelStore store(db);
  ASSERT_EQ(store.list().size(), 1u);
  EXPECT_EQ(store.read(firstId).productPoses.size(), 600u);
  EXPECT_EQ(dump(path.str()), before);
}

TEST(Robustness, TwoReadersAndOneWriterAtOnce) {
  test::TempDbPath path("concurrent");
  { TaskDatabase::open(path.str()); }
  constexpr int kModels = 12;
  std::atomic<bool> writerDone{false};
  std::atomic<int> inconsistent{0}, reads{0};
  std::thread writer([&] {
    auto db = TaskDatabase::open(path.str());
    TaskModelStore store(db);
    for (int i = 0; i < kModels; ++i) store.write(test::bulkModel("m" + std::to_string(i), 400, 3));
    writerDone = true;
  });
  const auto reader = [&] {
    auto db = TaskDatabase::open(path.str(), TaskDatabase::Mode::ReadOnly);
    TaskModelStore store(db);
    while (!writerDone || reads < 4) {
      for (const auto& info : store.list()) {
        const TaskModel m = store.read(info.id);
        // Every model a reader sees is complete: never half-written.
        if (m.handPositions.size() != 400u || m.productPoses.size() != 1200u) ++inconsistent;
        ++reads;
      }
    }
  };
  std::thread r1(reader), r2(reader);
  writer.join();
  r1.join();
  r2.join();
  EXPECT_EQ(inconsistent.load(), 0);
  EXPECT_GT(reads.load(), 0);
  auto db = TaskDatabase::open(path.str());
  EXPECT_EQ(TaskModelStore(db).list().size(), static_cast<std::size_t>(kModels));
}

TEST(Robustness, BulkInsertOf100kPoseRows) {
  // A 60 s, 30 FPS demo with 50 objects: 1800 x 50 = 90 000 pose rows + 1800 hand rows.
  // The time is measured by bench/taskdb_bench.cpp; here only correctness.
  test::TempDbPath path("bulk");
  auto db = TaskDatabase::open(path.str());
  TaskModelStore store(db);
  const TaskModel m = test::bulkModel("bulk", 2000, 50);
  const int id = store.write(m);
  const TaskModel back = store.read(id);
  ASSERT_EQ(back.productPoses.size(), 100000u);
  EXPECT_EQ(back.productPoses[54321], m.productPoses[54321]);
  EXPECT_EQ(back.handPositions.size(), 2000u);
}

// ---- Issue 21: concurrent first use, read-only use, foreign files, messages ----

namespace {
std::string fileBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}
bool exists(const std::string& path) { return std::filesystem::exists(path); }
}  // namespace

TEST(Robustness, TwoWritersOnANewFileBothStoreTheirWork) {
  constexpr int kRounds = 30;
  test::TempDbPath path("first_use");
  for (int round = 0; round < kRounds; ++round) {
    for (const char* suffix : {"", "-wal", "-shm", "-journal"}) std::filesystem::remove(path.str() + suffix);
    // Two processes (file locks are per process) open the same new file at once.
    pid_t children[2];
    for (int w = 0; w < 2; ++w) {
      children[w] = fork();
      ASSERT_GE(children[w], 0);
      if (children[w] == 0) {
        try {
          auto db = TaskDatabase::open(path.str());
          TaskModelStore(db).write(test::bulkModel("writer" + std::to_string(w), 50, 2));
          _exit(0);
        } catch (const std::exception& e) {
          std::fprintf(stderr, "writer %d: %s\n", w, e.what());
          _exit(1);
        }
      }
    }
    for (const pid_t child : children) {
      int status = 0;
      waitpid(child, &status, 0);
      ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << "round " << round << ": a writer failed";
    }
    auto db = TaskDatabase::open(path.str(), TaskDatabase::Mode::ReadOnly);
    const auto models = TaskModelStore(db).list();
    ASSERT_EQ(models.size(), 2u) << "round " << round;
    for (const auto& m : models) EXPECT_EQ(TaskModelStore(db).read(m.id).productPoses.size(), 100u);
  }
}

TEST(Robustness, ReadOnlyOpenWritesNothing) {
  test::TempDbPath path("readonly");
  {
    auto db = TaskDatabase::open(path.str());
    TaskModelStore(db).write(test::bulkModel("kept", 100, 2));
  }
  ASSERT_FALSE(exists(path.str() + "-wal")) << "the last writer's close checkpoints and removes the WAL";
  const std::string before = fileBytes(path.str());
  const auto mtime = std::filesystem::last_write_time(path.str());
  {
    auto db = TaskDatabase::open(path.str(), TaskDatabase::Mode::ReadOnly);
    TaskModelStore store(db);
    ASSERT_EQ(store.list().size(), 1u);
    EXPECT_EQ(store.read(store.list()[0].id).handPositions.size(), 100u);
    EXPECT_THROW(db.connection().exec("DELETE FROM TaskModels"), SQLite::Exception) << "opened with SQLITE_OPEN_READONLY";
  }
  EXPECT_EQ(fileBytes(path.str()), before);
  EXPECT_EQ(std::filesystem::last_write_time(path.str()), mtime);
  // SQLite may leave an empty -wal beside a WAL database a reader opened (a
  // read-only connection cannot remove it), but nothing is written to it.
  if (exists(path.str() + "-wal")) EXPECT_EQ(std::filesystem::file_size(path.str() + "-wal"), 0u);

  // A database in rollback-journal mode stays so: a read-only open switches nothing.
  { SQLite::Database raw(path.str(), SQLite::OPEN_READWRITE); raw.exec("PRAGMA journal_mode = DELETE"); }
  const std::string rollback = fileBytes(path.str());
  ASSERT_EQ(rollback[18], 1) << "file format byte: 1 = rollback journal, 2 = WAL";
  { auto db = TaskDatabase::open(path.str(), TaskDatabase::Mode::ReadOnly); TaskModelStore(db).list(); }
  EXPECT_EQ(fileBytes(path.str()), rollback);
}

TEST(Robustness, ReadOnlyOpenWorksInAReadOnlyFolder) {
  const std::string failure = asOrdinaryUser([](const std::filesystem::path& folder) {
    const auto dir = folder / "rofolder";
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    const std::string path = (dir / "task.db").string();
    {
      auto db = TaskDatabase::open(path);
      TaskModelStore(db).write(test::bulkModel("kept", 10, 1));
    }
    std::filesystem::permissions(dir, std::filesystem::perms::owner_read | std::filesystem::perms::owner_exec);
    std::string error;
    std::size_t count = 0;
    try {
      auto db = TaskDatabase::open(path, TaskDatabase::Mode::ReadOnly);
      count = TaskModelStore(db).list().size();
    } catch (const std::exception& e) {
      error = e.what();
    }
    std::filesystem::permissions(dir, std::filesystem::perms::owner_all);
    std::filesystem::remove_all(dir);
    if (!error.empty()) return "read-only open failed: " + error;
    if (count != 1) return "listed " + std::to_string(count) + " task models, expected 1";
    return std::string();
  });
  EXPECT_EQ(failure, "");
}

TEST(Robustness, ForeignSqliteFileIsRefusedAndLeftUnchanged) {
  test::TempDbPath path("foreign");
  {
    SQLite::Database raw(path.str(), SQLite::OPEN_READWRITE | SQLite::OPEN_CREATE);
    raw.exec("CREATE TABLE Customers (id INTEGER PRIMARY KEY, name TEXT); INSERT INTO Customers VALUES (1, 'ada')");
  }
  const std::string before = fileBytes(path.str());
  for (const auto mode : {TaskDatabase::Mode::ReadWrite, TaskDatabase::Mode::ReadOnly}) {
    try {
      TaskDatabase::open(path.str(), mode);
      ADD_FAILURE() << "another application's SQLite file was accepted";
    } catch (const FileError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("not a task database"), std::string::npos) << what;
      EXPECT_NE(what.find("Customers"), std::string::npos) << what;
    }
  }
  EXPECT_EQ(fileBytes(path.str()), before) << "no tables added, no switch to WAL";
  EXPECT_FALSE(exists(path.str() + "-wal"));

  // An empty file is fine: it becomes a task database.
  test::TempDbPath empty("empty");
  std::ofstream(empty.str()).close();
  EXPECT_EQ(TaskDatabase::open(empty.str()).schemaVersion(), kSchemaVersion);
}

TEST(Robustness, LockContentionIsReportedAsALockNotAsCorruption) {
  test::TempDbPath path("locked");
  { TaskDatabase::open(path.str()); }
  SQLite::Database holder(path.str(), SQLite::OPEN_READWRITE);
  holder.exec("BEGIN EXCLUSIVE");
  constexpr int kShortTimeout_ms = 200;
  std::string what;
  try {
    TaskDatabase::open(path.str(), TaskDatabase::Mode::ReadWrite, kShortTimeout_ms);
  } catch (const FileError& e) {
    what = e.what();
  }
  EXPECT_NE(what.find("locked by another program"), std::string::npos) << what;
  EXPECT_NE(what.find("retry"), std::string::npos) << what;
  EXPECT_EQ(what.find("corrupt"), std::string::npos) << what;

  // A write on an open connection waits, then says the same.
  holder.exec("ROLLBACK");
  auto db = TaskDatabase::open(path.str(), TaskDatabase::Mode::ReadWrite, kShortTimeout_ms);
  holder.exec("BEGIN EXCLUSIVE");
  try {
    TaskModelStore(db).write(test::bulkModel("late", 5, 1));
    ADD_FAILURE() << "write under another writer's lock succeeded";
  } catch (const FileError& e) {
    EXPECT_NE(std::string(e.what()).find("locked by another program"), std::string::npos) << e.what();
  }
  holder.exec("ROLLBACK");
  EXPECT_EQ(TaskModelStore(db).list().size(), 0u);
}

TEST(Robustness, NoPermissionIsReportedAsSuch) {
  const std::string failure = asOrdinaryUser([](const std::filesystem::path& folder) {
    const std::string path = (folder / "noperm.db").string();
    for (const char* suffix : {"", "-wal", "-shm"}) std::filesystem::remove(path + suffix);
    { TaskDatabase::open(path); }
    std::filesystem::permissions(path, std::filesystem::perms::none);
    const std::string what = errorOf(path);
    std::filesystem::permissions(path, std::filesystem::perms::owner_read | std::filesystem::perms::owner_write);
    for (const char* suffix : {"", "-wal", "-shm"}) std::filesystem::remove(path + suffix);
    if (what.find("permission") == std::string::npos) return "no 'permission' in: " + what;
    if (what.find("corrupt") != std::string::npos) return "'corrupt' in: " + what;
    return std::string();
  });
  EXPECT_EQ(failure, "");
}

// Issue 21: seeded single-byte mutations and truncations of a small task
// database: each opens and reads (SQLite has no page checksums, so a flipped
// value can read as another value) or fails with srp's error naming the file;
// never a crash or a raw SQLite exception.
TEST(TaskDbFuzz, MutatedDatabasesReadOrNameTheFile) {
  constexpr int kCases = 600;
  test::TempDbPath original("fuzz_original");
  {
    auto db = TaskDatabase::open(original.str());
    TaskModelStore(db).write(test::bulkModel("fuzz", 30, 2));
    db.connection().exec("PRAGMA wal_checkpoint(TRUNCATE)");
  }
  const std::string bytes = fileBytes(original.str());
  const std::string clean = dump(original.str());
  test::TempDbPath path("fuzz_case");
  std::mt19937 rng(2021);
  int exact = 0, changed = 0, refused = 0;
  for (int i = 0; i < kCases; ++i) {
    std::string m = bytes;
    if (i % 6 == 5) {
      m.resize(rng() % m.size());
    } else {
      const std::size_t at = rng() % m.size();
      m[at] = static_cast<char>(m[at] ^ static_cast<char>(1 + rng() % 255));
    }
    for (const char* suffix : {"", "-wal", "-shm"}) std::filesystem::remove(path.str() + suffix);
    std::ofstream(path.str(), std::ios::binary) << m;
    try {
      auto db = TaskDatabase::open(path.str(), TaskDatabase::Mode::ReadOnly);
      TaskModelStore store(db);
      for (const auto& info : store.list()) store.read(info.id);
      std::string content;
      try {
        content = dump(path.str());  // every row, also pages the store did not read
      } catch (const SQLite::Exception&) {
        content = "unreadable";
      }
      (content == clean ? exact : changed)++;
    } catch (const srp::core::Error& e) {
      ++refused;
      const std::string what = e.what();
      if (what.find(path.str()) == std::string::npos && what.find("task model") == std::string::npos)
        ADD_FAILURE() << "case " << i << ": message names neither the file nor the model: " << what;
    } catch (const std::exception& e) {
      ADD_FAILURE() << "case " << i << ": not an srp error: " << e.what();
    }
  }
  EXPECT_EQ(exact + changed + refused, kCases);
  EXPECT_GT(refused, 0);
  std::cout << "[ fuzz ] task database: " << kCases << " cases, " << exact << " read exactly, " << changed
            << " read with changed values, " << refused << " refused\n";
}
