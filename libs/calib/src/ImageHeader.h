#pragma once
// The size an image file declares in its header, read before decoding it
// (private to libs/calib): a small file whose header claims a huge image is
// refused before any pixel buffer is allocated.
#include <opencv2/core.hpp>
#include <optional>
#include <string>

namespace srp::calib::detail {

/// Width x height declared by a PNG (IHDR) or JPEG (first SOFn segment) file;
/// nullopt when the file is neither or its header is cut short.
std::optional<cv::Size> imageSizeFromHeader(const std::string& path);

}  // namespace srp::calib::detail
