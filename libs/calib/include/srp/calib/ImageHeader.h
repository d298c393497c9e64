#pragma once
/// \file ImageHeader.h
/// \brief An image file's pixel size from its header, read before the image is
/// decoded: a small compressed file (a PNG of one colour, a JPEG with a forged
/// size) can decode to gigabytes, so a reader checks the size against its
/// limit first (checkImageFile()).
///
/// Formats: PNG (IHDR), JPEG (the first SOFn marker), BMP, PNM (P1-P6), TIFF
/// (the first IFD's ImageWidth/ImageLength). Other formats are refused by
/// checkImageFile(): it cannot bound what it cannot read.
///
/// \code
///   srp::calib::checkImageFile(path, 50'000'000);   // throws FileError above 50 MP
///   const cv::Mat image = cv::imread(path, cv::IMREAD_COLOR);
/// \endcode

#include <cstdint>
#include <optional>
#include <string>

namespace srp::calib {

/// Width and height [px] of an image file.
struct ImageSize {
  std::int64_t width_px = 0;
  std::int64_t height_px = 0;
};

/// The size from the file's header, or nullopt when the format is none of the
/// above or the header is cut short. Throws FileError when the file cannot be opened.
std::optional<ImageSize> readImageSize(const std::string& path);

/// Default bound on the pixels of an image srp decodes from a user's file
/// (50 MP: a 8192 x 6144 camera; a decoded 8-bit BGR image of that size is 150 MB).
constexpr std::int64_t kMaxImagePixels = 50'000'000;

/// Throws FileError naming the file, its size and the limit when its header
/// gives more than `maxPixels` pixels (or a zero size), or when its format's
/// header cannot be read; returns the size otherwise.
ImageSize checkImageFile(const std::string& path, std::int64_t maxPixels = kMaxImagePixels);

}  // namespace srp::calib
