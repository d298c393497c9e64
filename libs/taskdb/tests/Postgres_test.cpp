// Server-only behaviour of the PostgreSQL backend: concurrent first use,
// migration of older schema versions, race-free versioning under concurrent
// writers, read-only connections, credentials never shown.
#include <gtest/gtest.h>

#include <SQLiteCpp/SQLiteCpp.h>
#include <sqlite3.h>

#include <cstdio>
#include <optional>
#include <set>
#include <thread>

#include "MigrationFixture.h"
#include "PgCluster.h"
#include "Schema.h"
#include "TestDb.h"
#include "srp/core/Error.h"
#include "srp/core/Json.h"
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

// Every row of every table of an SQLite task database, as text (doubles with
// 17 digits, so a last-bit difference shows).
std::string dumpFile(const std::string& path) {
  SQLite::Database db(path, SQLite::OPEN_READONLY);
  std::string out;
  for (const char* table : {"TaskModels", "Products", "SourceLocations", "TargetLocations", "TaskModelTargetObjects",
                            "GroundedProducts", "ProductPose", "HandPositions", "Skills", "PerceivedScenes",
                            "SceneObjects", "ObservedClasses"}) {
    SQLite::Statement st(db, std::string("SELECT * FROM ") + table + " ORDER BY 1, 2");
    out += table;
    int rows = 0;
    while (st.executeStep()) {
      ++rows;
      out += "\n";
      for (int c = 0; c < st.getColumnCount(); ++c) {
        const SQLite::Column col = st.getColumn(c);
        if (col.getType() == SQLITE_FLOAT) {
          char buf[32];
          std::snprintf(buf, sizeof buf, "%.17g", col.getDouble());
          out += std::string("|") + buf;
        } else {
          out += "|" + (col.isNull() ? std::string("NULL") : col.getString());
        }
      }
    }
    out += "\n" + std::to_string(rows) + " rows\n";
  }
  return out;
}

// A server database at schema `version` (the tables that version had) holding
// every row of the SQLite file `fixture` of that version.
std::string serverDatabaseAtVersion(int version, const std::string& fixture, const std::string& name) {
  const std::string uri = test::PgCluster::instance().createDatabase(name);
  pqxx::connection c(uri);
  pqxx::work w(c);
  w.exec(detail::createSchemaSql(detail::Dialect::PostgreSQL, version));
  SQLite::Database file(fixture, SQLite::OPEN_READONLY);
  SQLite::Statement tables(file, "SELECT name FROM sqlite_master WHERE type = 'table' AND name NOT LIKE 'sqlite_%' "
                                 "ORDER BY name != 'TaskModels', rowid");
  while (tables.executeStep()) {
    const std::string table = tables.getColumn(0).getString();
    SQLite::Statement rows(file, "SELECT * FROM " + table);
    while (rows.executeStep()) {
      std::string columns, placeholders;
      std::vector<std::optional<std::string>> texts;
      for (int i = 0; i < rows.getColumnCount(); ++i) {
        const SQLite::Column col = rows.getColumn(i);
        columns += (i ? ", " : "") + std::string(col.getName());
        placeholders += (i ? ", $" : "$") + std::to_string(i + 1);
        char buf[32];
        std::snprintf(buf, sizeof buf, "%.17g", col.getDouble());
        if (col.isNull()) texts.emplace_back();
        else texts.emplace_back(col.getType() == SQLITE_FLOAT ? std::string(buf) : col.getString());
      }
      std::vector<const char*> values;
      for (const auto& t : texts) values.push_back(t ? t->c_str() : nullptr);
      w.exec_params("INSERT INTO " + table + " (" + columns + ") VALUES (" + placeholders + ")",
                    pqxx::prepare::make_dynamic_params(values));
    }
  }
  w.exec("SELECT setval(pg_get_serial_sequence('taskmodels', 'taskmodelid'), (SELECT MAX(TaskModelId) FROM TaskModels))");
  w.commit();
  return uri;
}

}  // namespace

// A server database at schema 1 or 2 (what srp wrote before instance ids and
// before the perceived scene) is migrated by the first program that opens it
// read-write, in one transaction under the advisory lock: four programs
// opening it at once all find the current version, every row is kept, and it
// then stores two instances of one class with a perceived scene. Read-only
// opening refuses it, saying how to migrate.
TEST_F(Postgres, AnOlderSchemaIsMigratedOnceWithEveryRow) {
  for (const auto& [version, fixture] : {std::pair<int, std::string>{1, test::kFixture}, {2, test::kFixtureV2}}) {
    SCOPED_TRACE("schema " + std::to_string(version));
    const std::string uri = serverDatabaseAtVersion(version, fixture, "migrate_v" + std::to_string(version));
    EXPECT_THROW(TaskDatabase::open(uri, TaskDatabase::Mode::ReadOnly), srp::core::FileError);
    const auto failed = onThreads(4, [&](int) {
      auto db = TaskDatabase::open(uri);
      if (db.schemaVersion() != kSchemaVersion) throw std::runtime_error("not migrated");
    });
    EXPECT_TRUE(failed.empty()) << failed.front();
    auto db = TaskDatabase::open(uri);
    const TaskModel read = TaskModelStore(db).read(1);
    test::expectEveryRowOfTheFixture(read);
    EXPECT_FALSE(read.scene.has_value());

    TaskModel two = test::twoCuboidsModel();
    two.scene = PerceivedScene{};
    two.scene->catalogue = "catalogue.json";
    two.scene->objects.push_back({"cuboid_red", 3, "cuboid", srp::core::Pose3::Identity(), std::nullopt, std::nullopt});
    const int id = TaskModelStore(db).write(two);
    EXPECT_EQ(id, 2);
    const TaskModel back = TaskModelStore(db).read(id);
    EXPECT_EQ(back.groundedProducts.size(), 2u);
    EXPECT_EQ(back.productPoses.size(), 2u);
    ASSERT_TRUE(back.scene.has_value());
    EXPECT_EQ(back.scene->objects.size(), 1u);
  }
}

// srp db import --from: SQLite -> PostgreSQL -> SQLite keeps every row of
// every table (the bundled Appendix C task model, a bulk model with skills, a
// model with a perceived scene). The bulk model's 3300 poses and 1100 hand
// rows reach the server as multi-row INSERTs of 1000, 1000, 1000 and 300
// rows (and 1000 + 100): every batch size and boundary is in the comparison.
TEST_F(Postgres, ImportRoundTripKeepsEveryRow) {
  test::TempDbPath original("roundtrip_original"), back("roundtrip_back");
  {
    auto db = TaskDatabase::open(original.str());
    TaskModelStore store(db);
    store.write(taskModelFromJson(srp::core::readJsonFile(std::string(SRP_DATASETS_DIR) +
                                                          "/examples/appendix_c_instruction1.json"),
                                  "appendix_c_instruction1.json"));
    TaskModel bulk = test::bulkModel("bulk", 1100, 3);
    bulk.info.intrinsics = srp::core::CameraIntrinsics{607.178, 607.234, 321.391, 241.918, 640, 480};
    bulk.info.X_base_camera = srp::core::makePoseYPR({0.1, -0.5, 0.9}, 0.3, 0.0, M_PI);
    bulk.skills = {{1, srp::core::SkillType::Reach, 0, 95, {{"weights", {0.1, 1.0 / 3.0, -2.718281828459045e-7}}}},
                   {1, srp::core::SkillType::Grasp, 96, 96, {}}};
    store.write(bulk);
    store.write(test::bulkModel("bulk", 10, 1));  // version 2
    TaskModel scene = test::bulkModel("scene", 5, 1);
    PerceivedScene s;
    s.catalogue = "datasets/kb/catalogue.json";
    s.tableSize_m = {1.2, 0.8};
    s.X_table_camera = srp::core::makePoseYPR({0.1, -0.2, 0.9}, 0.2, 0.1, M_PI / 3);
    s.objects = {{"cuboid_red", 3, "cuboid", srp::core::makePoseYPR({0.1, 0.05, 0.02}, 0.4, 0.0, 0.0), "red",
                  Eigen::Vector3d(0.8, 0.1, 1.0 / 7.0)},
                 {"box", 1, "box", srp::core::makePoseYPR({-0.2, 0.1, 0.0}, -1.0, 0.0, 0.0), {}, {}}};
    scene.scene = s;
    store.write(scene);
  }
  const std::string server = test::PgCluster::instance().createDatabase("roundtrip");
  {
    auto from = TaskDatabase::open(original.str(), TaskDatabase::Mode::ReadOnly);
    auto to = TaskDatabase::open(server);
    EXPECT_EQ(copyTaskModels(from, to).size(), 4u);
    // Copying again would duplicate names and versions: refused, nothing changes.
    EXPECT_THROW(copyTaskModels(from, to), srp::core::InvalidInputError);
    EXPECT_EQ(TaskModelStore(to).list().size(), 4u);
  }
  {
    auto from = TaskDatabase::open(server, TaskDatabase::Mode::ReadOnly);
    auto to = TaskDatabase::open(back.str());
    EXPECT_EQ(copyTaskModels(from, to).size(), 4u);
  }
  const std::string before = dumpFile(original.str()), after = dumpFile(back.str());
  EXPECT_EQ(before, after);
  EXPECT_NE(before.find("TaskModels\n|1|appendix-c"), std::string::npos) << before.substr(0, 200);
  EXPECT_NE(before.find("\n4 rows\n"), std::string::npos) << "the four task models are in the dump";
}

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
