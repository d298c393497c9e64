#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>

#include "srp/core/Error.h"
#include "srp/plot/Figure.h"

using namespace srp::plot;

namespace {
// Pixels of exactly this BGR colour in the image.
int countColour(const cv::Mat& img, const Color& c) {
  int n = 0;
  for (int r = 0; r < img.rows; ++r)
    for (int k = 0; k < img.cols; ++k) {
      const auto& p = img.at<cv::Vec3b>(r, k);
      n += (p[0] == c.b && p[1] == c.g && p[2] == c.r);
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
  ax.verticalLine(5.0, "grasp", Color{0, 0, 0});
  fig.axes(1, 0).scatter(t, c, "cos", Color::tab(3), Marker::Square, 3);
  const auto png = fig.encodePng();
  const cv::Mat img = cv::imdecode(png, cv::IMREAD_COLOR);
  ASSERT_EQ(img.cols, 640);
  ASSERT_EQ(img.rows, 480);
  // A 10 s sine across ~550 px of axes at 2 px width: several hundred pixels of its colour.
  EXPECT_GT(countColour(img, Color::tab(0)), 300);
  // 101 filled 7x7 squares.
  EXPECT_GT(countColour(img, Color::tab(3)), 101 * 20);
  const std::string path = (std::filesystem::temp_directory_path() / "srp_plot_test.png").string();
  fig.save(path);
  EXPECT_GT(std::filesystem::file_size(path), 1000u);
  std::filesystem::remove(path);
}

TEST(Figure, BadInputIsRejected) {
  Axes ax;
  EXPECT_THROW(ax.line({1, 2}, {1}, "bad"), srp::core::InvalidInputError);
  EXPECT_THROW(Figure(10, 10), srp::core::InvalidInputError);
  Figure fig(200, 200);
  EXPECT_THROW(fig.axes(1, 0), srp::core::InvalidInputError);
  EXPECT_THROW(fig.save("/nonexistent/dir/x.png"), srp::core::FileError);
}
