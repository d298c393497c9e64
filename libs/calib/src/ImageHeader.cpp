#include "ImageHeader.h"

#include <array>
#include <fstream>

namespace srp::calib::detail {

namespace {

// A JPEG header is read at most this far for its SOF segment (EXIF
// thumbnails come before it; 1 MB is far beyond any camera's).
constexpr std::streamoff kMaxJpegHeaderScan_bytes = 1 << 20;

unsigned be16(const unsigned char* p) { return (static_cast<unsigned>(p[0]) << 8) | p[1]; }
unsigned long be32(const unsigned char* p) {
  return (static_cast<unsigned long>(p[0]) << 24) | (static_cast<unsigned long>(p[1]) << 16) |
         (static_cast<unsigned long>(p[2]) << 8) | p[3];
}

std::optional<cv::Size> pngSize(std::ifstream& in) {
  std::array<unsigned char, 24> h{};
  in.seekg(0);
  if (!in.read(reinterpret_cast<char*>(h.data()), h.size())) return std::nullopt;
  static const unsigned char kSignature[8] = {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A};
  for (int i = 0; i < 8; ++i)
    if (h[i] != kSignature[i]) return std::nullopt;
  if (h[12] != 'I' || h[13] != 'H' || h[14] != 'D' || h[15] != 'R') return std::nullopt;
  const unsigned long w = be32(&h[16]), ht = be32(&h[20]);
  if (w == 0 || ht == 0 || w > 0x7fffffffUL || ht > 0x7fffffffUL) return std::nullopt;
  return cv::Size(static_cast<int>(w), static_cast<int>(ht));
}

std::optional<cv::Size> jpegSize(std::ifstream& in) {
  in.seekg(0);
  unsigned char soi[2];
  if (!in.read(reinterpret_cast<char*>(soi), 2) || soi[0] != 0xFF || soi[1] != 0xD8) return std::nullopt;
  while (in && in.tellg() < kMaxJpegHeaderScan_bytes) {
    int c = in.get();
    if (c != 0xFF) return std::nullopt;
    do c = in.get();
    while (c == 0xFF);  // fill bytes
    if (c == EOF) return std::nullopt;
    const int marker = c;
    if (marker == 0x01 || (marker >= 0xD0 && marker <= 0xD7)) continue;  // no length
    unsigned char len[2];
    if (!in.read(reinterpret_cast<char*>(len), 2)) return std::nullopt;
    const unsigned length = be16(len);
    if (length < 2) return std::nullopt;
    const bool sof = marker >= 0xC0 && marker <= 0xCF && marker != 0xC4 && marker != 0xC8 && marker != 0xCC;
    if (sof) {
      unsigned char f[5];
      if (length < 7 || !in.read(reinterpret_cast<char*>(f), 5)) return std::nullopt;
      const unsigned h = be16(&f[1]), w = be16(&f[3]);
      if (w == 0 || h == 0) return std::nullopt;
      return cv::Size(static_cast<int>(w), static_cast<int>(h));
    }
    in.seekg(length - 2, std::ios::cur);
  }
  return std::nullopt;
}

}  // namespace

std::optional<cv::Size> imageSizeFromHeader(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  if (const auto s = pngSize(in)) return s;
  in.clear();
  return jpegSize(in);
}

}  // namespace srp::calib::detail
