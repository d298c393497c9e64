#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>

#include "srp/core/Error.h"
#include "srp/plot/Figure.h"

using namespace srp::plot;

namespace {
// Pixels of this BGR colour in the image (each channel within `tol` levels).
int countColour(const cv::Mat& img, const Colour& c, int tol = 0) {
  int n = 0;
  for (int r = 0; r < img.rows; ++r)
    for (int k = 0; k < img.cols; ++k) {
      const auto& p = img.at<cv::Vec3b>(r, k);
      n += (std::abs(p[0] - c.b) <= tol && std::abs(p[1] - c.g) <= tol && std::abs(p[2] - c.r) <= tol);
    }
  return n;
}
}  // namespace

TEST(Figure, DrawsSeriesInTheirColoursAndWritesPng) {
  Figure fig(640, 480, 2, 1);
  fig.title = "test";
  std::vector<double> t, s, c;
  for (int i = 0; i <= 100; ++i) {
    t.push_back(i * 0.1);
    s.push_back(std::sin(i * 0.1));
    c.push_back(std::cos(i * 0.1));
  }
  auto& ax = fig.axes(0, 0);
  ax.title = "sine";
  ax.xLabel = "t [s]";
  ax.yLabel = "y [m]";
  ax.line(t, s, "sin");
  ax.verticalLine(5.0, "grasp", Colour{0, 0, 0});
  fig.axes(1, 0).scatter(t, c, "cos", Colour::tab(3), Marker::Square, 3);
  const auto png = fig.encodePng();
  const cv::Mat img = cv::imdecode(png, cv::IMREAD_COLOR);
  ASSERT_EQ(img.cols, 640);
  ASSERT_EQ(img.rows, 480);
  // A 10 s sine across ~550 px of axes at 2 px width: several hundred pixels of its colour.
  EXPECT_GT(countColour(img, Colour::tab(0)), 300);
  // 101 filled 7x7 squares.
  EXPECT_GT(countColour(img, Colour::tab(3)), 101 * 20);
  const std::string path = (std::filesystem::temp_directory_path() / "srp_plot_test.png").string();
  fig.save(path);
  EXPECT_GT(std::filesystem::file_size(path), 1000u);
  std::filesystem::remove(path);
}

TEST(Figure, BandShadesItsIntervalAndNothingElse) {
  // Axes 0..10 (limits fixed), an opaque band over [2, 4] = a fifth of the plot width,
  // a half-transparent one over [6, 7] that blends with the white background.
  Figure fig(600, 400);
  auto& ax = fig.axes();
  ax.xLimits = std::make_pair(0.0, 10.0);
  ax.yLimits = std::make_pair(0.0, 1.0);
  ax.line({0.0, 10.0}, {0.5, 0.5}, "", Colour::tab(0), 1.0);
  const Colour opaque = Colour::tab(2), half = Colour::tab(3);
  ax.band(2.0, 4.0, "reach", opaque, 1.0);
  ax.band(6.0, 7.0, "", half, 0.5);
  const cv::Mat img = cv::imdecode(fig.encodePng(), cv::IMREAD_COLOR);
  // Plot area as drawAxes lays it out: 70 px left, 15 right, 15 top (no title), 50 bottom.
  const double plotWidth_px = 600 - 70 - 15, plotHeight_px = 400 - 15 - 50;
  const double expected_px = 0.2 * plotWidth_px * plotHeight_px;
  // Grid lines, the data line and the legend swatch cut a few percent out of / into the band.
  constexpr double kAreaTol = 0.08;
  EXPECT_NEAR(countColour(img, opaque), expected_px, kAreaTol * expected_px);
  // 50 % blend with white, to within the rounding of 8-bit arithmetic.
  const Colour blended{(255 + half.r) / 2, (255 + half.g) / 2, (255 + half.b) / 2};
  const double halfArea_px = 0.1 * plotWidth_px * plotHeight_px;
  EXPECT_NEAR(countColour(img, blended, 1), halfArea_px, kAreaTol * halfArea_px);
  // Outside the bands (x = 5, the middle of the gap) the background stays white.
  const int x5 = 70 + static_cast<int>(0.5 * plotWidth_px);
  const auto& p = img.at<cv::Vec3b>(15 + 40, x5);
  EXPECT_EQ(p, cv::Vec3b(255, 255, 255));
}

TEST(Figure, BadInputIsRejected) {
  Axes ax;
  EXPECT_THROW(ax.line({1, 2}, {1}, "bad"), srp::core::InvalidInputError);
  EXPECT_THROW(Figure(10, 10), srp::core::InvalidInputError);
  EXPECT_THROW(ax.band(2.0, 1.0, "reversed"), srp::core::InvalidInputError);
  EXPECT_THROW(ax.band(0.0, 1.0, "too opaque", std::nullopt, 1.5), srp::core::InvalidInputError);
  Figure fig(200, 200);
  EXPECT_THROW(fig.axes(1, 0), srp::core::InvalidInputError);
  EXPECT_THROW(fig.save("/nonexistent/dir/x.png"), srp::core::FileError);
}
