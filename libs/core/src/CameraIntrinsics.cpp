#include "srp/core/CameraIntrinsics.h"

#include <nlohmann/json.hpp>

#include "srp/core/Error.h"

namespace srp::core {

Eigen::Vector3d CameraIntrinsics::backProject(double u, double v, double Z) const {
  return {(u - cx_px) * Z / fx_px, (v - cy_px) * Z / fy_px, Z};
}

std::optional<Eigen::Vector2d> CameraIntrinsics::project(const Eigen::Vector3d& p) const {
  if (!(p.z() > 0.0)) return std::nullopt;
  return Eigen::Vector2d(fx_px * p.x() / p.z() + cx_px, fy_px * p.y() / p.z() + cy_px);
}

bool CameraIntrinsics::contains(double u, double v) const {
  return u >= -0.5 && v >= -0.5 && u < width_px - 0.5 && v < height_px - 0.5;
}

void CameraIntrinsics::validate(const std::string& what) const {
  if (!(fx_px > 0.0) || !(fy_px > 0.0))
    throw InvalidInputError(what + ": focal lengths fx, fy must be positive (got " +
                            std::to_string(fx_px) + ", " + std::to_string(fy_px) + ")");
  if (width_px <= 0 || height_px <= 0)
    throw InvalidInputError(what + ": image width and height must be positive (got " +
                            std::to_string(width_px) + "x" + std::to_string(height_px) + ")");
}

bool CameraIntrinsics::operator==(const CameraIntrinsics& o) const {
  return fx_px == o.fx_px && fy_px == o.fy_px && cx_px == o.cx_px && cy_px == o.cy_px &&
         width_px == o.width_px && height_px == o.height_px;
}

void to_json(nlohmann::json& j, const CameraIntrinsics& k) {
  j = nlohmann::json{{"fx", k.fx_px},         {"fy", k.fy_px},          {"cx", k.cx_px},
                     {"cy", k.cy_px},         {"width", k.width_px}, {"height", k.height_px}};
}

void from_json(const nlohmann::json& j, CameraIntrinsics& k) {
  for (const char* key : {"fx", "fy", "cx", "cy", "width", "height"})
    if (!j.contains(key))
      throw InvalidInputError(std::string("camera intrinsics: missing field '") + key + "'");
  k.fx_px = j.at("fx").get<double>();
  k.fy_px = j.at("fy").get<double>();
  k.cx_px = j.at("cx").get<double>();
  k.cy_px = j.at("cy").get<double>();
  k.width_px = j.at("width").get<int>();
  k.height_px = j.at("height").get<int>();
}

}  // namespace srp::core
