#pragma once
/// \file SchemaVersion.h
/// \brief The task database schema version this build reads and writes.

namespace srp::taskdb {

/// The schema version this build reads and writes (`PRAGMA user_version` of an
/// SQLite file, the SrpSchema table on a server). Older versions are migrated
/// forward when opened read-write; newer ones are refused.
inline constexpr int kSchemaVersion = 3;

}  // namespace srp::taskdb
