#pragma once
/// \file SegmentColour.h
/// \brief The colour of a segment: the median colour of a part's top face,
/// and the basic colour words its pixels show.

#include <array>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace srp::perception {

/// Per-channel median BGR colour of `pixels` in `colour_bgr8` (non-empty):
/// of a part seen from above, the colour of its top face (side walls, shading
/// and a few background pixels at the outline do not move a median).
cv::Vec3b medianColour(const std::vector<cv::Point>& pixels, const cv::Mat& colour_bgr8);

/// The basic colour words of the instructions (core::rgbOfColourName's, "gray"
/// for both spellings), in the order of ColourShares.
constexpr int kColourWordCount = 12;
const std::array<std::string, kColourWordCount>& colourWords();

/// Index in colourWords() of the word that names one pixel of a camera image,
/// from its hue, saturation and value (8-bit HSV): dark -> black; unsaturated
/// -> white or gray by value; else the hue's word (an orange hue when dark is
/// brown, a red one when pale is pink). Camera images (8-bit sRGB), not the
/// catalogue's linear RGB.
int colourWordIndex(const cv::Vec3b& bgr);

/// Share [0, 1] of each colour word among a segment's pixels (sums to 1).
using ColourShares = std::array<float, kColourWordCount>;

/// The shares of `pixels` in `colour_bgr8`; all zero for no pixel.
ColourShares colourShares(const std::vector<cv::Point>& pixels, const cv::Mat& colour_bgr8);

/// Histogram intersection [0, 1] of two share vectors (1 = the same colours),
/// each word's share first spread half to the words a camera confuses it
/// with (gray-white-black-brown, orange-red-yellow-brown, blue-cyan-purple...).
double colourSimilarity(const ColourShares& a, const ColourShares& b);

/// Share of `word` ("grey" = "gray"); 0 for a word that is not a basic colour.
double shareOf(const ColourShares& shares, const std::string& word);

/// The word naming a segment: the chromatic word with the largest share when
/// that share reaches `minChromaticShare` (a blue toy with a beige face is
/// "blue"), else the largest share's word.
std::string dominantColourWord(const ColourShares& shares, double minChromaticShare = 0.25);

}  // namespace srp::perception
