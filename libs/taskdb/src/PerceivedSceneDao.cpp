#include "srp/taskdb/PerceivedSceneDao.h"

#include <cmath>

#include "SqlUtil.h"
#include "srp/core/ObjectClassJson.h"

namespace srp::taskdb {
using namespace detail;

namespace {

// The least norm a stored quaternion may have (it is normalised when read).
constexpr double kMinQuaternionNorm = 0.5;

void bindPose(Statement& st, int first, const core::Pose3& X) {
  const Eigen::Quaterniond q(X.linear());
  const double v[] = {X.translation().x(), X.translation().y(), X.translation().z(), q.w(), q.x(), q.y(), q.z()};
  for (int i = 0; i < 7; ++i) st.bind(first + i, v[i]);
}

void checkPose(const core::Pose3& X, const std::string& what) {
  if (!X.matrix().allFinite()) throw core::InvalidInputError(what + " has a non-finite value (NaN/inf)");
}

// A number read back; a FileError naming table, row and column when it is not finite.
double finiteColumn(const Statement& st, int column, const std::string& where, const std::string& path) {
  const Column c = st.getColumn(column);
  const double v = c.getDouble();
  if (c.isNull() || !std::isfinite(v))
    throw core::FileError(path, where + " column " + c.getName() + " is not a finite number; the task model is "
                                        "damaged (program the task again)");
  return v;
}

core::Pose3 readPose(const Statement& st, int first, const std::string& where, const std::string& path) {
  double v[7];
  for (int i = 0; i < 7; ++i) v[i] = finiteColumn(st, first + i, where, path);
  const Eigen::Quaterniond q(v[3], v[4], v[5], v[6]);
  if (!(q.norm() > kMinQuaternionNorm))
    throw core::FileError(path, where + " has a quaternion of norm " + std::to_string(q.norm()) +
                                    " (not a rotation); the task model is damaged (program the task again)");
  core::Pose3 X = core::Pose3::Identity();
  X.linear() = q.normalized().toRotationMatrix();
  X.translation() = Eigen::Vector3d(v[0], v[1], v[2]);
  return X;
}

}  // namespace

void PerceivedSceneDao::add(int tm, const PerceivedScene& s) {
  const std::string ctx = "perceived scene of task model " + std::to_string(tm);
  if (!s.tableSize_m.allFinite() || (s.tableSize_m.array() <= 0.0).any())
    throw core::InvalidInputError(ctx + ": the table size must be two positive numbers");
  checkPose(s.X_table_camera, ctx + ": the camera pose");
  Statement scene(db_,
                          "INSERT INTO PerceivedScenes (TaskModelId, Catalogue, TableSizeX_m, TableSizeY_m, CameraX, "
                          "CameraY, CameraZ, CameraQW, CameraQX, CameraQY, CameraQZ) VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?)");
  scene.bind(1, tm);
  scene.bind(2, s.catalogue);
  scene.bind(3, s.tableSize_m.x());
  scene.bind(4, s.tableSize_m.y());
  bindPose(scene, 5, s.X_table_camera);
  scene.exec();

  Statement object(db_,
                           "INSERT INTO SceneObjects (TaskModelId, ObjectId, ClassId, ClassName, X, Y, Z, QW, QX, QY, "
                           "QZ, Color, R, G, B) VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?)");
  for (const auto& o : s.objects) {
    checkPose(o.X_table_object, ctx + ": object '" + o.objectId + "'");
    if (o.rgb && (!o.rgb->allFinite() || (o.rgb->array() < 0.0).any() || (o.rgb->array() > 1.0).any()))
      throw core::InvalidInputError(ctx + ": object '" + o.objectId + "' has an rgb outside [0, 1]");
    object.reset();
    object.bind(1, tm);
    object.bind(2, o.objectId);
    object.bind(3, o.classId);
    object.bind(4, o.className);
    bindPose(object, 5, o.X_table_object);
    bindOptional(object, 12, o.colour);
    for (int k = 0; k < 3; ++k) bindOptional(object, 13 + k, o.rgb ? std::optional<double>((*o.rgb)[k]) : std::nullopt);
    object.exec();
  }

  Statement cls(db_,
                        "INSERT INTO ObservedClasses (TaskModelId, ClassId, Name, Definition) VALUES (?, ?, ?, ?)");
  for (const auto& c : s.observedClasses) {
    const nlohmann::json definition = core::objectClassToJson(c);
    core::objectClassFromJson(definition, ctx + ": observed class");  // what is stored must read back
    cls.reset();
    cls.bind(1, tm);
    cls.bind(2, c.classId);
    cls.bind(3, c.name);
    cls.bind(4, definition.dump());
    cls.exec();
  }
}

std::optional<PerceivedScene> PerceivedSceneDao::get(int tm) const {
  const std::string& path = db_.path();
  const std::string model = "task model " + std::to_string(tm);
  Statement scene(db_,
                          "SELECT Catalogue, TableSizeX_m, TableSizeY_m, CameraX, CameraY, CameraZ, CameraQW, CameraQX, "
                          "CameraQY, CameraQZ FROM PerceivedScenes WHERE TaskModelId = ?");
  scene.bind(1, tm);
  if (!scene.executeStep()) return std::nullopt;
  PerceivedScene s;
  const std::string sceneRow = "table PerceivedScenes, row of " + model + ",";
  s.catalogue = scene.getColumn(0).getString();
  s.tableSize_m = {finiteColumn(scene, 1, sceneRow, path), finiteColumn(scene, 2, sceneRow, path)};
  if ((s.tableSize_m.array() <= 0.0).any())
    throw core::FileError(path, sceneRow + " the table size is not positive; the task model is damaged");
  s.X_table_camera = readPose(scene, 3, sceneRow, path);

  Statement object(db_,
                           "SELECT ObjectId, ClassId, ClassName, X, Y, Z, QW, QX, QY, QZ, Color, R, G, B FROM "
                           "SceneObjects WHERE TaskModelId = ? ORDER BY " +
                               std::string(db_.isPostgres() ? "Seq" : "rowid"));
  object.bind(1, tm);
  while (object.executeStep()) {
    SceneObjectRow o;
    o.objectId = object.getColumn(0).getString();
    const std::string where = "table SceneObjects, row '" + o.objectId + "' of " + model + ",";
    o.classId = object.getColumn(1).getInt();
    o.className = object.getColumn(2).getString();
    o.X_table_object = readPose(object, 3, where, path);
    o.colour = optionalText(object.getColumn(10));
    if (!object.getColumn(11).isNull() || !object.getColumn(12).isNull() || !object.getColumn(13).isNull()) {
      const Eigen::Vector3d rgb(finiteColumn(object, 11, where, path), finiteColumn(object, 12, where, path),
                                finiteColumn(object, 13, where, path));
      if ((rgb.array() < 0.0).any() || (rgb.array() > 1.0).any())
        throw core::FileError(path, where + " the colour (R, G, B) is outside [0, 1]; the task model is damaged");
      o.rgb = rgb;
    }
    s.objects.push_back(o);
  }

  Statement cls(db_,
                        "SELECT ClassId, Name, Definition FROM ObservedClasses WHERE TaskModelId = ? ORDER BY ClassId");
  cls.bind(1, tm);
  while (cls.executeStep()) {
    const std::string name = cls.getColumn(1).getString();
    const std::string where = "table ObservedClasses, row '" + name + "' of " + model + ", column Definition";
    core::ObjectClass c;
    try {
      c = core::objectClassFromJson(nlohmann::json::parse(cls.getColumn(2).getString()), where);
    } catch (const core::InvalidInputError& e) {
      throw core::FileError(path, std::string(e.what()) + "; the task model is damaged (program the task again)");
    } catch (const nlohmann::json::exception& e) {
      throw core::FileError(path, where + ": not JSON (" + e.what() + "); the task model is damaged");
    }
    if (c.classId != cls.getColumn(0).getInt() || c.name != name)
      throw core::FileError(path, where + ": the definition names class '" + c.name + "' (" +
                                      std::to_string(c.classId) + "), not the row's; the task model is damaged");
    s.observedClasses.push_back(c);
  }
  return s;
}

bool PerceivedSceneDao::remove(int tm) {
  Statement classes(db_, "DELETE FROM ObservedClasses WHERE TaskModelId = ?");
  classes.bind(1, tm);
  classes.exec();
  Statement objects(db_, "DELETE FROM SceneObjects WHERE TaskModelId = ?");
  objects.bind(1, tm);
  objects.exec();
  Statement scene(db_, "DELETE FROM PerceivedScenes WHERE TaskModelId = ?");
  scene.bind(1, tm);
  return scene.exec() > 0;
}

}  // namespace srp::taskdb
