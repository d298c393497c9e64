#include "srp/execution/CellDescription.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "srp/execution/DmpPathGenerator.h"

using srp::core::Pose3;
using namespace srp::execution;

namespace {
constexpr double kHeightTol_m = 1e-9;  // the rule is exact arithmetic on the boxes

CellObject part(const std::string& name, const Eigen::Vector3d& size_m, const Eigen::Vector2d& at_m) {
  CellObject o;
  o.name = name;
  o.kind = CellObjectKind::Part;
  o.size_m = size_m;
  o.X_world_object.translation() = Eigen::Vector3d(at_m.x(), at_m.y(), 0.0);
  return o;
}

CellObject container(const std::string& name, const Eigen::Vector3d& size_m, const Eigen::Vector2d& at_m,
                     double yaw_rad) {
  CellObject o = part(name, size_m, at_m);
  o.kind = CellObjectKind::Container;
  o.X_world_object.linear() = Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  return o;
}
}  // namespace

// Known geometry: a bin 14.9 cm high (turned 30 deg about z: its walls' top does not
// change) and a 6 cm box; a 18.8 cm toy and a 3 cm cube. A Move crosses at the highest
// wall top + the tallest part + 2 cm, whichever part it carries.
TEST(CellDescription, CarryHeightIsTheHighestWallPlusTheTallestPartPlusTheClearance) {
  CellDescription cell;
  EXPECT_EQ(cell.carryHeight_m(), 0.0) << "no container: no wall to clear";
  cell.objects.push_back(part("cube", {0.03, 0.03, 0.03}, {0.1, 0.2}));
  EXPECT_EQ(cell.carryHeight_m(), 0.0) << "parts alone: no wall to clear";
  cell.objects.push_back(container("box", {0.2, 0.2, 0.06}, {-0.2, 0.1}, 0.0));
  EXPECT_NEAR(cell.carryHeight_m(), 0.06 + 0.03 + CellDescription::kCarriedAboveWalls_m, kHeightTol_m);
  cell.objects.push_back(container("bin", {0.40, 0.31, 0.149}, {0.3, -0.1}, 30.0 * M_PI / 180.0));
  cell.objects.push_back(part("toy", {0.22, 0.13, 0.188}, {0.0, -0.2}));
  EXPECT_NEAR(cell.carryHeight_m(), 0.149 + 0.188 + 0.02, kHeightTol_m);
  EXPECT_NEAR(cell.carryHeight_m(0.05), 0.149 + 0.188 + 0.05, kHeightTol_m);
  // A container standing on something (its bottom 0.1 m up): its walls' top counts where it is.
  cell.objects[1].X_world_object.translation().z() = 0.1;
  EXPECT_NEAR(cell.carryHeight_m(), 0.1 + 0.06 + 0.188 + 0.02, kHeightTol_m);
}

// The default scene (6 cm walls, parts of at most 3 cm) crosses below the learned
// paths' default end height, so `srp execute` keeps its Moves there unchanged.
TEST(CellDescription, TheDefaultSceneCrossesAtTheDefaultEndHeight) {
  const CellDescription cell = CellDescription::loadScene();
  EXPECT_GT(cell.carryHeight_m(), 0.0);
  EXPECT_LE(cell.carryHeight_m(), DmpPathGenerator::kDefaultEndHeight_m);
}
