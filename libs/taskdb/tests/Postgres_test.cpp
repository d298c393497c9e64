// Server-only behaviour of the PostgreSQL backend: concurrent first use,
// race-free versioning under concurrent writers, read-only connections,
// credentials never shown.
#include <gtest/gtest.h>

#include <set>
#include <thread>

#include "PgCluster.h"
#include "TestDb.h"
#include "srp/core/Error.h"
#include "srp/taskdb/TaskModelDao.h"
#include "srp/taskdb/TaskModelStore.h"

using namespace srp::taskdb;

namespace {

class Postgres : public ::testing::Test {
 protected:
  void SetUp() override {
    auto& cluster = test::PgCluster::instance();
    if (cluster.noBinary()) GTEST_SKIP() << cluster.problem();
    ASSERT_TRUE(cluster.available()) << cluster.problem();
  }
};

// Runs `body(i)` on n threads at once; returns the errors they threw.
template <typename F>
std::vector<std::string> onThreads(int n, F body) {
  std::vector<std::string> errors(static_cast<std::size_t>(n));
  std::vector<std::thread> threads;
  for (int i = 0; i < n; ++i)
    threads.emplace_back([&, i] {
      try {
        body(i);
      } catch (const std::exception& e) {
        errors[static_cast<std::size_t>(i)] = e.what();
      }
    });
  for (auto& t : threads) t.join();
  std::vector<std::string> failed;
  for (const auto& e : errors)
    if (!e.empty()) failed.push_back(e);
  return failed;
}

}  // namespace

TEST_F(Postgres, ConcurrentFirstUseCreatesTheSchemaOnce) {
  constexpr int kWriters = 8;
  const std::string uri = test::PgCluster::instance().createDatabase("first_use");
  const auto failed = onThreads(kWriters, [&](int i) {
    auto db = TaskDatabase::open(uri);
    TaskModelStore(db).write(test::bulkModel("first use " + std::to_string(i), 20, 1));
  });
  EXPECT_TRUE(failed.empty()) << failed.front();
  auto db = TaskDatabase::open(uri, TaskDatabase::Mode::ReadOnly);
  EXPECT_EQ(db.schemaVersion(), kSchemaVersion);
  EXPECT_EQ(TaskModelStore(db).list().size(), static_cast<std::size_t>(kWriters));
}

TEST_F(Postgres, ConcurrentWritersOfOneNameGetDistinctVersions) {
  constexpr int kWriters = 8;
  constexpr int kModelsEach = 3;
  constexpr int kFrames = 40;
  const std::string uri = test::PgCluster::instance().createDatabase("versions");
  TaskDatabase::open(uri);  // schema
  const auto failed = onThreads(kWriters, [&](int) {
    auto db = TaskDatabase::open(uri);
    for (int k = 0; k < kModelsEach; ++k) TaskModelStore(db).write(test::bulkModel("shared name", kFrames, 2));
  });
  EXPECT_TRUE(failed.empty()) << failed.front();
  auto db = TaskDatabase::open(uri, TaskDatabase::Mode::ReadOnly);
  TaskModelStore store(db);
  std::set<int> versions;
  for (const auto& info : store.list()) {
    versions.insert(info.version);
    const TaskModel m = store.read(info.id);  // every model complete
    EXPECT_EQ(m.handPositions.size(), static_cast<std::size_t>(kFrames));
    EXPECT_EQ(m.productPoses.size(), static_cast<std::size_t>(2 * kFrames));
  }
  ASSERT_EQ(versions.size(), static_cast<std::size_t>(kWriters * kModelsEach));
  EXPECT_EQ(*versions.begin(), 1);
  EXPECT_EQ(*versions.rbegin(), kWriters * kModelsEach);
}

TEST_F(Postgres, AReadOnlyConnectionWritesNothing) {
  const std::string uri = test::PgCluster::instance().createDatabase("read_only");
  EXPECT_THROW(TaskDatabase::open(uri, TaskDatabase::Mode::ReadOnly), srp::core::FileError)
      << "a database without the schema is not a task database yet";
  { auto db = TaskDatabase::open(uri); }
  auto db = TaskDatabase::open(uri, TaskDatabase::Mode::ReadOnly);
  EXPECT_THROW(TaskModelStore(db).write(test::bulkModel("refused", 5, 1)), srp::core::Error);
  EXPECT_TRUE(TaskModelStore(db).list().empty());
}

TEST_F(Postgres, CredentialsAreNeverShown) {
  const std::string secret = "s3cr3t-pw";
  const std::string uri = test::PgCluster::instance().createDatabase("credentials");
  // The cluster trusts local connections, so the password is accepted and unused.
  std::string withPassword = uri;
  withPassword.replace(withPassword.find("srp@"), 4, "srp:" + secret + "@");
  auto db = TaskDatabase::open(withPassword);
  EXPECT_EQ(db.path().find(secret), std::string::npos) << db.path();
  EXPECT_EQ(db.path(), uri);
  const int id = TaskModelStore(db).write(test::bulkModel("credentials", 5, 1));
  EXPECT_EQ(toJson(TaskModelStore(db).read(id)).dump().find(secret), std::string::npos);
  EXPECT_EQ(TaskDatabase::displayName("postgresql://u:" + secret + "@h:1/d?password=" + secret + "&x=1").find(secret),
            std::string::npos);
  // A server that is not there: the message names the URI without the password.
  try {
    TaskDatabase::open("postgresql://srp:" + secret + "@127.0.0.1:1/none");
    ADD_FAILURE() << "connected to port 1";
  } catch (const srp::core::FileError& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.find(secret), std::string::npos) << what;
    EXPECT_NE(what.find("postgresql://srp@127.0.0.1:1/none"), std::string::npos) << what;
  }
}
