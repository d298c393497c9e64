#pragma once
// Test frames for the rawlog tests: the same frame for the same arguments.
#include <opencv2/core.hpp>

#include <cstdint>

#include "srp/core/CameraIntrinsics.h"
#include "srp/rawlog/RgbdFrame.h"

namespace srp::rawlog::testing {

/// Frame `index` at t = 1.7e9 s + index / 30 s with intrinsics K: uniformly
/// random BGR colour (cv::RNG seeded with `colourSeed`) and depth
/// depthAt_m(row, col) [m] (0: invalid).
template <class DepthAt>
RgbdFrame testFrame(int index, const core::CameraIntrinsics& K, std::uint64_t colourSeed, DepthAt depthAt_m) {
  RgbdFrame f;
  f.index = index;
  f.t_s = 1700000000.0 + index / 30.0;
  f.intrinsics = K;
  f.colour_bgr8 = cv::Mat(K.height_px, K.width_px, CV_8UC3);
  cv::RNG rng(colourSeed);
  rng.fill(f.colour_bgr8, cv::RNG::UNIFORM, cv::Scalar::all(0), cv::Scalar::all(256));
  f.depth_m = cv::Mat(K.height_px, K.width_px, CV_32FC1);
  for (int r = 0; r < f.depth_m.rows; ++r)
    for (int c = 0; c < f.depth_m.cols; ++c) f.depth_m.at<float>(r, c) = depthAt_m(r, c);
  return f;
}

}  // namespace srp::rawlog::testing
