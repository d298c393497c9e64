// dilateWhere and regionsReachingBorder against the OpenCV calls they stand for, on drawn images.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>
#include <vector>

#include "SyntheticFrames.h"
#include "srp/core/Error.h"
#include "srp/perception/MaskMorphology.h"

namespace srp::perception {
namespace {

/// A drawn background depth: a table and an arm ending in a palm, with a ring of depth holes (0) round
/// the palm (narrow gaps) and a wide band without depth at the left border, as a warped background has.
cv::Mat drawnDepth_m() {
  cv::Mat depth = testing::handFrames(8, 4)[6].depth_m.clone();
  cv::circle(depth, testing::palmPixel(6), 30, cv::Scalar(0.f), 2);
  cv::rectangle(depth, cv::Rect(0, 0, 40, 240), cv::Scalar(0.f), cv::FILLED);
  return depth;
}

/// Noise of each type the detector dilates (every pixel differs from its neighbours, so a missing or
/// extra element pixel shows), of a size that is no multiple of a SIMD width.
std::vector<cv::Mat> images() {
  cv::RNG rng(7);
  std::vector<cv::Mat> out{drawnDepth_m()};
  for (const int type : {CV_8UC1, CV_8UC3, CV_16UC1, CV_32FC1}) {
    cv::Mat im(61, 83, type);
    rng.fill(im, cv::RNG::UNIFORM, 0, CV_MAT_DEPTH(type) == CV_32F ? 3.0 : 250.0);
    out.push_back(im);
  }
  return out;
}

TEST(MaskMorphology, DilateWhereIsTheDilationThere) {
  cv::RNG rng(11);
  for (const auto& im : images())
    for (const int d : {1, 2, 3, 5, 7, 10, 11}) {
      const cv::Mat disc = cv::getStructuringElement(cv::MORPH_ELLIPSE, {d, d});
      cv::Mat where(im.size(), CV_8UC1);
      rng.fill(where, cv::RNG::UNIFORM, 0, 2);
      where.row(0).setTo(1);  // the border rows and columns, where the element reaches outside
      where.col(im.cols - 1).setTo(1);
      cv::Mat expected;
      cv::dilate(im, expected, disc);
      expected.setTo(cv::Scalar::all(0), where == 0);
      const cv::Mat got = dilateWhere(im, disc, where);
      ASSERT_EQ(got.type(), im.type());
      EXPECT_EQ(cv::norm(got, expected, cv::NORM_INF), 0.0) << "type " << im.type() << ", diameter " << d << " px";
    }
}

TEST(MaskMorphology, DilateWhereRefusesAMaskOfAnotherSize) {
  const cv::Mat im = drawnDepth_m();
  EXPECT_THROW(dilateWhere(im, cv::Mat::ones(3, 3, CV_8UC1), cv::Mat::ones(10, 10, CV_8UC1)), core::InvalidInputError);
}

/// The components whose bounding box comes within `m` of the border (cv::connectedComponentsWithStats).
cv::Mat componentsAtBorder(const cv::Mat& mask, int m) {
  cv::Mat labels, stats, centroids;
  cv::connectedComponentsWithStats(mask, labels, stats, centroids, 8, CV_32S);
  cv::Mat out(mask.size(), CV_8UC1, cv::Scalar(0));
  for (int v = 0; v < mask.rows; ++v)
    for (int u = 0; u < mask.cols; ++u) {
      const int l = labels.at<int>(v, u);
      if (l == 0) continue;
      const int x = stats.at<int>(l, cv::CC_STAT_LEFT), y = stats.at<int>(l, cv::CC_STAT_TOP);
      const int w = stats.at<int>(l, cv::CC_STAT_WIDTH), h = stats.at<int>(l, cv::CC_STAT_HEIGHT);
      if (x <= m || y <= m || x + w >= mask.cols - m || y + h >= mask.rows - m) out.at<uchar>(v, u) = 255;
    }
  return out;
}

TEST(MaskMorphology, RegionsReachingBorderAreTheComponentsThere) {
  // Drawn: the arm's frame above the table's height band (the arm reaches the right border, the band
  // without depth the left one), plus islands 0-4 px from each border and in the middle.
  const cv::Mat depth = drawnDepth_m();
  cv::Mat drawn = (depth < 0.8f) | (depth <= 0.f);
  for (int gap = 0; gap <= 4; ++gap) {
    cv::rectangle(drawn, cv::Rect(60 + 20 * gap, gap, 6, 6), cv::Scalar(255), cv::FILLED);
    cv::rectangle(drawn, cv::Rect(60 + 20 * gap, drawn.rows - 6 - gap, 6, 6), cv::Scalar(255), cv::FILLED);
  }
  cv::circle(drawn, {150, 200}, 5, cv::Scalar(7), cv::FILLED);  // another non-zero value counts as in
  cv::line(drawn, {100, 100}, {110, 110}, cv::Scalar(255));      // diagonal: 8-connected
  cv::RNG rng(3);
  cv::Mat noise(47, 71, CV_8UC1);
  rng.fill(noise, cv::RNG::UNIFORM, 0, 4);  // a quarter of the pixels set, in many small regions
  noise = noise == 0;
  for (const auto& mask : {drawn, noise})
    for (const int m : {0, 1, 2, 5}) {
      const cv::Mat expected = componentsAtBorder(mask, m), got = regionsReachingBorder(mask, m);
      ASSERT_GT(cv::countNonZero(expected), 0);
      EXPECT_LT(cv::countNonZero(expected), cv::countNonZero(mask));  // some regions left out
      EXPECT_EQ(cv::norm(got, expected, cv::NORM_INF), 0.0) << "margin " << m << " px";
    }
}

}  // namespace
}  // namespace srp::perception
