#include "srp/core/Json.h"

#include <cstdio>
#include <fstream>

#include "srp/core/Error.h"

namespace srp::core {

nlohmann::json readJsonFile(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw FileError(path, "cannot open JSON file (does it exist and is it readable?)");
  try {
    return nlohmann::json::parse(in);
  } catch (const nlohmann::json::parse_error& e) {
    throw FileError(path, std::string("malformed JSON: ") + e.what());
  }
}

void writeJsonFile(const std::string& path, const nlohmann::json& j) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp);
    if (!out) throw FileError(path, "cannot write (is the folder there and writable?)");
    out << j.dump(2) << '\n';
    if (!out) throw FileError(path, "write failed (disk full?)");
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) throw FileError(path, "cannot rename temporary file");
}

const nlohmann::json& requireField(const nlohmann::json& j, const std::string& key,
                                   const std::string& context) {
  if (!j.is_object() || !j.contains(key))
    throw InvalidInputError(context + ": missing field '" + key + "'");
  return j.at(key);
}

nlohmann::json poseToJson(const Pose3& X) {
  const Eigen::Quaterniond q(X.linear());
  const Eigen::Vector3d t = X.translation();
  return {{"translation", {t.x(), t.y(), t.z()}}, {"quaternion", {q.w(), q.x(), q.y(), q.z()}}};
}

Pose3 poseFromJson(const nlohmann::json& j, const std::string& context) {
  try {
    if (j.contains("matrix")) {
      const auto& m = j.at("matrix");
      Pose3 X = Pose3::Identity();
      const bool nested = m.size() == 4 && m[0].is_array();
      if (!nested && m.size() != 16)
        throw InvalidInputError(context + ": 'matrix' must be 4x4 or 16 numbers (row-major)");
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 4; ++c) {
          const double v = nested ? m[r][c].get<double>() : m[r * 4 + c].get<double>();
          if (c < 3) X.linear()(r, c) = v; else X.translation()(r) = v;
        }
      return X;
    }
    const auto& t = requireField(j, "translation", context);
    const auto& q = requireField(j, "quaternion", context);
    if (t.size() != 3 || q.size() != 4)
      throw InvalidInputError(context + ": 'translation' needs 3 numbers, 'quaternion' 4 (w,x,y,z)");
    return makePose({t[0].get<double>(), t[1].get<double>(), t[2].get<double>()},
                    Eigen::Quaterniond(q[0].get<double>(), q[1].get<double>(), q[2].get<double>(),
                                       q[3].get<double>()));
  } catch (const nlohmann::json::exception& e) {
    throw InvalidInputError(context + ": bad pose (" + e.what() + ")");
  }
}

}  // namespace srp::core
