#include "srp/core/CameraIntrinsics.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <sstream>

#include "srp/core/Error.h"

namespace srp::core {

namespace {
// Sane bounds: no camera has a 16k-pixel side or a focal length of a million pixels.
constexpr int kMaxSide_px = 16384;
constexpr double kMaxFocal_px = 1e6;
}  // namespace

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
  const auto text = [](double v) {
    std::ostringstream s;
    s << v;
    return s.str();
  };
  if (!(fx_px > 0.0) || !(fy_px > 0.0) || !std::isfinite(fx_px) || !std::isfinite(fy_px) || fx_px > kMaxFocal_px ||
      fy_px > kMaxFocal_px)
    throw InvalidInputError(what + ": focal lengths fx, fy (ViSP px, py) must be numbers in (0, " + text(kMaxFocal_px) +
                            "] px (got " + text(fx_px) + ", " + text(fy_px) + ")");
  if (!std::isfinite(cx_px) || !std::isfinite(cy_px) || std::abs(cx_px) > kMaxFocal_px ||
      std::abs(cy_px) > kMaxFocal_px)
    throw InvalidInputError(what + ": principal point cx, cy (ViSP u0, v0) must be finite numbers [px] (got " +
                            text(cx_px) + ", " + text(cy_px) + ")");
  if (width_px <= 0 || height_px <= 0 || width_px > kMaxSide_px || height_px > kMaxSide_px)
    throw InvalidInputError(what + ": image width and height must be in 1.." + std::to_string(kMaxSide_px) +
                            " px (got " + std::to_string(width_px) + "x" + std::to_string(height_px) + ")");
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
  for (const char* key : {"fx", "fy", "cx", "cy"})
    if (!j.at(key).is_number())
      throw InvalidInputError(std::string("camera intrinsics: '") + key + "' must be a number [px] (got " +
                              j.at(key).dump() + ")");
  // Integers only, in range: 1e12 or 640.5 is not an image size (get<int> would wrap it).
  for (const char* key : {"width", "height"}) {
    const auto& v = j.at(key);
    if (!v.is_number_integer() || v.get<long long>() < 1 || v.get<long long>() > kMaxSide_px)
      throw InvalidInputError(std::string("camera intrinsics: '") + key + "' must be a whole number of pixels in 1.." +
                              std::to_string(kMaxSide_px) + " (got " + v.dump() + ")");
  }
  k.fx_px = j.at("fx").get<double>();
  k.fy_px = j.at("fy").get<double>();
  k.cx_px = j.at("cx").get<double>();
  k.cy_px = j.at("cy").get<double>();
  k.width_px = j.at("width").get<int>();
  k.height_px = j.at("height").get<int>();
}

}  // namespace srp::core
