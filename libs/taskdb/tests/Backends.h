#pragma once
// The DAO suite runs on both backends: TEST_P(BackendTest, ...) gets a fresh,
// empty task database from newDatabase(); srp_taskdb_tests instantiates it on
// SQLite files, srp_taskdb_postgres_tests on a throw-away PostgreSQL cluster.
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "TestDb.h"

namespace srp::taskdb::test {

enum class Engine { SQLite, PostgreSQL };

inline std::string engineName(const ::testing::TestParamInfo<Engine>& info) {
  return info.param == Engine::SQLite ? "SQLite" : "PostgreSQL";
}

/// Base of the tests that run on both backends.
class BackendTest : public ::testing::TestWithParam<Engine> {
 protected:
  void SetUp() override;
  /// A new, empty task database (a file path or a server URI).
  std::string newDatabase(const std::string& name);

 private:
  std::vector<std::unique_ptr<TempDbPath>> files_;
};

/// The suites run on both backends (instantiated in SqliteBackend_test.cpp / PostgresBackend_test.cpp).
class Daos : public BackendTest {};
class AppendixC : public BackendTest {};
class PerceivedSceneStore : public BackendTest {};

#define SRP_INSTANTIATE_BACKEND_SUITES(prefix, engine)                                        \
  INSTANTIATE_TEST_SUITE_P(prefix, Daos, ::testing::Values(engine), engineName);              \
  INSTANTIATE_TEST_SUITE_P(prefix, AppendixC, ::testing::Values(engine), engineName);         \
  INSTANTIATE_TEST_SUITE_P(prefix, PerceivedSceneStore, ::testing::Values(engine), engineName)

}  // namespace srp::taskdb::test
