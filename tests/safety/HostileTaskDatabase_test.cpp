// Task databases read defensively: one cell of a valid task model at a time is
// replaced by a hostile value (text in a number column, Inf, 1e308, a blob,
// out-of-range flags and quaternions, broken or unusable JSON in Skills,
// Intrinsics, X_base_camera; CHECK constraints switched off, as another program
// could write them), and the model is read as `srp execute` reads it
// (TaskModelStore::read, then the learned skills: DmpPathGenerator). Each case
// is read exactly (a valid value) or refused with srp's error naming the table
// and the column; nothing else is thrown, nothing crashes (ASan/UBSan in
// make test-sanitize), no Skills row is silently replaced by minimum-jerk paths.
#include <SQLiteCpp/SQLiteCpp.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <regex>

#include "ScratchFolder.h"
#include "srp/core/Error.h"
#include "srp/execution/DmpPathGenerator.h"
#include "srp/motion/Dmp.h"
#include "srp/taskdb/TaskDatabase.h"
#include "srp/taskdb/TaskModelStore.h"

namespace fs = std::filesystem;
using namespace srp;

namespace {

/// A valid task model: one part, 40 frames of hand and object poses, a camera,
/// and learned Reach and Move DMPs.
taskdb::TaskModel goodModel() {
  taskdb::TaskModel m;
  m.info.name = "hostile";
  m.info.instruction = "Pick up the cuboid and place it in the gray box.";
  m.info.intrinsics = core::CameraIntrinsics{};
  m.info.intrinsics->fx_px = m.info.intrinsics->fy_px = 500.0;
  m.info.intrinsics->cx_px = 320.0;
  m.info.intrinsics->cy_px = 240.0;
  m.info.intrinsics->width_px = 640;
  m.info.intrinsics->height_px = 480;
  m.info.X_base_camera = core::Pose3::Identity();
  m.products.push_back({0, "cuboid", {}, {}, std::string("red"), 3, 0, 3, ""});
  m.targetObjectIds = {0};
  m.groundedProducts.push_back({3, "cuboid", {}, {}, std::string("red"), ""});
  Eigen::VectorXd t(40);
  Eigen::MatrixXd Y(40, 3);
  for (int k = 0; k < 40; ++k) {
    const double s = k / 39.0;
    t(k) = k / 30.0;
    Y.row(k) << 0.1 * s, 0.05 * std::sin(3.0 * s), 0.6 - 0.1 * s * s;
    m.handPositions.push_back({k, Y.row(k).transpose(), true});
    taskdb::ProductPoseRow r;
    r.classId = 3;
    r.timeId = k;
    r.p_m = Eigen::Vector3d(0.1, 0.0, 0.6);
    r.confidence = 0.9;
    m.productPoses.push_back(r);
  }
  const motion::Dmp dmp = motion::Dmp::imitate(t, Y, motion::Dmp::Options{});
  for (const auto skill : {core::SkillType::Reach, core::SkillType::Move}) {
    taskdb::SkillRow row;
    row.classId = 3;
    row.skill = skill;
    row.startTimeId = skill == core::SkillType::Reach ? 0 : 20;
    row.endTimeId = skill == core::SkillType::Reach ? 20 : 39;
    row.parameters = {{"frame", "camera"}, {"dmp", dmp.toJson()}};
    m.skills.push_back(row);
  }
  return m;
}

struct Cell {
  std::string table, column, value;  ///< value: an SQL expression
  std::string where = "1";           ///< which rows
};

std::vector<Cell> hostileCells(const std::string& validDmp) {
  std::vector<Cell> cells;
  const std::vector<std::string> numbers = {"'abc'", "'1.0x'", "''", "X'00FF'", "9e999", "-9e999", "1e308", "-1e308",
                                            "1e20", "1099511627776", "-2147483649", "0.5"};
  for (const char* column : {"X", "Y", "Z", "QW", "QX", "QY", "QZ", "Confidence", "Reach", "Detected", "ClassId", "TimeId"})
    for (const auto& v : numbers) cells.push_back({"ProductPose", column, v, "TimeId = 5"});
  cells.push_back({"ProductPose", "QW", "0", "TimeId = 6"});  // with QX..QZ = 0: a zero quaternion
  for (const char* column : {"X", "Y", "Z", "Detected", "TimeId"})
    for (const auto& v : numbers) cells.push_back({"HandPositions", column, v, "TimeId = 7"});
  for (const auto& v : {"0", "-1", "9e999", "'thirty'", "1e300", "NULL"})
    cells.push_back({"TaskModels", "FrameRate_Hz", v});
  for (const auto& v : {"'{'", "'[]'", "'null'", "'{\"fx\": -1}'", "'{\"fx\": 1e308, \"fy\": 1, \"cx\": 0, \"cy\": 0}'", "'NaN'"})
    cells.push_back({"TaskModels", "Intrinsics", v});
  for (const auto& v : {"'{'", "'[]'", "'{\"translation\": [1e300, 0, 0], \"quaternion\": [1, 0, 0, 0]}'",
                        "'{\"translation\": [0, 0, 0], \"quaternion\": [0, 0, 0, 0]}'", "'{\"matrix\": [1, 2]}'"})
    cells.push_back({"TaskModels", "X_base_camera", v});
  for (const auto& v : {"'abc'", "0", "-5", "9e999"}) cells.push_back({"TaskModels", "Version", v});
  for (const auto& v : {"'{}'", "'null'", "'[]'", "'\"text\"'", "'{\"dmp\": null}'", "'{\"dmp\": {}}'", "'{\"dmp\": []}'",
                        "'{\"dmp\": \"x\"}'", "'NaN'", "'Infinity'", "'1e999'", "'{\"dmp\": 1e999}'", "'{'", "''",
                        "'{\"frame\": \"camera\"}'"})
    cells.push_back({"Skills", "Parameters", v, "Skill = 'Reach'"});
  // A valid DMP, one field made hostile.
  const auto dmpWith = [&](const std::string& from, const std::string& to) {
    std::string j = "{\"frame\": \"camera\", \"dmp\": " + validDmp + "}";
    const std::size_t at = j.find(from);
    if (at != std::string::npos) j.replace(at, from.size(), to);
    std::string quoted = "'";
    for (char c : j) quoted += c == '\'' ? std::string("''") : std::string(1, c);
    return quoted + "'";
  };
  cells.push_back({"Skills", "Parameters", dmpWith("\"frame\": \"camera\"", "\"frame\": \"world\""), "Skill = 'Move'"});
  cells.push_back({"Skills", "Parameters", dmpWith("\"basis_count\":20", "\"basis_count\":2000000000"), "Skill = 'Move'"});
  cells.push_back({"Skills", "Parameters", dmpWith("\"basis_count\":20", "\"basis_count\":-1"), "Skill = 'Move'"});
  cells.push_back({"Skills", "Parameters", dmpWith("\"demo\":{\"duration_s\":", "\"demo\":{\"duration_s\":1e12,\"x\":"),
                   "Skill = 'Move'"});
  cells.push_back({"Skills", "Parameters", dmpWith("\"class\":\"srp::motion::Dmp\"", "\"class\":\"other\""), "Skill = 'Move'"});
  for (const auto& v : {"'Jump'", "''", "NULL"}) cells.push_back({"Skills", "Skill", v, "Skill = 'Reach'"});
  for (const auto& v : {"'abc'", "1e20", "-1000"}) cells.push_back({"Skills", "EndTimeId", v, "Skill = 'Reach'"});
  for (const auto& v : {"'abc'", "1099511627776"}) {
    cells.push_back({"Products", "ObjectId", v});
    cells.push_back({"Products", "ClassId", v});
    cells.push_back({"GroundedProducts", "ClassId", v});
    cells.push_back({"TaskModelTargetObjects", "TargetObjectId", v});
  }
  return cells;
}

}  // namespace

TEST(HostileTaskDatabase, EveryCellIsReadOrRefusedNamingIt) {
  const srp::safety::ScratchFolder scratch("db");
  const fs::path& dir = scratch.path;
  const std::string good = (dir / "good.db").string();
  const taskdb::TaskModel model = goodModel();
  {
    auto db = taskdb::TaskDatabase::open(good);
    taskdb::TaskModelStore(db).write(model);
    db.connection().exec("PRAGMA wal_checkpoint(TRUNCATE)");
  }
  const std::string validDmp = model.skills.front().parameters.at("dmp").dump();
  int read = 0, refused = 0, foreign = 0, unnamed = 0, silentFallback = 0, cases = 0;
  for (const Cell& cell : hostileCells(validDmp)) {
    const std::string path = (dir / ("case_" + std::to_string(cases++) + ".db")).string();
    fs::copy_file(good, path, fs::copy_options::overwrite_existing);
    try {
      SQLite::Database raw(path, SQLite::OPEN_READWRITE);
      raw.exec("PRAGMA synchronous = OFF");  // a scratch copy: no need to wait for the disk
      raw.exec("PRAGMA ignore_check_constraints = ON");
      raw.exec("PRAGMA foreign_keys = OFF");
      if (cell.table == "ProductPose" && cell.where == "TimeId = 6") raw.exec("UPDATE ProductPose SET QX = 0, QY = 0, QZ = 0 WHERE TimeId = 6");
      raw.exec("UPDATE " + cell.table + " SET " + cell.column + " = " + cell.value + " WHERE " + cell.where);
    } catch (const SQLite::Exception& e) {
      continue;  // SQLite itself refuses the value (NOT NULL): nothing to read
    }
    const std::string what = cell.table + "." + cell.column + " = " + cell.value;
    try {
      auto db = taskdb::TaskDatabase::open(path, taskdb::TaskDatabase::Mode::ReadOnly);
      const taskdb::TaskModel m = taskdb::TaskModelStore(db).read(1);
      const auto generator = execution::DmpPathGenerator::fromTaskModel(m, core::Pose3::Identity());
      ++read;
      // Read: the Skills rows are used, never replaced by another path.
      if (generator.sourceFor(core::SkillType::Reach, "cuboid") != "dmp" ||
          generator.sourceFor(core::SkillType::Move, "cuboid") != "dmp") {
        ++silentFallback;
        ADD_FAILURE() << what << ": read, but the learned skill is not used";
      }
      for (const auto& r : m.productPoses) EXPECT_TRUE(r.p_m.allFinite() && r.q.coeffs().allFinite()) << what;
      EXPECT_TRUE(std::isfinite(m.info.frameRate_hz) && m.info.frameRate_hz > 0) << what;
    } catch (const core::Error& e) {
      ++refused;
      const std::string message = e.what();
      const bool names = message.find(cell.column) != std::string::npos &&
                         (message.find(cell.table) != std::string::npos ||
                          (cell.table == "Skills" && message.find("Skills row") != std::string::npos));
      if (!names && message.find("foreign key") == std::string::npos && message.find(path) == std::string::npos) {
        ++unnamed;
        ADD_FAILURE() << what << ": the message names neither the table and column nor the file: " << message;
      }
    } catch (const std::exception& e) {
      ++foreign;
      ADD_FAILURE() << what << ": not an srp error: " << e.what();
    }
  }
  std::printf("[ sweep ] task database cells: %d cases, %d read, %d refused naming the cell, %d unnamed, %d foreign "
              "errors, %d silent fall-backs\n",
              cases, read, refused - unnamed, unnamed, foreign, silentFallback);
  EXPECT_EQ(foreign, 0);
  EXPECT_EQ(unnamed, 0);
  EXPECT_EQ(silentFallback, 0);
  EXPECT_GT(refused, cases / 2);
}
