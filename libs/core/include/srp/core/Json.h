#pragma once
/// \file Json.h
/// \brief JSON helpers shared by the modules: reading a JSON file with errors
/// that name the file, and checked field access that names the missing field.

#include <nlohmann/json.hpp>
#include <string>

#include "srp/core/Pose.h"

namespace srp::core {

/// Parses a JSON file; throws FileError naming the path on a missing or
/// malformed file (with the parser's position).
nlohmann::json readJsonFile(const std::string& path);

/// Writes JSON (2-space indent) atomically: a temporary file renamed over `path`.
void writeJsonFile(const std::string& path, const nlohmann::json& j);

/// j[key]; throws InvalidInputError "<context>: missing field '<key>'" when absent.
const nlohmann::json& requireField(const nlohmann::json& j, const std::string& key,
                                   const std::string& context);

/// Pose as {"translation": [x,y,z], "quaternion": [w,x,y,z]} (metres).
nlohmann::json poseToJson(const Pose3& X);
/// Accepts that form or {"matrix": 4x4 row-major}; `context` names it in errors.
Pose3 poseFromJson(const nlohmann::json& j, const std::string& context);

}  // namespace srp::core
