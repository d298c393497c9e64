#pragma once
/// \file SegmentColour.h
/// \brief The colour of a part's top face from its depth segment.

#include <opencv2/core.hpp>
#include <vector>

namespace srp::perception {

/// Per-channel median BGR colour of `pixels` in `colour_bgr8` (non-empty):
/// of a part seen from above, the colour of its top face (side walls, shading
/// and a few background pixels at the outline do not move a median).
cv::Vec3b medianColour(const std::vector<cv::Point>& pixels, const cv::Mat& colour_bgr8);

}  // namespace srp::perception
