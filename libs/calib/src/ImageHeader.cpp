#include "srp/calib/ImageHeader.h"

#include "ImageHeader.h"

#include <cctype>
#include <climits>
#include <cstring>
#include <fstream>
#include <vector>

#include "srp/core/Error.h"

namespace srp::calib {
namespace {

std::uint32_t be32(const unsigned char* p) {
  return (std::uint32_t(p[0]) << 24) | (std::uint32_t(p[1]) << 16) | (std::uint32_t(p[2]) << 8) | p[3];
}
std::uint16_t be16(const unsigned char* p) { return static_cast<std::uint16_t>((p[0] << 8) | p[1]); }
std::uint32_t le32(const unsigned char* p) {
  return std::uint32_t(p[0]) | (std::uint32_t(p[1]) << 8) | (std::uint32_t(p[2]) << 16) | (std::uint32_t(p[3]) << 24);
}
std::uint16_t le16(const unsigned char* p) { return static_cast<std::uint16_t>(p[0] | (p[1] << 8)); }

std::optional<ImageSize> jpegSize(std::ifstream& in) {
  in.seekg(2);
  unsigned char m[9];
  for (int guard = 0; guard < 10000 && in.read(reinterpret_cast<char*>(m), 4); ++guard) {
    if (m[0] != 0xFF) return std::nullopt;
    const unsigned char marker = m[1];
    if (marker == 0xFF) {  // fill byte: step one byte
      in.seekg(-3, std::ios::cur);
      continue;
    }
    const std::uint16_t length = be16(m + 2);
    const bool sof = marker >= 0xC0 && marker <= 0xCF && marker != 0xC4 && marker != 0xC8 && marker != 0xCC;
    if (sof) {
      if (!in.read(reinterpret_cast<char*>(m), 5)) return std::nullopt;
      return ImageSize{be16(m + 3), be16(m + 1)};
    }
    if (length < 2) return std::nullopt;
    in.seekg(length - 2, std::ios::cur);
  }
  return std::nullopt;
}

std::optional<ImageSize> pnmSize(std::ifstream& in) {
  in.seekg(2);
  std::int64_t values[2];
  for (auto& v : values) {
    int c = in.get();
    while (c != EOF && (std::isspace(c) || c == '#')) {
      if (c == '#')
        while (c != EOF && c != '\n') c = in.get();
      c = in.get();
    }
    if (c == EOF || !std::isdigit(c)) return std::nullopt;
    v = 0;
    for (int digits = 0; c != EOF && std::isdigit(c) && digits < 12; ++digits, c = in.get()) v = v * 10 + (c - '0');
  }
  return ImageSize{values[0], values[1]};
}

std::optional<ImageSize> tiffSize(std::ifstream& in, bool little) {
  unsigned char b[12];
  in.seekg(4);
  if (!in.read(reinterpret_cast<char*>(b), 4)) return std::nullopt;
  const auto u16 = [little](const unsigned char* p) { return little ? le16(p) : be16(p); };
  const auto u32 = [little](const unsigned char* p) { return little ? le32(p) : be32(p); };
  in.seekg(u32(b));
  if (!in.read(reinterpret_cast<char*>(b), 2)) return std::nullopt;
  const int entries = u16(b);
  std::optional<std::int64_t> width, height;
  for (int i = 0; i < entries && i < 1000; ++i) {
    if (!in.read(reinterpret_cast<char*>(b), 12)) return std::nullopt;
    const int tag = u16(b), type = u16(b + 2);
    const std::int64_t value = type == 3 ? u16(b + 8) : u32(b + 8);  // SHORT or LONG
    if (tag == 256) width = value;
    if (tag == 257) height = value;
  }
  if (!width || !height) return std::nullopt;
  return ImageSize{*width, *height};
}

}  // namespace

std::optional<ImageSize> readImageSize(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw core::FileError(path, "cannot open this image");
  unsigned char h[32] = {};
  in.read(reinterpret_cast<char*>(h), sizeof(h));
  const std::streamsize n = in.gcount();
  in.clear();
  static const unsigned char kPng[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  if (n >= 24 && std::memcmp(h, kPng, 8) == 0 && std::memcmp(h + 12, "IHDR", 4) == 0)
    return ImageSize{be32(h + 16), be32(h + 20)};
  if (n >= 4 && h[0] == 0xFF && h[1] == 0xD8) return jpegSize(in);
  if (n >= 26 && h[0] == 'B' && h[1] == 'M') {
    const std::int32_t height = static_cast<std::int32_t>(le32(h + 22));
    return ImageSize{static_cast<std::int32_t>(le32(h + 18)), height < 0 ? -std::int64_t(height) : height};
  }
  if (n >= 3 && h[0] == 'P' && h[1] >= '1' && h[1] <= '6') return pnmSize(in);
  if (n >= 8 && ((h[0] == 'I' && h[1] == 'I' && h[2] == 42) || (h[0] == 'M' && h[1] == 'M' && h[3] == 42)))
    return tiffSize(in, h[0] == 'I');
  return std::nullopt;
}

ImageSize checkImageFile(const std::string& path, std::int64_t maxPixels) {
  const std::optional<ImageSize> size = readImageSize(path);
  if (!size)
    throw core::FileError(path, "not a PNG, JPEG, BMP, PNM or TIFF image whose size can be read before decoding; "
                                "convert it to PNG");
  if (size->width_px <= 0 || size->height_px <= 0 || size->width_px > maxPixels || size->height_px > maxPixels ||
      size->width_px * size->height_px > maxPixels)
    throw core::FileError(path, "the image declares " + std::to_string(size->width_px) + " x " +
                                    std::to_string(size->height_px) + " px, outside the limit of " +
                                    std::to_string(maxPixels / 1000000) +
                                    " MP (a damaged file, or a decompression bomb); it was not decoded");
  return *size;
}

namespace detail {

std::optional<cv::Size> imageSizeFromHeader(const std::string& path) {
  if (!std::ifstream(path, std::ios::binary)) return std::nullopt;
  const std::optional<ImageSize> size = readImageSize(path);
  if (!size || size->width_px <= 0 || size->height_px <= 0 || size->width_px > INT_MAX || size->height_px > INT_MAX)
    return std::nullopt;
  return cv::Size(static_cast<int>(size->width_px), static_cast<int>(size->height_px));
}

}  // namespace detail

}  // namespace srp::calib
