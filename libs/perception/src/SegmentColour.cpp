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

namespace {
enum Word { kRed, kOrange, kYellow, kGreen, kCyan, kBlue, kPurple, kPink, kBrown, kBlack, kWhite, kGray };
bool chromatic(int w) { return w != kBlack && w != kWhite && w != kGray; }
}  // namespace

const std::array<std::string, kColourWordCount>& colourWords() {
  static const std::array<std::string, kColourWordCount> kWords{"red",  "orange", "yellow", "green", "cyan",  "blue",
                                                                "purple", "pink", "brown",  "black", "white", "gray"};
  return kWords;
}

int colourWordIndex(const cv::Vec3b& bgr) {
  const int b = bgr[0], g = bgr[1], r = bgr[2];
  const int maxc = std::max({r, g, b}), minc = std::min({r, g, b});
  const double value = maxc / 255.0;
  const double saturation = maxc > 0 ? static_cast<double>(maxc - minc) / maxc : 0.0;
  if (value < 0.18) return kBlack;
  if (saturation < 0.2 || maxc - minc < 20) return value > 0.8 ? kWhite : kGray;
  double hue = 0.0;  // degrees
  if (maxc == r) hue = 60.0 * (g - b) / (maxc - minc);
  else if (maxc == g) hue = 60.0 * (2.0 + static_cast<double>(b - r) / (maxc - minc));
  else hue = 60.0 * (4.0 + static_cast<double>(r - g) / (maxc - minc));
  if (hue < 0) hue += 360.0;
  if (hue < 15 || hue >= 340) return saturation < 0.45 && value > 0.7 ? kPink : kRed;
  if (hue < 45) return value < 0.5 ? kBrown : kOrange;
  if (hue < 70) return value < 0.45 ? kBrown : kYellow;
  if (hue < 165) return kGreen;
  if (hue < 195) return kCyan;
  if (hue < 260) return kBlue;
  if (hue < 290) return kPurple;
  return kPink;
}

ColourShares colourShares(const std::vector<cv::Point>& pixels, const cv::Mat& colour_bgr8) {
  ColourShares shares{};
  if (pixels.empty()) return shares;
  for (const auto& p : pixels) shares[static_cast<std::size_t>(colourWordIndex(colour_bgr8.at<cv::Vec3b>(p)))] += 1.0f;
  for (auto& s : shares) s /= static_cast<float>(pixels.size());
  return shares;
}

namespace {
// Each word's share spread half to the words a camera confuses it with
// (lighting, white balance, a pixel at the boundary of two words).
ColourShares spread(const ColourShares& a) {
  static const std::vector<std::vector<int>> kNeighbours = {
      {kOrange, kPink, kBrown}, {kRed, kYellow, kBrown}, {kOrange, kGreen}, {kYellow, kCyan},
      {kGreen, kBlue},          {kCyan, kPurple},        {kBlue, kPink},    {kRed, kPurple},
      {kOrange, kRed, kGray, kBlack}, {kGray, kBrown},   {kGray},           {kWhite, kBlack, kBrown}};
  ColourShares out{};
  double total = 0.0;
  for (int i = 0; i < kColourWordCount; ++i) {
    const double share = a[static_cast<std::size_t>(i)];
    out[static_cast<std::size_t>(i)] += static_cast<float>(share);
    for (int j : kNeighbours[static_cast<std::size_t>(i)])
      out[static_cast<std::size_t>(j)] += static_cast<float>(0.5 * share / kNeighbours[static_cast<std::size_t>(i)].size());
    total += 1.5 * share;
  }
  if (total > 0)
    for (auto& v : out) v = static_cast<float>(v / total);
  return out;
}
}  // namespace

double colourSimilarity(const ColourShares& a, const ColourShares& b) {
  const ColourShares sa = spread(a), sb = spread(b);
  double s = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) s += std::min(sa[i], sb[i]);
  return s;
}

double shareOf(const ColourShares& shares, const std::string& word) {
  const std::string w = word == "grey" ? "gray" : word;
  const auto& words = colourWords();
  const auto it = std::find(words.begin(), words.end(), w);
  return it == words.end() ? 0.0 : shares[static_cast<std::size_t>(it - words.begin())];
}

std::string dominantColourWord(const ColourShares& shares, double minChromaticShare) {
  int best = 0, bestChromatic = -1;
  for (int i = 0; i < kColourWordCount; ++i) {
    if (shares[static_cast<std::size_t>(i)] > shares[static_cast<std::size_t>(best)]) best = i;
    if (chromatic(i) && (bestChromatic < 0 || shares[static_cast<std::size_t>(i)] > shares[static_cast<std::size_t>(bestChromatic)]))
      bestChromatic = i;
  }
  if (bestChromatic >= 0 && shares[static_cast<std::size_t>(bestChromatic)] >= minChromaticShare)
    return colourWords()[static_cast<std::size_t>(bestChromatic)];
  return colourWords()[static_cast<std::size_t>(best)];
}

}  // namespace srp::perception
