#pragma once
/// \file RgbdFolder.h
/// \brief Reads a folder of registered RGB-D images (color_NNNN.png or .jpg +
/// depth_NNNN.png, 16-bit depth) with a `cam.json` (px, py, u0, v0, w, h,
/// depthScale), the layout of ViSP's RealSense recordings
/// (datasets/real/visp-rbt-cube).

#include <string>
#include <vector>

#include "srp/rawlog/RgbdFrame.h"

namespace srp::perception {

/// Frames color_0000.png, depth_0000.png, ... in index order, up to maxFrames
/// (0 = all). Depth Z [m] = raw * depthScale; raw 0 = invalid. Throws FileError
/// naming the folder or file when cam.json, a colour/depth pair or a PNG is
/// missing or unreadable, and InvalidInputError when the sizes disagree.
std::vector<rawlog::RgbdFrame> readRgbdFolder(const std::string& folder, int maxFrames = 0);

}  // namespace srp::perception
