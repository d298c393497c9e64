#include "srp/execution/CellRenderer.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

using namespace srp::execution;

TEST(CellRenderer, RendersTheDefaultCellToAPng) {
  const auto scene = srp::core::Scene::load(std::string(SRP_SIM_DIR) + "/scenes/default.json");
  const auto cell = CellDescription::fromScene(scene, srp::core::ObjectCatalogue::load(scene.cataloguePath));
  CellRenderer renderer(RobotModel::defaultUr5(), cell, CellRendererOptions{});
  CellSnapshot snap;
  snap.q_rad << -1.57, -1.6, 1.6, -1.57, -1.57, 0.0;
  const std::string path = std::string(SRP_BINARY_DIR) + "/cell_renderer_test.png";
  std::filesystem::remove(path);
  renderer.renderPng(snap, path);
  ASSERT_TRUE(std::filesystem::exists(path));
  std::ifstream in(path, std::ios::binary);
  char magic[4] = {};
  in.read(magic, 4);
  EXPECT_EQ(std::string(magic + 1, 3), "PNG");
  EXPECT_GT(std::filesystem::file_size(path), 5000u);  // not a blank image
}
