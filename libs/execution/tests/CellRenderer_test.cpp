#include "srp/execution/CellRenderer.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <mrpt/img/CImage.h>

using namespace srp::execution;

namespace {

mrpt::img::CImage renderGrey(CellRenderer& renderer, const Eigen::Matrix<double, 6, 1>& q_rad, const std::string& name) {
  CellSnapshot snap;
  snap.q_rad = q_rad;
  const std::string path = std::string(SRP_BINARY_DIR) + "/" + name;
  std::filesystem::remove(path);
  renderer.renderPng(snap, path);
  mrpt::img::CImage img;
  EXPECT_TRUE(img.loadFromFile(path)) << path;
  return img.grayscale();
}

/// Fraction of pixels whose grey level differs by more than kGreyStep.
double changedFraction(const mrpt::img::CImage& a, const mrpt::img::CImage& b) {
  constexpr int kGreyStep = 30;
  std::size_t changed = 0;
  for (std::size_t v = 0; v < a.getHeight(); ++v)
    for (std::size_t u = 0; u < a.getWidth(); ++u)
      if (std::abs(int(*a(u, v)) - int(*b(u, v))) > kGreyStep) ++changed;
  return double(changed) / double(a.getWidth() * a.getHeight());
}

}  // namespace

// The renderer draws the cell at the requested size, the same snapshot twice the same
// way, and the arm where the joints put it: turning the shoulder changes a part of the
// image (the arm) and leaves the rest (table, boxes, parts) as it was.
TEST(CellRenderer, DrawsTheArmWhereTheJointsPutIt) {
  const auto cell = CellDescription::loadScene();
  CellRendererOptions options;
  options.width_px = 320;
  options.height_px = 240;
  CellRenderer renderer(RobotModel::defaultUr5(), cell, options);
  Eigen::Matrix<double, 6, 1> q_home, q_turned;
  q_home << -1.57, -1.6, 1.6, -1.57, -1.57, 0.0;
  q_turned = q_home;
  q_turned(0) += 1.2;  // shoulder pan [rad]

  const auto home = renderGrey(renderer, q_home, "cell_renderer_home.png");
  const auto again = renderGrey(renderer, q_home, "cell_renderer_home_again.png");
  const auto turned = renderGrey(renderer, q_turned, "cell_renderer_turned.png");
  ASSERT_EQ(home.getWidth(), 320u);
  ASSERT_EQ(home.getHeight(), 240u);

  // Not a blank image: the scene has contrast.
  std::size_t minGrey = 255, maxGrey = 0;
  for (std::size_t v = 0; v < home.getHeight(); ++v)
    for (std::size_t u = 0; u < home.getWidth(); ++u) {
      minGrey = std::min<std::size_t>(minGrey, *home(u, v));
      maxGrey = std::max<std::size_t>(maxGrey, *home(u, v));
    }
  EXPECT_GT(maxGrey - minGrey, 100u);

  EXPECT_EQ(changedFraction(home, again), 0.0);  // deterministic
  const double moved = changedFraction(home, turned);
  constexpr double kMinArmFraction = 0.01, kMaxArmFraction = 0.4;  // the arm is part of the image, not all of it
  EXPECT_GT(moved, kMinArmFraction);
  EXPECT_LT(moved, kMaxArmFraction);
}
