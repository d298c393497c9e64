#include "srp/core/Json.h"

#include <cstdio>
#include <fstream>

#include "srp/core/Error.h"
#include "srp/core/OutputFile.h"

namespace srp::core {

nlohmann::json readJsonFile(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw FileError(path, "cannot open JSON file (does it exist and is it readable?)");
  try {
    return nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    // Parse errors, numbers out of range (1e999) and invalid UTF-8 alike;
    // without nlohmann's "[json.exception.<kind>.<id>] " prefix.
    std::string what = e.what();
    if (what.rfind("[json.exception.", 0) == 0 && what.find("] ") != std::string::npos)
      what = what.substr(what.find("] ") + 2);
    throw FileError(path, "malformed JSON: " + what + " (fix the file; numbers must be finite doubles)");
  }
}

void writeJsonFile(const std::string& path, const nlohmann::json& j) {
  writeFileAtomically(path, j.dump(2) + "\n");
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
    const Eigen::Vector3d p(t[0].get<double>(), t[1].get<double>(), t[2].get<double>());
    const Eigen::Quaterniond rotation(q[0].get<double>(), q[1].get<double>(), q[2].get<double>(), q[3].get<double>());
    if (!p.allFinite()) throw InvalidInputError(context + ": 'translation' must be 3 finite numbers [m]");
    // A quaternion of (almost) zero length is no rotation; normalising it gives NaN.
    constexpr double kMinQuaternionNorm = 1e-6;
    if (!rotation.coeffs().allFinite() || !(rotation.norm() > kMinQuaternionNorm))
      throw InvalidInputError(context + ": 'quaternion' (w,x,y,z) must be finite and not zero (e.g. [1, 0, 0, 0])");
    return makePose(p, rotation);
  } catch (const nlohmann::json::exception& e) {
    throw InvalidInputError(context + ": bad pose (" + e.what() + ")");
  }
}

}  // namespace srp::core
