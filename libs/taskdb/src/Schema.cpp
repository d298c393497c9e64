#include "Schema.h"

namespace srp::taskdb::detail {

// Version 1: the thesis' seven table types (Appendix C), normalised, plus
// TaskModels and Skills. Ids are local to a task model, hence the composite
// keys. The location <-> product references are circular, so those foreign
// keys are deferred to the end of the writing transaction.
static const char* kSchemaV1 = R"SQL(
CREATE TABLE TaskModels (
  TaskModelId   INTEGER PRIMARY KEY AUTOINCREMENT,
  Name          TEXT    NOT NULL,
  Version       INTEGER NOT NULL DEFAULT 1 CHECK (Version >= 1),
  CreatedUtc    TEXT    NOT NULL,
  Instruction   TEXT    NOT NULL DEFAULT '',
  Frame         TEXT    NOT NULL DEFAULT 'camera',
  Units         TEXT    NOT NULL DEFAULT 'm',
  FrameRate_Hz  REAL    NOT NULL DEFAULT 30 CHECK (FrameRate_Hz > 0),
  Intrinsics    TEXT    CHECK (Intrinsics IS NULL OR json_valid(Intrinsics)),
  X_base_camera TEXT    CHECK (X_base_camera IS NULL OR json_valid(X_base_camera)),
  UNIQUE (Name, Version)
);
CREATE TABLE Products (
  TaskModelId      INTEGER NOT NULL REFERENCES TaskModels(TaskModelId) ON DELETE CASCADE,
  ObjectId         INTEGER NOT NULL,
  ObjectName       TEXT    NOT NULL,
  SourceLocationId INTEGER,
  TargetLocationId INTEGER,
  Color            TEXT,
  TokenId          INTEGER,
  SentenceId       INTEGER,
  ClassId          INTEGER,
  PRIMARY KEY (TaskModelId, ObjectId),
  FOREIGN KEY (TaskModelId, SourceLocationId) REFERENCES SourceLocations(TaskModelId, LocationId) DEFERRABLE INITIALLY DEFERRED,
  FOREIGN KEY (TaskModelId, TargetLocationId) REFERENCES TargetLocations(TaskModelId, LocationId) DEFERRABLE INITIALLY DEFERRED,
  FOREIGN KEY (TaskModelId, ClassId) REFERENCES GroundedProducts(TaskModelId, ClassId) DEFERRABLE INITIALLY DEFERRED
);
CREATE TABLE SourceLocations (
  TaskModelId       INTEGER NOT NULL REFERENCES TaskModels(TaskModelId) ON DELETE CASCADE,
  LocationId        INTEGER NOT NULL,
  TrajectorObjectId INTEGER NOT NULL,
  Description       TEXT    NOT NULL,
  PRIMARY KEY (TaskModelId, LocationId),
  FOREIGN KEY (TaskModelId, TrajectorObjectId) REFERENCES Products(TaskModelId, ObjectId) DEFERRABLE INITIALLY DEFERRED
);
CREATE TABLE TargetLocations (
  TaskModelId       INTEGER NOT NULL REFERENCES TaskModels(TaskModelId) ON DELETE CASCADE,
  LocationId        INTEGER NOT NULL,
  IndicatorObjectId INTEGER NOT NULL,
  Description       TEXT    NOT NULL,
  PRIMARY KEY (TaskModelId, LocationId),
  FOREIGN KEY (TaskModelId, IndicatorObjectId) REFERENCES Products(TaskModelId, ObjectId) DEFERRABLE INITIALLY DEFERRED
);
CREATE TABLE TaskModelTargetObjects (
  TaskModelId    INTEGER NOT NULL REFERENCES TaskModels(TaskModelId) ON DELETE CASCADE,
  StepIndex      INTEGER NOT NULL,
  TargetObjectId INTEGER NOT NULL,
  PRIMARY KEY (TaskModelId, StepIndex),
  FOREIGN KEY (TaskModelId, TargetObjectId) REFERENCES Products(TaskModelId, ObjectId) DEFERRABLE INITIALLY DEFERRED
);
CREATE TABLE GroundedProducts (
  TaskModelId      INTEGER NOT NULL REFERENCES TaskModels(TaskModelId) ON DELETE CASCADE,
  ClassId          INTEGER NOT NULL,
  ObjectName       TEXT    NOT NULL,
  SourceLocationId INTEGER,
  TargetLocationId INTEGER,
  Color            TEXT,
  PRIMARY KEY (TaskModelId, ClassId),
  FOREIGN KEY (TaskModelId, SourceLocationId) REFERENCES SourceLocations(TaskModelId, LocationId) DEFERRABLE INITIALLY DEFERRED,
  FOREIGN KEY (TaskModelId, TargetLocationId) REFERENCES TargetLocations(TaskModelId, LocationId) DEFERRABLE INITIALLY DEFERRED
);
CREATE TABLE ProductPose (
  TaskModelId INTEGER NOT NULL REFERENCES TaskModels(TaskModelId) ON DELETE CASCADE,
  ClassId     INTEGER NOT NULL,
  TimeId      INTEGER NOT NULL,
  X REAL NOT NULL, Y REAL NOT NULL, Z REAL NOT NULL,
  QW REAL NOT NULL, QX REAL NOT NULL, QY REAL NOT NULL, QZ REAL NOT NULL,
  Reach   INTEGER NOT NULL DEFAULT 0 CHECK (Reach IN (0, 1)),
  Grasp   INTEGER NOT NULL DEFAULT 0 CHECK (Grasp IN (0, 1)),
  Move    INTEGER NOT NULL DEFAULT 0 CHECK (Move IN (0, 1)),
  Release INTEGER NOT NULL DEFAULT 0 CHECK (Release IN (0, 1)),
  Detected   INTEGER NOT NULL DEFAULT 1 CHECK (Detected IN (0, 1)),
  Confidence REAL,
  PRIMARY KEY (TaskModelId, ClassId, TimeId),
  FOREIGN KEY (TaskModelId, ClassId) REFERENCES GroundedProducts(TaskModelId, ClassId) DEFERRABLE INITIALLY DEFERRED
) WITHOUT ROWID;
CREATE TABLE HandPositions (
  TimeId      INTEGER NOT NULL,
  TaskModelId INTEGER NOT NULL REFERENCES TaskModels(TaskModelId) ON DELETE CASCADE,
  X REAL NOT NULL, Y REAL NOT NULL, Z REAL NOT NULL,
  Detected INTEGER NOT NULL DEFAULT 1 CHECK (Detected IN (0, 1)),
  PRIMARY KEY (TaskModelId, TimeId)
) WITHOUT ROWID;
CREATE TABLE Skills (
  TaskModelId INTEGER NOT NULL REFERENCES TaskModels(TaskModelId) ON DELETE CASCADE,
  ClassId     INTEGER NOT NULL,
  Skill       TEXT    NOT NULL CHECK (Skill IN ('Reach', 'Grasp', 'Move', 'Release')),
  StartTimeId INTEGER NOT NULL,
  EndTimeId   INTEGER NOT NULL CHECK (EndTimeId >= StartTimeId),
  Parameters  TEXT    NOT NULL DEFAULT '{}' CHECK (json_valid(Parameters)),
  PRIMARY KEY (TaskModelId, ClassId, Skill),
  FOREIGN KEY (TaskModelId, ClassId) REFERENCES GroundedProducts(TaskModelId, ClassId) DEFERRABLE INITIALLY DEFERRED
);
)SQL";

// Version 2: several instances of one class (issue 19). GroundedProducts,
// ProductPose and Skills are keyed by (ClassId, InstanceId) instead of ClassId
// alone; Products name the instance they were grounded to (and are rebuilt
// too: their foreign key to GroundedProducts gains the InstanceId). InstanceId is the
// scene's object id ("cuboid_red"); '' is the one instance of a class, which
// is what every version-1 row meant. SQLite cannot change a primary key in
// place, so the three tables are rebuilt (create, copy, drop, rename; the
// migration runs with foreign keys off, inside the opening transaction).
static const char* kSchemaV2 = R"SQL(
CREATE TABLE Products_v2 (
  TaskModelId      INTEGER NOT NULL REFERENCES TaskModels(TaskModelId) ON DELETE CASCADE,
  ObjectId         INTEGER NOT NULL,
  ObjectName       TEXT    NOT NULL,
  SourceLocationId INTEGER,
  TargetLocationId INTEGER,
  Color            TEXT,
  TokenId          INTEGER,
  SentenceId       INTEGER,
  ClassId          INTEGER,
  InstanceId       TEXT    NOT NULL DEFAULT '',
  PRIMARY KEY (TaskModelId, ObjectId),
  FOREIGN KEY (TaskModelId, SourceLocationId) REFERENCES SourceLocations(TaskModelId, LocationId) DEFERRABLE INITIALLY DEFERRED,
  FOREIGN KEY (TaskModelId, TargetLocationId) REFERENCES TargetLocations(TaskModelId, LocationId) DEFERRABLE INITIALLY DEFERRED,
  FOREIGN KEY (TaskModelId, ClassId, InstanceId) REFERENCES GroundedProducts(TaskModelId, ClassId, InstanceId) DEFERRABLE INITIALLY DEFERRED
);
INSERT INTO Products_v2 (TaskModelId, ObjectId, ObjectName, SourceLocationId, TargetLocationId, Color, TokenId, SentenceId, ClassId, InstanceId)
  SELECT TaskModelId, ObjectId, ObjectName, SourceLocationId, TargetLocationId, Color, TokenId, SentenceId, ClassId, '' FROM Products;
CREATE TABLE GroundedProducts_v2 (
  TaskModelId      INTEGER NOT NULL REFERENCES TaskModels(TaskModelId) ON DELETE CASCADE,
  ClassId          INTEGER NOT NULL,
  InstanceId       TEXT    NOT NULL DEFAULT '',
  ObjectName       TEXT    NOT NULL,
  SourceLocationId INTEGER,
  TargetLocationId INTEGER,
  Color            TEXT,
  PRIMARY KEY (TaskModelId, ClassId, InstanceId),
  FOREIGN KEY (TaskModelId, SourceLocationId) REFERENCES SourceLocations(TaskModelId, LocationId) DEFERRABLE INITIALLY DEFERRED,
  FOREIGN KEY (TaskModelId, TargetLocationId) REFERENCES TargetLocations(TaskModelId, LocationId) DEFERRABLE INITIALLY DEFERRED
);
INSERT INTO GroundedProducts_v2 (TaskModelId, ClassId, InstanceId, ObjectName, SourceLocationId, TargetLocationId, Color)
  SELECT TaskModelId, ClassId, '', ObjectName, SourceLocationId, TargetLocationId, Color FROM GroundedProducts;
CREATE TABLE ProductPose_v2 (
  TaskModelId INTEGER NOT NULL REFERENCES TaskModels(TaskModelId) ON DELETE CASCADE,
  ClassId     INTEGER NOT NULL,
  InstanceId  TEXT    NOT NULL DEFAULT '',
  TimeId      INTEGER NOT NULL,
  X REAL NOT NULL, Y REAL NOT NULL, Z REAL NOT NULL,
  QW REAL NOT NULL, QX REAL NOT NULL, QY REAL NOT NULL, QZ REAL NOT NULL,
  Reach   INTEGER NOT NULL DEFAULT 0 CHECK (Reach IN (0, 1)),
  Grasp   INTEGER NOT NULL DEFAULT 0 CHECK (Grasp IN (0, 1)),
  Move    INTEGER NOT NULL DEFAULT 0 CHECK (Move IN (0, 1)),
  Release INTEGER NOT NULL DEFAULT 0 CHECK (Release IN (0, 1)),
  Detected   INTEGER NOT NULL DEFAULT 1 CHECK (Detected IN (0, 1)),
  Confidence REAL,
  PRIMARY KEY (TaskModelId, ClassId, InstanceId, TimeId),
  FOREIGN KEY (TaskModelId, ClassId, InstanceId) REFERENCES GroundedProducts(TaskModelId, ClassId, InstanceId) DEFERRABLE INITIALLY DEFERRED
) WITHOUT ROWID;
INSERT INTO ProductPose_v2 (TaskModelId, ClassId, InstanceId, TimeId, X, Y, Z, QW, QX, QY, QZ, Reach, Grasp, Move, Release, Detected, Confidence)
  SELECT TaskModelId, ClassId, '', TimeId, X, Y, Z, QW, QX, QY, QZ, Reach, Grasp, Move, Release, Detected, Confidence FROM ProductPose;
CREATE TABLE Skills_v2 (
  TaskModelId INTEGER NOT NULL REFERENCES TaskModels(TaskModelId) ON DELETE CASCADE,
  ClassId     INTEGER NOT NULL,
  InstanceId  TEXT    NOT NULL DEFAULT '',
  Skill       TEXT    NOT NULL CHECK (Skill IN ('Reach', 'Grasp', 'Move', 'Release')),
  StartTimeId INTEGER NOT NULL,
  EndTimeId   INTEGER NOT NULL CHECK (EndTimeId >= StartTimeId),
  Parameters  TEXT    NOT NULL DEFAULT '{}' CHECK (json_valid(Parameters)),
  PRIMARY KEY (TaskModelId, ClassId, InstanceId, Skill),
  FOREIGN KEY (TaskModelId, ClassId, InstanceId) REFERENCES GroundedProducts(TaskModelId, ClassId, InstanceId) DEFERRABLE INITIALLY DEFERRED
);
INSERT INTO Skills_v2 (TaskModelId, ClassId, InstanceId, Skill, StartTimeId, EndTimeId, Parameters)
  SELECT TaskModelId, ClassId, '', Skill, StartTimeId, EndTimeId, Parameters FROM Skills;
DROP TABLE Skills;
DROP TABLE ProductPose;
DROP TABLE Products;
DROP TABLE GroundedProducts;
ALTER TABLE GroundedProducts_v2 RENAME TO GroundedProducts;
ALTER TABLE Products_v2 RENAME TO Products;
ALTER TABLE ProductPose_v2 RENAME TO ProductPose;
ALTER TABLE Skills_v2 RENAME TO Skills;
)SQL";

// Version 3: the scene the demonstration was perceived in, so a task runs in
// the scene of its own demonstration: PerceivedScenes (one row per task model:
// the table rectangle, the camera in the table frame, the knowledge base the
// classes are named in), SceneObjects (each object where it stood when the
// demonstration began, table frame) and ObservedClasses (the full definition of
// a class seen without a CAD file, core::objectClassToJson). New tables only:
// every version-2 task model simply has no perceived scene.
static const char* kSchemaV3 = R"SQL(
CREATE TABLE PerceivedScenes (
  TaskModelId  INTEGER PRIMARY KEY REFERENCES TaskModels(TaskModelId) ON DELETE CASCADE,
  Catalogue    TEXT    NOT NULL,
  TableSizeX_m REAL    NOT NULL CHECK (TableSizeX_m > 0),
  TableSizeY_m REAL    NOT NULL CHECK (TableSizeY_m > 0),
  CameraX REAL NOT NULL, CameraY REAL NOT NULL, CameraZ REAL NOT NULL,
  CameraQW REAL NOT NULL, CameraQX REAL NOT NULL, CameraQY REAL NOT NULL, CameraQZ REAL NOT NULL
);
CREATE TABLE SceneObjects (
  TaskModelId INTEGER NOT NULL REFERENCES PerceivedScenes(TaskModelId) ON DELETE CASCADE,
  ObjectId    TEXT    NOT NULL,
  ClassId     INTEGER NOT NULL,
  ClassName   TEXT    NOT NULL,
  X REAL NOT NULL, Y REAL NOT NULL, Z REAL NOT NULL,
  QW REAL NOT NULL, QX REAL NOT NULL, QY REAL NOT NULL, QZ REAL NOT NULL,
  Color TEXT,
  R REAL, G REAL, B REAL,
  PRIMARY KEY (TaskModelId, ObjectId)
);
CREATE TABLE ObservedClasses (
  TaskModelId INTEGER NOT NULL REFERENCES TaskModels(TaskModelId) ON DELETE CASCADE,
  ClassId     INTEGER NOT NULL,
  Name        TEXT    NOT NULL,
  Definition  TEXT    NOT NULL CHECK (json_valid(Definition)),
  PRIMARY KEY (TaskModelId, ClassId),
  UNIQUE (TaskModelId, Name)
);
)SQL";

const std::vector<std::string>& migrations() {
  static const std::vector<std::string> m = {kSchemaV1, kSchemaV2, kSchemaV3};
  return m;
}

}  // namespace srp::taskdb::detail
