// The backend-parameterised suite on a throw-away PostgreSQL cluster.
#include "Backends.h"
#include "PgCluster.h"

namespace srp::taskdb::test {
void BackendTest::SetUp() {
  auto& cluster = PgCluster::instance();
  if (cluster.noBinary()) GTEST_SKIP() << cluster.problem();
  ASSERT_TRUE(cluster.available()) << cluster.problem();
}
std::string BackendTest::newDatabase(const std::string& name) { return PgCluster::instance().createDatabase(name); }
SRP_INSTANTIATE_BACKEND_SUITES(Server, Engine::PostgreSQL);
}  // namespace srp::taskdb::test
