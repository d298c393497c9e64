#include "srp/perception/SegmentColour.h"

#include <algorithm>
#include <cstdint>

namespace srp::perception {

cv::Vec3b medianColour(const std::vector<cv::Point>& pixels, const cv::Mat& colour_bgr8) {
  cv::Vec3b median;
  std::vector<std::uint8_t> channel(pixels.size());
  for (int c = 0; c < 3; ++c) {
    for (std::size_t i = 0; i < pixels.size(); ++i) channel[i] = colour_bgr8.at<cv::Vec3b>(pixels[i])[c];
    std::nth_element(channel.begin(), channel.begin() + static_cast<long>(channel.size() / 2), channel.end());
    median[c] = channel[channel.size() / 2];
  }
  return median;
}

}  // namespace srp::perception
