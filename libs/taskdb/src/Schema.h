#pragma once
// The task database schema (private to taskdb): one description of every
// table (columns with a logical type, keys, the schema version each appeared
// or went away in) that emits the DDL of both SQLite and PostgreSQL, and the
// forward migrations between versions. A new column is added once, to the
// description, with the version it appears in.
#include <string>

namespace srp::taskdb::detail {

enum class Dialect { SQLite, PostgreSQL };

/// SQL that creates schema `version` (1 .. kSchemaVersion) on an empty
/// database: its tables and the version number (PRAGMA user_version on SQLite,
/// table SrpSchema on a server).
std::string createSchemaSql(Dialect dialect, int version);

/// SQL that takes a database from schema version `from` to from + 1, version
/// number included (run inside
/// the opening transaction; on SQLite with foreign keys off, as they are when
/// the connection opens).
std::string migrationSql(Dialect dialect, int from);

}  // namespace srp::taskdb::detail
