#pragma once
// The size an image file declares in its header, read before decoding it
// (private to libs/calib; the reader is srp/calib/ImageHeader.h's readImageSize):
// a small file whose header claims a huge image is refused before any pixel
// buffer is allocated.
#include <opencv2/core.hpp>
#include <optional>
#include <string>

namespace srp::calib::detail {

/// Width x height declared by a PNG, JPEG, BMP, PNM or TIFF file (readImageSize);
/// nullopt when the file cannot be opened, is none of these or its header is cut short.
std::optional<cv::Size> imageSizeFromHeader(const std::string& path);

}  // namespace srp::calib::detail
