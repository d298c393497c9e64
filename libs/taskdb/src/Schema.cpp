#include "Schema.h"

#include <cctype>
#include <stdexcept>
#include <vector>

#include "srp/taskdb/SchemaVersion.h"

namespace srp::taskdb::detail {

namespace {

/// A column's logical type; each dialect has its own spelling.
enum class Type {
  Id,        ///< the task model's id: INTEGER PRIMARY KEY AUTOINCREMENT / an identity column
  Integer,   ///< INTEGER
  Real,      ///< REAL / DOUBLE PRECISION
  Text,      ///< TEXT
  Json,      ///< TEXT checked with json_valid() / jsonb
  RowOrder,  ///< insertion order: SQLite's rowid (no column) / a BIGINT identity column
};

constexpr int kNever = 1 << 30;

struct Column {
  const char* name;
  Type type;
  /// NOT NULL, DEFAULT, CHECK, REFERENCES: SQL both dialects read alike.
  const char* constraints = "";
  int since = 1;
};

/// PRIMARY KEY (...), UNIQUE (...) or FOREIGN KEY (...) REFERENCES ...,
/// present in versions [since, until).
struct Key {
  std::string sql;
  int since = 1;
  int until = kNever;
};

struct Table {
  const char* name;
  std::vector<Column> columns;
  std::vector<Key> keys;
  int since = 1;
  /// SQLite's WITHOUT ROWID (the bulk tables, keyed by their primary key).
  bool withoutRowid = false;
};

constexpr const char* kTaskModelRef = "NOT NULL REFERENCES TaskModels(TaskModelId) ON DELETE CASCADE";
constexpr const char* kFlag0 = "NOT NULL DEFAULT 0 CHECK (%s IN (0, 1))";
constexpr const char* kDeferred = " DEFERRABLE INITIALLY DEFERRED";

std::string fk(const std::string& columns, const std::string& target) {
  return "FOREIGN KEY (" + columns + ") REFERENCES " + target + kDeferred;
}

// The schema. Version 1: the thesis' seven table types (Appendix C),
// normalised, plus TaskModels and Skills; ids are local to a task model,
// hence the composite keys; the location <-> product references are
// circular, so those foreign keys are deferred to COMMIT. Version 2: several
// instances of one class: GroundedProducts, ProductPose and Skills are keyed
// by (ClassId, InstanceId), Products name the instance they were grounded to
// (InstanceId = the scene's object id, '' = the one instance of a class,
// which is what every version-1 row meant). Version 3: the scene the
// demonstration was perceived in (PerceivedScenes, SceneObjects,
// ObservedClasses; a version-2 task model has none).
// The plan: the task model, its products and their source and target locations (thesis Appendix C).
std::vector<Table> planTables() {
  return {
      {"TaskModels",
       {{"TaskModelId", Type::Id},
        {"Name", Type::Text, "NOT NULL"},
        {"Version", Type::Integer, "NOT NULL DEFAULT 1 CHECK (Version >= 1)"},
        {"CreatedUtc", Type::Text, "NOT NULL"},
        {"Instruction", Type::Text, "NOT NULL DEFAULT ''"},
        {"Frame", Type::Text, "NOT NULL DEFAULT 'camera'"},
        {"Units", Type::Text, "NOT NULL DEFAULT 'm'"},
        {"FrameRate_Hz", Type::Real, "NOT NULL DEFAULT 30 CHECK (FrameRate_Hz > 0)"},
        {"Intrinsics", Type::Json},
        {"X_base_camera", Type::Json}},
       {{"UNIQUE (Name, Version)"}}},
      {"Products",
       {{"TaskModelId", Type::Integer, kTaskModelRef},
        {"ObjectId", Type::Integer, "NOT NULL"},
        {"ObjectName", Type::Text, "NOT NULL"},
        {"SourceLocationId", Type::Integer},
        {"TargetLocationId", Type::Integer},
        {"Color", Type::Text},
        {"TokenId", Type::Integer},
        {"SentenceId", Type::Integer},
        {"ClassId", Type::Integer},
        {"InstanceId", Type::Text, "NOT NULL DEFAULT ''", 2}},
       {{"PRIMARY KEY (TaskModelId, ObjectId)"},
        {fk("TaskModelId, SourceLocationId", "SourceLocations(TaskModelId, LocationId)")},
        {fk("TaskModelId, TargetLocationId", "TargetLocations(TaskModelId, LocationId)")},
        {fk("TaskModelId, ClassId", "GroundedProducts(TaskModelId, ClassId)"), 1, 2},
        {fk("TaskModelId, ClassId, InstanceId", "GroundedProducts(TaskModelId, ClassId, InstanceId)"), 2}}},
      {"SourceLocations",
       {{"TaskModelId", Type::Integer, kTaskModelRef},
        {"LocationId", Type::Integer, "NOT NULL"},
        {"TrajectorObjectId", Type::Integer, "NOT NULL"},
        {"Description", Type::Text, "NOT NULL"}},
       {{"PRIMARY KEY (TaskModelId, LocationId)"},
        {fk("TaskModelId, TrajectorObjectId", "Products(TaskModelId, ObjectId)")}}},
      {"TargetLocations",
       {{"TaskModelId", Type::Integer, kTaskModelRef},
        {"LocationId", Type::Integer, "NOT NULL"},
        {"IndicatorObjectId", Type::Integer, "NOT NULL"},
        {"Description", Type::Text, "NOT NULL"}},
       {{"PRIMARY KEY (TaskModelId, LocationId)"},
        {fk("TaskModelId, IndicatorObjectId", "Products(TaskModelId, ObjectId)")}}},
      {"TaskModelTargetObjects",
       {{"TaskModelId", Type::Integer, kTaskModelRef},
        {"StepIndex", Type::Integer, "NOT NULL"},
        {"TargetObjectId", Type::Integer, "NOT NULL"}},
       {{"PRIMARY KEY (TaskModelId, StepIndex)"},
        {fk("TaskModelId, TargetObjectId", "Products(TaskModelId, ObjectId)")}}},
  };
}

// What the demonstration showed and what was learned from it: grounded products, their poses, the hand, the skills.
std::vector<Table> trajectoryTables() {
  return {
      {"GroundedProducts",
       {{"TaskModelId", Type::Integer, kTaskModelRef},
        {"ClassId", Type::Integer, "NOT NULL"},
        {"InstanceId", Type::Text, "NOT NULL DEFAULT ''", 2},
        {"ObjectName", Type::Text, "NOT NULL"},
        {"SourceLocationId", Type::Integer},
        {"TargetLocationId", Type::Integer},
        {"Color", Type::Text}},
       {{"PRIMARY KEY (TaskModelId, ClassId)", 1, 2},
        {"PRIMARY KEY (TaskModelId, ClassId, InstanceId)", 2},
        {fk("TaskModelId, SourceLocationId", "SourceLocations(TaskModelId, LocationId)")},
        {fk("TaskModelId, TargetLocationId", "TargetLocations(TaskModelId, LocationId)")}}},
      {"ProductPose",
       {{"TaskModelId", Type::Integer, kTaskModelRef},
        {"ClassId", Type::Integer, "NOT NULL"},
        {"InstanceId", Type::Text, "NOT NULL DEFAULT ''", 2},
        {"TimeId", Type::Integer, "NOT NULL"},
        {"X", Type::Real, "NOT NULL"},
        {"Y", Type::Real, "NOT NULL"},
        {"Z", Type::Real, "NOT NULL"},
        {"QW", Type::Real, "NOT NULL"},
        {"QX", Type::Real, "NOT NULL"},
        {"QY", Type::Real, "NOT NULL"},
        {"QZ", Type::Real, "NOT NULL"},
        {"Reach", Type::Integer, kFlag0},
        {"Grasp", Type::Integer, kFlag0},
        {"Move", Type::Integer, kFlag0},
        {"Release", Type::Integer, kFlag0},
        {"Detected", Type::Integer, "NOT NULL DEFAULT 1 CHECK (%s IN (0, 1))"},
        {"Confidence", Type::Real}},
       {{"PRIMARY KEY (TaskModelId, ClassId, TimeId)", 1, 2},
        {"PRIMARY KEY (TaskModelId, ClassId, InstanceId, TimeId)", 2},
        {fk("TaskModelId, ClassId", "GroundedProducts(TaskModelId, ClassId)"), 1, 2},
        {fk("TaskModelId, ClassId, InstanceId", "GroundedProducts(TaskModelId, ClassId, InstanceId)"), 2}},
       1,
       true},
      {"HandPositions",
       {{"TimeId", Type::Integer, "NOT NULL"},
        {"TaskModelId", Type::Integer, kTaskModelRef},
        {"X", Type::Real, "NOT NULL"},
        {"Y", Type::Real, "NOT NULL"},
        {"Z", Type::Real, "NOT NULL"},
        {"Detected", Type::Integer, "NOT NULL DEFAULT 1 CHECK (%s IN (0, 1))"}},
       {{"PRIMARY KEY (TaskModelId, TimeId)"}},
       1,
       true},
      {"Skills",
       {{"TaskModelId", Type::Integer, kTaskModelRef},
        {"ClassId", Type::Integer, "NOT NULL"},
        {"InstanceId", Type::Text, "NOT NULL DEFAULT ''", 2},
        {"Skill", Type::Text, "NOT NULL CHECK (Skill IN ('Reach', 'Grasp', 'Move', 'Release'))"},
        {"StartTimeId", Type::Integer, "NOT NULL"},
        {"EndTimeId", Type::Integer, "NOT NULL CHECK (EndTimeId >= StartTimeId)"},
        {"Parameters", Type::Json, "NOT NULL DEFAULT '{}'"}},
       {{"PRIMARY KEY (TaskModelId, ClassId, Skill)", 1, 2},
        {"PRIMARY KEY (TaskModelId, ClassId, InstanceId, Skill)", 2},
        {fk("TaskModelId, ClassId", "GroundedProducts(TaskModelId, ClassId)"), 1, 2},
        {fk("TaskModelId, ClassId, InstanceId", "GroundedProducts(TaskModelId, ClassId, InstanceId)"), 2}}},
  };
}

// The scene the demonstration was perceived in (version 3).
std::vector<Table> sceneTables() {
  return {
      {"PerceivedScenes",
       {{"TaskModelId", Type::Integer, "PRIMARY KEY REFERENCES TaskModels(TaskModelId) ON DELETE CASCADE"},
        {"Catalogue", Type::Text, "NOT NULL"},
        {"TableSizeX_m", Type::Real, "NOT NULL CHECK (TableSizeX_m > 0)"},
        {"TableSizeY_m", Type::Real, "NOT NULL CHECK (TableSizeY_m > 0)"},
        {"CameraX", Type::Real, "NOT NULL"},
        {"CameraY", Type::Real, "NOT NULL"},
        {"CameraZ", Type::Real, "NOT NULL"},
        {"CameraQW", Type::Real, "NOT NULL"},
        {"CameraQX", Type::Real, "NOT NULL"},
        {"CameraQY", Type::Real, "NOT NULL"},
        {"CameraQZ", Type::Real, "NOT NULL"}},
       {},
       3},
      {"SceneObjects",
       {{"TaskModelId", Type::Integer, "NOT NULL REFERENCES PerceivedScenes(TaskModelId) ON DELETE CASCADE"},
        {"ObjectId", Type::Text, "NOT NULL"},
        {"ClassId", Type::Integer, "NOT NULL"},
        {"ClassName", Type::Text, "NOT NULL"},
        {"X", Type::Real, "NOT NULL"},
        {"Y", Type::Real, "NOT NULL"},
        {"Z", Type::Real, "NOT NULL"},
        {"QW", Type::Real, "NOT NULL"},
        {"QX", Type::Real, "NOT NULL"},
        {"QY", Type::Real, "NOT NULL"},
        {"QZ", Type::Real, "NOT NULL"},
        {"Color", Type::Text},
        {"R", Type::Real},
        {"G", Type::Real},
        {"B", Type::Real},
        {"Seq", Type::RowOrder}},
       {{"PRIMARY KEY (TaskModelId, ObjectId)"}},
       3},
      {"ObservedClasses",
       {{"TaskModelId", Type::Integer, kTaskModelRef},
        {"ClassId", Type::Integer, "NOT NULL"},
        {"Name", Type::Text, "NOT NULL"},
        {"Definition", Type::Json, "NOT NULL"}},
       {{"PRIMARY KEY (TaskModelId, ClassId)"}, {"UNIQUE (TaskModelId, Name)"}},
       3},
  };
}

const std::vector<Table>& tables() {
  static const std::vector<Table> t = [] {
    std::vector<Table> all = planTables();
    for (auto&& group : {trajectoryTables(), sceneTables()}) all.insert(all.end(), group.begin(), group.end());
    return all;
  }();
  return t;
}

bool inVersion(const Column& c, int v) { return c.since <= v; }
bool inVersion(const Key& k, int v) { return k.since <= v && v < k.until; }
bool isForeignKey(const Key& k) { return k.sql.rfind("FOREIGN KEY", 0) == 0; }

// "NOT NULL DEFAULT 0 CHECK (%s IN (0, 1))" with the column's name.
std::string constraintsOf(const Column& c) {
  std::string s = c.constraints;
  for (auto p = s.find("%s"); p != std::string::npos; p = s.find("%s", p)) s.replace(p, 2, c.name);
  return s;
}

// The column's definition, or "" when the dialect has no column for it.
std::string columnSql(const Column& c, Dialect d) {
  const bool pg = d == Dialect::PostgreSQL;
  std::string type;
  std::string extra = constraintsOf(c);
  switch (c.type) {
    case Type::Id:
      type = pg ? "INTEGER GENERATED BY DEFAULT AS IDENTITY PRIMARY KEY" : "INTEGER PRIMARY KEY AUTOINCREMENT";
      break;
    case Type::Integer: type = "INTEGER"; break;
    case Type::Real: type = pg ? "DOUBLE PRECISION" : "REAL"; break;
    case Type::Text: type = "TEXT"; break;
    case Type::Json:
      type = pg ? "JSONB" : "TEXT";
      if (!pg) {
        const std::string name = c.name;
        const bool notNull = extra.find("NOT NULL") != std::string::npos;
        extra += (extra.empty() ? "CHECK (" : " CHECK (") + (notNull ? "" : name + " IS NULL OR ") + "json_valid(" +
                 name + "))";
      }
      break;
    case Type::RowOrder:
      if (!pg) return "";
      type = "BIGINT GENERATED ALWAYS AS IDENTITY";
      break;
  }
  return std::string(c.name) + " " + type + (extra.empty() ? "" : " " + extra);
}

// CREATE TABLE `name` as of `version`. On a server the table's foreign keys
// come later (ALTER TABLE: the tables reference each other in a circle).
std::string createTableSql(const Table& t, Dialect d, int version, const std::string& name) {
  std::string sql = "CREATE TABLE " + name + " (\n";
  bool first = true;
  auto add = [&](const std::string& line) {
    if (line.empty()) return;
    sql += (first ? "  " : ",\n  ") + line;
    first = false;
  };
  for (const auto& c : t.columns)
    if (inVersion(c, version)) add(columnSql(c, d));
  for (const auto& k : t.keys)
    if (inVersion(k, version) && !(d == Dialect::PostgreSQL && isForeignKey(k))) add(k.sql);
  sql += "\n)";
  if (t.withoutRowid && d == Dialect::SQLite) sql += " WITHOUT ROWID";
  return sql + ";\n";
}

std::string addForeignKeysSql(const Table& t, int version, bool onlyNew) {
  std::string sql;
  for (const auto& k : t.keys)
    if (isForeignKey(k) && inVersion(k, version) && (!onlyNew || !inVersion(k, version - 1)))
      sql += "ALTER TABLE " + std::string(t.name) + " ADD " + k.sql + ";\n";
  return sql;
}

// PostgreSQL's name of an unnamed key: table_pkey, table_col1_col2_key,
// table_col1_col2_fkey (lower case; the schema's names stay far below 63 bytes).
std::string serverKeyName(const Table& t, const Key& k) {
  auto lower = [](std::string s) {
    for (auto& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return s;
  };
  const std::string table = lower(t.name);
  if (k.sql.rfind("PRIMARY KEY", 0) == 0) return table + "_pkey";
  const auto open = k.sql.find('('), close = k.sql.find(')');
  std::string columns;
  for (const char c : k.sql.substr(open + 1, close - open - 1))
    if (c != ' ') columns += c == ',' ? '_' : c;
  return table + "_" + lower(columns) + (isForeignKey(k) ? "_fkey" : "_key");
}

bool changes(const Table& t, int to) {
  for (const auto& c : t.columns)
    if (c.since == to) return true;
  for (const auto& k : t.keys)
    if (k.since == to || k.until == to) return true;
  return false;
}

std::string columnList(const Table& t, int version, Dialect d) {
  std::string s;
  for (const auto& c : t.columns)
    if (inVersion(c, version) && !columnSql(c, d).empty()) s += (s.empty() ? "" : ", ") + std::string(c.name);
  return s;
}

// SQLite cannot change a primary key in place: a changed table is rebuilt
// (create, copy, drop, rename; new columns take their DEFAULT).
std::string sqliteMigration(int from) {
  const int to = from + 1;
  std::string create, drop, rename;
  for (const auto& t : tables()) {
    if (t.since == to) {
      create += createTableSql(t, Dialect::SQLite, to, t.name);
    } else if (t.since <= from && changes(t, to)) {
      const std::string rebuilt = std::string(t.name) + "_v" + std::to_string(to);
      const std::string columns = columnList(t, from, Dialect::SQLite);
      create += createTableSql(t, Dialect::SQLite, to, rebuilt);
      create += "INSERT INTO " + rebuilt + " (" + columns + ") SELECT " + columns + " FROM " + t.name + ";\n";
      drop += "DROP TABLE " + std::string(t.name) + ";\n";
      rename += "ALTER TABLE " + rebuilt + " RENAME TO " + t.name + ";\n";
    }
  }
  return create + drop + rename + "PRAGMA user_version = " + std::to_string(to) + ";\n";
}

// A server changes tables in place: keys that go away are dropped (foreign
// keys first), columns added, new tables created, new keys added (foreign
// keys last).
std::string serverMigration(int from) {
  const int to = from + 1;
  std::string dropForeign, dropOther, addColumns, create, addOther, addForeign;
  for (const auto& t : tables()) {
    if (t.since == to) {
      create += createTableSql(t, Dialect::PostgreSQL, to, t.name);
      addForeign += addForeignKeysSql(t, to, false);
      continue;
    }
    if (t.since > from) continue;
    const std::string alter = "ALTER TABLE " + std::string(t.name);
    for (const auto& k : t.keys) {
      if (k.until == to)
        (isForeignKey(k) ? dropForeign : dropOther) += alter + " DROP CONSTRAINT " + serverKeyName(t, k) + ";\n";
      if (k.since == to && !isForeignKey(k)) addOther += alter + " ADD " + k.sql + ";\n";
    }
    for (const auto& c : t.columns)
      if (c.since == to) addColumns += alter + " ADD COLUMN " + columnSql(c, Dialect::PostgreSQL) + ";\n";
    addForeign += addForeignKeysSql(t, to, true);
  }
  return dropForeign + dropOther + addColumns + create + addOther + addForeign +
         "UPDATE SrpSchema SET Version = " + std::to_string(to) + ";\n";
}

void checkVersion(int version, int lowest) {
  if (version < lowest || version > kSchemaVersion)
    throw std::logic_error("task database schema version " + std::to_string(version) + " is not in [" +
                           std::to_string(lowest) + ", " + std::to_string(kSchemaVersion) + "]");
}

}  // namespace

std::string createSchemaSql(Dialect dialect, int version) {
  checkVersion(version, 1);
  std::string sql, foreign;
  for (const auto& t : tables()) {
    if (t.since > version) continue;
    sql += createTableSql(t, dialect, version, t.name);
    if (dialect == Dialect::PostgreSQL) foreign += addForeignKeysSql(t, version, false);
  }
  if (dialect == Dialect::SQLite) return sql + "PRAGMA user_version = " + std::to_string(version) + ";\n";
  return "CREATE TABLE SrpSchema (Version INTEGER NOT NULL);\n" + sql + foreign +
         "INSERT INTO SrpSchema (Version) VALUES (" + std::to_string(version) + ");\n";
}

std::string migrationSql(Dialect dialect, int from) {
  checkVersion(from + 1, 2);
  return dialect == Dialect::SQLite ? sqliteMigration(from) : serverMigration(from);
}

}  // namespace srp::taskdb::detail
