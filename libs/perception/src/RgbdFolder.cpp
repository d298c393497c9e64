#include "srp/perception/RgbdFolder.h"

#include <cstdio>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>

#include "srp/core/Error.h"
#include "srp/core/Json.h"

namespace srp::perception {

std::vector<rawlog::RgbdFrame> readRgbdFolder(const std::string& folder, int maxFrames) {
  namespace fs = std::filesystem;
  const std::string camPath = (fs::path(folder) / "cam.json").string();
  const nlohmann::json cam = core::readJsonFile(camPath);
  core::CameraIntrinsics k;
  k.fx_px = core::requireField(cam, "px", camPath).get<double>();
  k.fy_px = core::requireField(cam, "py", camPath).get<double>();
  k.cx_px = core::requireField(cam, "u0", camPath).get<double>();
  k.cy_px = core::requireField(cam, "v0", camPath).get<double>();
  k.width_px = core::requireField(cam, "w", camPath).get<int>();
  k.height_px = core::requireField(cam, "h", camPath).get<int>();
  const double depthScale_m = core::requireField(cam, "depthScale", camPath).get<double>();
  k.validate(camPath);

  std::vector<rawlog::RgbdFrame> frames;
  for (int i = 0; maxFrames <= 0 || i < maxFrames; ++i) {
    char name[32];
    std::snprintf(name, sizeof(name), "%04d", i);
    // Colour as PNG, else JPEG (HRT1's recordings); depth always a 16-bit PNG.
    std::string colourPath = (fs::path(folder) / ("color_" + std::string(name) + ".png")).string();
    if (!fs::exists(colourPath)) colourPath = (fs::path(folder) / ("color_" + std::string(name) + ".jpg")).string();
    const std::string depthPath = (fs::path(folder) / ("depth_" + std::string(name) + ".png")).string();
    if (!fs::exists(colourPath)) break;
    if (!fs::exists(depthPath)) throw core::FileError(depthPath, "missing: every color_NNNN.png/.jpg needs its depth_NNNN.png");
    rawlog::RgbdFrame f;
    f.index = i;
    f.t_s = i / 30.0;  // the folder carries no timestamps; RealSense rate
    f.intrinsics = k;
    f.colour_bgr8 = cv::imread(colourPath, cv::IMREAD_COLOR);
    if (f.colour_bgr8.empty()) throw core::FileError(colourPath, "not a readable image");
    const cv::Mat raw = cv::imread(depthPath, cv::IMREAD_ANYDEPTH);
    if (raw.empty() || raw.type() != CV_16UC1) throw core::FileError(depthPath, "not a readable 16-bit depth PNG");
    raw.convertTo(f.depth_m, CV_32FC1, depthScale_m);
    f.validate(colourPath);
    frames.push_back(std::move(f));
  }
  if (frames.empty()) throw core::FileError(folder, "no color_0000.png/depth_0000.png pair in this folder");
  return frames;
}

}  // namespace srp::perception
