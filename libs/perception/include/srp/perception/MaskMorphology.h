#pragma once
/// \file MaskMorphology.h
/// \brief Image morphology where only some pixels matter: a dilation at the pixels of a mask, and the
/// regions of a mask that reach the image border.

#include <opencv2/core.hpp>

namespace srp::perception {

/// cv::dilate(src, element) (anchor at the element's centre (cols / 2, rows / 2), OpenCV's default
/// border: pixels outside the image take no part) at the pixels where `where` (CV_8UC1, src's size) is non-zero, 0 elsewhere:
/// the same values to the bit, at a cost proportional to those pixels times the element's. For an image
/// whose dilation is needed at a few pixels (a background's narrow gaps). `src`: CV_32FC1, CV_16UC1,
/// CV_8UC1 or CV_8UC3 (per channel).
cv::Mat dilateWhere(const cv::Mat& src, const cv::Mat& element, const cv::Mat& where);

/// The 8-connected regions of `mask` (CV_8UC1, non-zero: in) with a pixel within `margin_px` of the
/// image border (column <= margin_px or >= cols - 1 - margin_px, or the same of the row): 255 there,
/// 0 elsewhere. The same pixels as cv::connectedComponentsWithStats's components whose bounding box
/// comes within margin_px of the border, found by flooding from the border (a cost proportional to
/// the regions reached).
cv::Mat regionsReachingBorder(const cv::Mat& mask, int margin_px);

}  // namespace srp::perception
