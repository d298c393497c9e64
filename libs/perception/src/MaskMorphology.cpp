#include "srp/perception/MaskMorphology.h"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <type_traits>
#include <opencv2/imgproc.hpp>
#include <string>
#include <vector>

#include "srp/core/Error.h"

namespace srp::perception {
namespace {

/// The largest of a and b, per channel.
template <typename Px>
Px largest(const Px& a, const Px& b) {
  if constexpr (std::is_arithmetic_v<Px>) {
    return std::max(a, b);
  } else {
    Px out;
    for (int c = 0; c < Px::channels; ++c) out[c] = std::max(a[c], b[c]);
    return out;
  }
}

template <typename Px>
void dilateWhereAs(const cv::Mat& src, const std::vector<cv::Point>& offsets, const std::vector<cv::Point>& at,
                   cv::Mat& out) {
  Px lowest;
  if constexpr (std::is_arithmetic_v<Px>) lowest = std::numeric_limits<Px>::lowest();
  else lowest = Px::all(std::numeric_limits<typename Px::value_type>::lowest());
  const int W = src.cols, H = src.rows;
  for (const auto& p : at) {
    Px m = lowest;
    for (const auto& d : offsets) {
      const int x = p.x + d.x, y = p.y + d.y;
      if (x >= 0 && x < W && y >= 0 && y < H) m = largest(m, src.ptr<Px>(y)[x]);
    }
    out.at<Px>(p) = m;
  }
}

}  // namespace

cv::Mat dilateWhere(const cv::Mat& src, const cv::Mat& element, const cv::Mat& where) {
  core::require(where.type() == CV_8UC1 && where.size() == src.size(),
                "dilateWhere: `where` must be CV_8UC1 of the image's size (" + std::to_string(src.cols) + "x" +
                    std::to_string(src.rows) + ")");
  core::require(element.type() == CV_8UC1 && !element.empty(), "dilateWhere: the element must be CV_8UC1, not empty");
  const cv::Point anchor(element.cols / 2, element.rows / 2);
  std::vector<cv::Point> offsets;  // of the element's pixels from the anchor
  for (int r = 0; r < element.rows; ++r)
    for (int c = 0; c < element.cols; ++c)
      if (element.at<uchar>(r, c)) offsets.emplace_back(c - anchor.x, r - anchor.y);
  cv::Mat out(src.size(), src.type(), cv::Scalar::all(0));
  std::vector<cv::Point> at;
  cv::findNonZero(where, at);
  switch (src.type()) {
    case CV_32FC1: dilateWhereAs<float>(src, offsets, at, out); break;
    case CV_16UC1: dilateWhereAs<std::uint16_t>(src, offsets, at, out); break;
    case CV_8UC1: dilateWhereAs<uchar>(src, offsets, at, out); break;
    case CV_8UC3: dilateWhereAs<cv::Vec3b>(src, offsets, at, out); break;
    default:
      throw core::InvalidInputError("dilateWhere: image type " + std::to_string(src.type()) +
                                    " is none of CV_32FC1, CV_16UC1, CV_8UC1, CV_8UC3");
  }
  return out;
}

cv::Mat regionsReachingBorder(const cv::Mat& mask, int margin_px) {
  core::require(mask.type() == CV_8UC1 && margin_px >= 0,
                "regionsReachingBorder: the mask must be CV_8UC1 and margin_px >= 0");
  const int W = mask.cols, H = mask.rows;
  // floodFill's mask: 1 px wider on every side; a filled pixel is 255 there.
  cv::Mat filled(H + 2, W + 2, CV_8UC1, cv::Scalar(0));
  cv::Mat in = mask != 0;  // 255 in, 0 out: one value per region for the flood
  const int flags = 8 | cv::FLOODFILL_MASK_ONLY | (255 << 8);
  auto seed = [&](int u, int v) {
    if (in.ptr<uchar>(v)[u] && !filled.ptr<uchar>(v + 1)[u + 1])
      cv::floodFill(in, filled, {u, v}, cv::Scalar(), nullptr, cv::Scalar(), cv::Scalar(), flags);
  };
  const int m = std::min(margin_px, std::max(W, H));
  for (int v = 0; v < H; ++v) {
    if (v <= m || v >= H - 1 - m) {
      for (int u = 0; u < W; ++u) seed(u, v);
    } else {
      for (int u = 0; u <= std::min(m, W - 1); ++u) seed(u, v);
      for (int u = std::max(0, W - 1 - m); u < W; ++u) seed(u, v);
    }
  }
  return filled(cv::Rect(1, 1, W, H)).clone();
}

}  // namespace srp::perception
