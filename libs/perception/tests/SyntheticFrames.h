#pragma once
// Tiny hand-made RGB-D frames for the hand detectors and the pipeline: a flat
// table seen from above and, from frame `handFrom` on, an arm entering from the
// right border ending in a palm disc (skin coloured, 10 cm above the table).
#include <opencv2/imgproc.hpp>
#include <vector>

#include "srp/rawlog/RgbdFrame.h"

namespace srp::perception::testing {

constexpr double kTableDepth_m = 0.85;
constexpr double kHandTopDepth_m = 0.75;

inline core::CameraIntrinsics smallCamera() { return {300.0, 300.0, 159.5, 119.5, 320, 240}; }

/// Palm centre pixel of frame i (moves left along a line).
inline cv::Point palmPixel(int i) { return {220 - 4 * i, 110 + i}; }

inline std::vector<rawlog::RgbdFrame> handFrames(int count, int handFrom) {
  std::vector<rawlog::RgbdFrame> frames;
  for (int i = 0; i < count; ++i) {
    rawlog::RgbdFrame f;
    f.index = i;
    f.t_s = i / 30.0;
    f.intrinsics = smallCamera();
    f.colour_bgr8 = cv::Mat(240, 320, CV_8UC3, cv::Scalar(150, 175, 190));  // table, BGR
    f.depth_m = cv::Mat(240, 320, CV_32FC1, cv::Scalar(kTableDepth_m));
    if (i >= handFrom) {
      const cv::Point palm = palmPixel(i);
      const cv::Scalar skin(120, 150, 215);  // BGR of light skin
      cv::rectangle(f.colour_bgr8, cv::Rect(palm.x, palm.y - 12, 320 - palm.x, 24), skin, cv::FILLED);
      cv::rectangle(f.depth_m, cv::Rect(palm.x, palm.y - 12, 320 - palm.x, 24), cv::Scalar(kHandTopDepth_m), cv::FILLED);
      cv::circle(f.colour_bgr8, palm, 28, skin, cv::FILLED);
      cv::circle(f.depth_m, palm, 28, cv::Scalar(kHandTopDepth_m), cv::FILLED);
    }
    frames.push_back(f);
  }
  return frames;
}

}  // namespace srp::perception::testing
