// The backend-parameterised suite on SQLite files.
#include "Backends.h"

namespace srp::taskdb::test {
void BackendTest::SetUp() {}
std::string BackendTest::newDatabase(const std::string& name) {
  files_.push_back(std::make_unique<TempDbPath>(name));
  return files_.back()->str();
}
SRP_INSTANTIATE_BACKEND_SUITES(Files, Engine::SQLite);
}  // namespace srp::taskdb::test
