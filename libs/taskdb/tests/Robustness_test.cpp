// Bad input, damaged files, kills and concurrency: the database must never
// lose or half-write a task model.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <SQLiteCpp/SQLiteCpp.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <thread>

#include "TestDb.h"
#include "srp/core/Error.h"
#include "srp/taskdb/ProductDao.h"
#include "srp/taskdb/TaskModelStore.h"

using namespace srp::taskdb;
using srp::core::FileError;

namespace {
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
  EXPECT_EQ(back.products.at(0).color, "gr'ay");
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
