#pragma once
// Private: Eigen vectors/matrices <-> JSON arrays (doubles round-trip exactly).
#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <string>

#include "srp/core/Error.h"

namespace srp::motion::detail {

inline nlohmann::json toJson(const Eigen::VectorXd& v) {
  return nlohmann::json(std::vector<double>(v.data(), v.data() + v.size()));
}

/// Rows as arrays.
inline nlohmann::json toJson(const Eigen::MatrixXd& M) {
  nlohmann::json rows = nlohmann::json::array();
  for (Eigen::Index r = 0; r < M.rows(); ++r) {
    std::vector<double> row(static_cast<std::size_t>(M.cols()));
    for (Eigen::Index c = 0; c < M.cols(); ++c) row[static_cast<std::size_t>(c)] = M(r, c);
    rows.push_back(row);
  }
  return rows;
}

inline Eigen::VectorXd vectorFromJson(const nlohmann::json& j, Eigen::Index size, const std::string& ctx) {
  if (!j.is_array() || static_cast<Eigen::Index>(j.size()) != size)
    throw core::InvalidInputError(ctx + ": expected an array of " + std::to_string(size) + " numbers");
  Eigen::VectorXd v(size);
  for (Eigen::Index i = 0; i < size; ++i) v(i) = j[static_cast<std::size_t>(i)].get<double>();
  return v;
}

inline Eigen::MatrixXd matrixFromJson(const nlohmann::json& j, const std::string& ctx) {
  if (!j.is_array() || j.empty() || !j[0].is_array())
    throw core::InvalidInputError(ctx + ": expected an array of rows");
  const auto rows = static_cast<Eigen::Index>(j.size()), cols = static_cast<Eigen::Index>(j[0].size());
  Eigen::MatrixXd M(rows, cols);
  for (Eigen::Index r = 0; r < rows; ++r) M.row(r) = vectorFromJson(j[static_cast<std::size_t>(r)], cols, ctx).transpose();
  return M;
}

/// Checks the "class" and "schema_version" fields of a serialised object.
inline void requireClassAndVersion(const nlohmann::json& j, const std::string& expectedClass, int knownVersion,
                                   const std::string& ctx) {
  if (!j.is_object()) throw core::InvalidInputError(ctx + ": expected an object");
  if (!j.contains("class") || !j.contains("schema_version"))
    throw core::InvalidInputError(ctx + ": missing field 'class' or 'schema_version'");
  const auto cls = j.at("class").get<std::string>();
  if (cls != expectedClass) throw core::InvalidInputError(ctx + ": class is '" + cls + "', expected " + expectedClass);
  const int version = j.at("schema_version").get<int>();
  if (version != knownVersion)
    throw core::InvalidInputError(ctx + ": schema_version " + std::to_string(version) +
                                  " is not known to this build (knows " + std::to_string(knownVersion) +
                                  "); update srp");
}

}  // namespace srp::motion::detail
