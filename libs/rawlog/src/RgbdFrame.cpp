#include "srp/rawlog/RgbdFrame.h"

#include "srp/core/Error.h"

namespace srp::rawlog {

void RgbdFrame::validate(const std::string& what) const {
  using srp::core::InvalidInputError;
  intrinsics.validate(what);
  const auto size = [](const cv::Mat& m) { return std::to_string(m.cols) + "x" + std::to_string(m.rows); };
  const std::string expected = std::to_string(intrinsics.width_px) + "x" + std::to_string(intrinsics.height_px);
  if (colour_bgr8.empty()) throw InvalidInputError(what + ": frame " + std::to_string(index) + " has no colour image");
  if (depth_m.empty()) throw InvalidInputError(what + ": frame " + std::to_string(index) + " has no depth image");
  if (colour_bgr8.type() != CV_8UC3)
    throw InvalidInputError(what + ": colour image of frame " + std::to_string(index) + " must be 8-bit BGR");
  if (depth_m.type() != CV_32FC1)
    throw InvalidInputError(what + ": depth image of frame " + std::to_string(index) + " must be float metres");
  if (colour_bgr8.cols != intrinsics.width_px || colour_bgr8.rows != intrinsics.height_px)
    throw InvalidInputError(what + ": colour image of frame " + std::to_string(index) + " is " + size(colour_bgr8) +
                            " but the intrinsics say " + expected);
  if (depth_m.cols != intrinsics.width_px || depth_m.rows != intrinsics.height_px)
    throw InvalidInputError(what + ": depth image of frame " + std::to_string(index) + " is " + size(depth_m) +
                            " but the colour image is " + expected + " (depth must be registered to colour)");
}

}  // namespace srp::rawlog
