#pragma once
// The task database schema and its forward migrations (private to taskdb).
#include <string>
#include <vector>

namespace srp::taskdb::detail {

/// kMigrations[i] takes a database from schema version i to i + 1.
const std::vector<std::string>& migrations();

}  // namespace srp::taskdb::detail

namespace srp::taskdb::detail {
/// The PostgreSQL schema: [0] creates the current version on an empty database.
const std::vector<std::string>& postgresMigrations();
}  // namespace srp::taskdb::detail
