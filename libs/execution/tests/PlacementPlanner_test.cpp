#include "srp/execution/PlacementPlanner.h"
#include "srp/execution/PlacementContext.h"

#include <gtest/gtest.h>

using srp::core::Pose3;
using namespace srp::execution;

namespace {
constexpr double kGeomTol_m = 1e-6;    // exact geometry of a computed pose
constexpr double kGridTol_m = 0.0051;  // one candidate-grid step

Pose3 at(double x, double y, double z = 0.0, double yaw = 0.0) {
  Pose3 X = Pose3::Identity();
  X.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  X.translation() = Eigen::Vector3d(x, y, z);
  return X;
}

CellObject part(const std::string& name, const Eigen::Vector3d& size, const Pose3& X) {
  CellObject o;
  o.name = name;
  o.noun = name;
  o.className = name;
  o.size_m = size;
  o.X_world_object = X;
  return o;
}

/// The default cell's geometry: base at (0, -0.3), camera looking down with image
/// right = world +x (so front = world -y), gray box at (0.16, 0.12).
CellDescription cell() {
  CellDescription c;
  c.X_world_base = at(0.0, -0.3, 0.0, M_PI / 2);
  c.tableHalfExtents_m = Eigen::Vector2d(0.6, 0.4);
  Pose3 cam = Pose3::Identity();
  cam.linear() = Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitX()).toRotationMatrix();
  cam.translation() = Eigen::Vector3d(0.0, 0.1, 0.85);
  c.X_world_camera = cam;
  CellObject box = part("gray box", Eigen::Vector3d(0.22, 0.17, 0.06), at(0.16, 0.12));
  box.kind = CellObjectKind::Container;
  box.noun = "box";
  box.colour = "gray";
  c.objects.push_back(box);
  c.objects.push_back(part("star", Eigen::Vector3d(0.05, 0.05, 0.025), at(-0.15, 0.1)));
  c.objects.push_back(part("octagon", Eigen::Vector3d(0.04, 0.04, 0.025), at(-0.15, -0.05)));
  c.objects.push_back(part("cuboid", Eigen::Vector3d(0.05, 0.03, 0.03), at(0.0, -0.05)));
  return c;
}

ExecutionStep stepOf(const std::string& object, SpatialRelation r) {
  ExecutionStep s;
  s.object = {object, {}};
  s.target.push_back(std::move(r));
  return s;
}

SpatialRelation rel(const std::string& r, const std::string& landmark) { return {r, {landmark, {}}, {}, ""}; }

const CellObject& get(const CellDescription& c, const std::string& name) { return *c.find(name); }

/// The scene after the part is put at its placement.
CellDescription after(CellDescription c, const std::string& name, const Pose3& X) {
  for (auto& o : c.objects)
    if (o.name == name) o.X_world_object = X;
  return c;
}

void expectHolds(const PlacementPlanner& planner, const CellDescription& c, const std::string& name,
                 const ExecutionStep& step, const Placement& p) {
  ASSERT_TRUE(p.X_world_object) << p.reason;
  const CellDescription placed = after(c, name, *p.X_world_object);
  const auto checks = planner.check(placed, get(placed, name), step);
  ASSERT_EQ(checks.size(), step.target.size());
  for (const auto& k : checks) EXPECT_TRUE(k.holds) << k.relation << " " << k.landmarks << ": " << k.detail;
}

}  // namespace

TEST(PlacementPlanner, DirectionsFollowTheCameraView) {
  const CellDescription c = cell();
  const PlacementPlanner planner;
  const Eigen::Vector2d star(-0.15, 0.1);
  // Camera x = world x: right = +x, front (towards the viewer, image down) = -y.
  const std::pair<const char*, Eigen::Vector2d> cases[] = {
      {"left of", {-1, 0}}, {"right of", {1, 0}}, {"in front of", {0, -1}}, {"behind", {0, 1}}};
  for (const auto& [word, d] : cases) {
    const ExecutionStep s = stepOf("cuboid", rel(word, "star"));
    const Placement p = planner.place(c, get(c, "cuboid"), s);
    ASSERT_TRUE(p.X_world_object) << word << ": " << p.reason;
    const Eigen::Vector2d off = p.X_world_object->translation().head<2>() - star;
    // Landmark yaw 0: half-extents along d are exact; gap = neighbourGap_m.
    const double expected = (std::abs(d.x()) > 0 ? 0.025 + 0.025 : 0.025 + 0.015) + planner.options().neighbourGap_m;
    EXPECT_NEAR(off.dot(d), expected, kGeomTol_m) << word;
    EXPECT_NEAR(std::abs(off.dot(Eigen::Vector2d(-d.y(), d.x()))), 0.0, kGeomTol_m) << word;
    EXPECT_NEAR(p.X_world_object->translation().z(), 0.0, kGeomTol_m) << word;
    expectHolds(planner, c, "cuboid", s, *&p);
  }
}

TEST(PlacementPlanner, RobotViewTurnsWithTheRobot) {
  CellDescription c = cell();
  c.X_world_base = at(-0.5, 0.0, 0.0, 0.0);  // robot on the left edge, looking at the table centre along +x
  PlacementContext::Options o;
  o.grounding.viewpoint = srp::core::Viewpoint::Robot;
  const PlacementPlanner planner(o);
  const ExecutionStep s = stepOf("cuboid", rel("left of", "star"));
  const Placement p = planner.place(c, get(c, "cuboid"), s);
  ASSERT_TRUE(p.X_world_object) << p.reason;
  // Looking along +x, left is +y.
  EXPECT_GT(p.X_world_object->translation().y() - 0.1, 0.04);
  EXPECT_NEAR(p.X_world_object->translation().x(), -0.15, kGeomTol_m);
}

TEST(PlacementPlanner, ATakenPlaceShiftsWithClearance) {
  CellDescription c = cell();
  // The octagon sits exactly where "left of the star" would go.
  for (auto& o : c.objects)
    if (o.name == "octagon") o.X_world_object = at(-0.15 - 0.04 - 0.015, 0.1);
  const PlacementPlanner planner;
  const ExecutionStep s = stepOf("cuboid", rel("left of", "star"));
  const Placement p = planner.place(c, get(c, "cuboid"), s);
  ASSERT_TRUE(p.X_world_object) << p.reason;
  const Eigen::Vector2d q = p.X_world_object->translation().head<2>(), oct(-0.205, 0.1);
  // Clear of the octagon's footprint by the clearance (axis-aligned boxes: per-axis gap).
  const double gapX = std::abs(q.x() - oct.x()) - 0.025 - 0.02, gapY = std::abs(q.y() - oct.y()) - 0.015 - 0.02;
  EXPECT_GE(std::max(gapX, gapY), planner.options().clearance_m - 1e-9);
  expectHolds(planner, c, "cuboid", s, p);
}

TEST(PlacementPlanner, BetweenCentresInTheFreeSpace) {
  const CellDescription c = cell();
  const PlacementPlanner planner;
  ExecutionStep s = stepOf("cuboid", rel("between", "star"));
  s.target[0].secondLandmark = ObjectReference{"octagon", {}};
  const Placement p = planner.place(c, get(c, "cuboid"), s);
  ASSERT_TRUE(p.X_world_object) << p.reason;
  // Star (y 0.1, half 0.025) and octagon (y -0.05, half 0.02): free space [-0.03, 0.075], centre 0.0225.
  EXPECT_NEAR(p.X_world_object->translation().x(), -0.15, kGridTol_m);
  EXPECT_NEAR(p.X_world_object->translation().y(), 0.0225, kGridTol_m);
  expectHolds(planner, c, "cuboid", s, p);
}

TEST(PlacementPlanner, BetweenTooCloseIsRefusedWithTheRoom) {
  CellDescription c = cell();
  for (auto& o : c.objects)
    if (o.name == "octagon") o.X_world_object = at(-0.15, 0.1 - 0.025 - 0.02 - 0.02);  // 2 cm apart
  const PlacementPlanner planner;
  ExecutionStep s = stepOf("cuboid", rel("between", "star"));
  s.target[0].secondLandmark = ObjectReference{"octagon", {}};
  const Placement p = planner.place(c, get(c, "cuboid"), s);
  EXPECT_FALSE(p.X_world_object);
  EXPECT_NE(p.reason.find("not enough room between the star and the octagon"), std::string::npos) << p.reason;
  ExecutionStep one = stepOf("cuboid", rel("between", "star"));
  EXPECT_NE(planner.place(c, get(c, "cuboid"), one).reason.find("needs two landmarks"), std::string::npos);
}

TEST(PlacementPlanner, BetweenATightGapCentresThePartNearerThanTheClearance) {
  CellDescription c = cell();
  // Star (y 0.1, half 0.025) and octagon (half 0.02) 41 mm apart: the cuboid's narrow
  // side (30 mm) fits with 5.5 mm each side, less than clearance_m (8 mm).
  for (auto& o : c.objects)
    if (o.name == "octagon") o.X_world_object = at(-0.15, 0.1 - 0.025 - 0.041 - 0.02);
  const PlacementPlanner planner;
  ASSERT_GT(planner.options().clearance_m, 0.0055);
  ExecutionStep s = stepOf("cuboid", rel("between", "star"));
  s.target[0].secondLandmark = ObjectReference{"octagon", {}};
  const Placement p = planner.place(c, get(c, "cuboid"), s);
  ASSERT_TRUE(p.X_world_object) << p.reason;
  EXPECT_NEAR(p.X_world_object->translation().x(), -0.15, kGridTol_m);
  EXPECT_NEAR(p.X_world_object->translation().y(), 0.1 - 0.025 - 0.0205, kGridTol_m);  // the gap's middle
  expectHolds(planner, c, "cuboid", s, p);
  EXPECT_TRUE(p.tight);
  // 33 mm: 1.5 mm each side, below minClearance_m (2 mm): refused, saying so.
  ASSERT_GT(planner.options().minClearance_m, 0.0015);
  for (auto& o : c.objects)
    if (o.name == "octagon") o.X_world_object = at(-0.15, 0.1 - 0.025 - 0.033 - 0.02);
  const Placement tight = planner.place(c, get(c, "cuboid"), s);
  EXPECT_FALSE(tight.X_world_object);
  EXPECT_NE(tight.reason.find("(33.0 mm free along the line between them, 34.0 mm needed"), std::string::npos)
      << tight.reason;
}

TEST(PlacementPlanner, StackingRestsOnTheLowerPartsTop) {
  const CellDescription c = cell();
  const PlacementPlanner planner;
  const ExecutionStep s = stepOf("cuboid", rel("on top of", "octagon"));
  const Placement p = planner.place(c, get(c, "cuboid"), s);
  ASSERT_TRUE(p.X_world_object) << p.reason;
  EXPECT_EQ(p.stackedOn, "octagon");
  EXPECT_NEAR(p.X_world_object->translation().z(), 0.025, kGeomTol_m);
  EXPECT_NEAR((p.X_world_object->translation().head<2>() - Eigen::Vector2d(-0.15, -0.05)).norm(), 0.0, kGeomTol_m);
  expectHolds(planner, c, "cuboid", s, p);
  // "on" a part stacks too; "on" a container puts it inside.
  EXPECT_EQ(planner.place(c, get(c, "cuboid"), stepOf("cuboid", rel("on", "octagon"))).stackedOn, "octagon");
  const Placement inBox = planner.place(c, get(c, "cuboid"), stepOf("cuboid", rel("onto", "box")));
  ASSERT_TRUE(inBox.X_world_object);
  EXPECT_EQ(inBox.container, "gray box");
  // Something already on the octagon: refused, nothing placed.
  const CellDescription taken = after(c, "star", at(-0.15, -0.05, 0.025));
  const Placement refused = planner.place(taken, get(taken, "cuboid"), s);
  EXPECT_FALSE(refused.X_world_object);
  EXPECT_NE(refused.reason.find("the star already lies on the octagon"), std::string::npos) << refused.reason;
}

TEST(PlacementPlanner, NamedCornerOfAContainer) {
  const CellDescription c = cell();
  const PlacementPlanner planner;
  for (const std::string corner : {"front left", "front right", "back left", "back right"}) {
    ExecutionStep s = stepOf("cuboid", rel("in", "box"));
    s.target[0].corner = corner;
    s.target[0].relation = "corner";
    const Placement p = planner.place(c, get(c, "cuboid"), s);
    ASSERT_TRUE(p.X_world_object) << corner << ": " << p.reason;
    const Eigen::Vector2d off = p.X_world_object->translation().head<2>() - Eigen::Vector2d(0.16, 0.12);
    // Inner corner: half size - wall - margin - half part = 0.11-0.006-0.008-0.025 (x), 0.085-0.006-0.008-0.015 (y).
    const double sx = corner.find("left") != std::string::npos ? -1 : 1;
    const double sy = corner.find("front") != std::string::npos ? -1 : 1;
    EXPECT_NEAR(off.x(), sx * 0.071, kGridTol_m) << corner;
    EXPECT_NEAR(off.y(), sy * 0.056, kGridTol_m) << corner;
    expectHolds(planner, c, "cuboid", s, p);
  }
  ExecutionStep bad = stepOf("cuboid", rel("corner", "box"));
  bad.target[0].corner = "left right";
  EXPECT_NE(planner.place(c, get(c, "cuboid"), bad).reason.find("unknown corner"), std::string::npos);
}

TEST(PlacementPlanner, LandmarkInAContainerKeepsThePartInsideTheWalls) {
  CellDescription c = cell();
  // The star against the box's left inner wall: "left of" has no room inside the box.
  c = after(c, "star", at(0.16 - 0.11 + 0.006 + 0.03, 0.12, 0.006));
  const PlacementPlanner planner;
  ExecutionStep inBox = stepOf("cuboid", rel("left of", "star"));
  inBox.target.push_back(rel("in", "box"));
  const Placement refused = planner.place(c, get(c, "cuboid"), inBox);
  EXPECT_FALSE(refused.X_world_object);
  EXPECT_NE(refused.reason.find("no free place left of the star inside the gray box"), std::string::npos)
      << refused.reason;
  // Without the box named: on the table, left of the box's outer wall (plus the wall margin).
  const ExecutionStep left = stepOf("cuboid", rel("left of", "star"));
  const Placement table = planner.place(c, get(c, "cuboid"), left);
  ASSERT_TRUE(table.X_world_object) << table.reason;
  EXPECT_EQ(table.container, "");
  EXPECT_NEAR(table.X_world_object->translation().z(), 0.0, kGeomTol_m);
  EXPECT_LE(table.X_world_object->translation().x() + 0.025, 0.16 - 0.11 - planner.options().wallMargin_m + 1e-9);
  expectHolds(planner, c, "cuboid", left, table);
  // Room inside: the part stays in the box, inside the walls.
  const ExecutionStep right = stepOf("cuboid", rel("right of", "star"));
  const Placement p = planner.place(c, get(c, "cuboid"), right);
  ASSERT_TRUE(p.X_world_object) << p.reason;
  EXPECT_EQ(p.container, "gray box");
  EXPECT_NEAR(p.X_world_object->translation().z(), 0.006, kGeomTol_m);
  expectHolds(planner, c, "cuboid", right, p);
}

TEST(PlacementPlanner, APlaceMustNotOverlapAContainerWall) {
  CellDescription c = cell();
  c = after(c, "star", at(0.16 - 0.11 - 0.03, 0.12));  // 0.5 cm left of the box's outer wall
  const PlacementPlanner planner;
  const ExecutionStep s = stepOf("cuboid", rel("right of", "star"));
  const Placement p = planner.place(c, get(c, "cuboid"), s);
  ASSERT_TRUE(p.X_world_object) << p.reason;
  // Not on the box's left wall (outer face x = 0.05): a table place wholly inside the box
  // rests on its floor, clear of the inner wall (x = 0.056) by the wall margin.
  EXPECT_NEAR(p.X_world_object->translation().z(), 0.006, kGeomTol_m);
  EXPECT_GE(p.X_world_object->translation().x() - 0.025, 0.056 + planner.options().wallMargin_m - 1e-9);
  expectHolds(planner, c, "cuboid", s, p);
}

// The suction tool (a 20 mm cylinder on the part's centre, lowered onto its top) passes
// beside a wall whose top is above the part's top: the centre keeps 20 + 2 mm from that
// wall, on the table (outer outline) and inside the box (inner walls), even where the
// footprint alone would keep its 2 mm; beside a tray lower than the part it need not.
TEST(PlacementPlanner, ToolKeepsItsRadiusFromWallsItComesLevelWith) {
  constexpr double kOuterWall_x = 0.16 - 0.11, kInnerWall_x = kOuterWall_x + 0.006;  // the gray box's left walls
  constexpr double kTooNear_m = 0.020, kFarEnough_m = 0.023;  // centre from the wall; the part's half-width is 15 mm
  CellDescription c = cell();
  const PlacementContext::Options tight =
      PlacementContext::Options{}.tight();  // 2 mm to walls: the footprint alone would fit
  ASSERT_NEAR(tight.toolClearance_m, 0.022, kGeomTol_m);
  const CellObject& cuboid = get(c, "cuboid");  // 50 x 30 x 30 mm, turned: 15 mm towards the wall
  const PlacementContext ctx(c, cuboid, tight);
  const CellObject& box = get(c, "gray box");
  EXPECT_FALSE(ctx.fitsTable(at(kOuterWall_x - kTooNear_m, 0.12, 0.0, M_PI / 2)));
  EXPECT_TRUE(ctx.fitsTable(at(kOuterWall_x - kFarEnough_m, 0.12, 0.0, M_PI / 2)));
  EXPECT_FALSE(ctx.fitsInside(box, at(kInnerWall_x + kTooNear_m, 0.12, 0.006, M_PI / 2)));
  EXPECT_TRUE(ctx.fitsInside(box, at(kInnerWall_x + kFarEnough_m, 0.12, 0.006, M_PI / 2)));
  EXPECT_NEAR(ctx.toolClearanceFrom(box, at(kOuterWall_x - kTooNear_m, 0.12, 0.0)), 0.022, kGeomTol_m);

  // A tray 20 mm high: the 30 mm part's top is 10 mm above its walls, the tool stays above them.
  CellDescription low = c;
  for (auto& o : low.objects)
    if (o.name == "gray box") o.size_m.z() = 0.020;
  const PlacementContext lowCtx(low, get(low, "cuboid"), tight);
  const CellObject& tray = get(low, "gray box");
  EXPECT_NEAR(lowCtx.toolClearanceFrom(tray, at(kOuterWall_x - kTooNear_m, 0.12, 0.0)), 0.0, kGeomTol_m);
  EXPECT_TRUE(lowCtx.fitsTable(at(kOuterWall_x - kTooNear_m, 0.12, 0.0, M_PI / 2)));
  EXPECT_TRUE(lowCtx.fitsInside(tray, at(kInnerWall_x + kTooNear_m, 0.12, 0.006, M_PI / 2)));
}

TEST(PlacementPlanner, OutOfReachIsRefused) {
  CellDescription c = cell();
  c = after(c, "star", at(0.55, 0.35));  // 0.87 m from the base
  const PlacementPlanner planner;
  const Placement p = planner.place(c, get(c, "cuboid"), stepOf("cuboid", rel("behind", "star")));
  EXPECT_FALSE(p.X_world_object);
  const Placement stack = planner.place(c, get(c, "cuboid"), stepOf("cuboid", rel("on top of", "star")));
  EXPECT_FALSE(stack.X_world_object);
  EXPECT_NE(stack.reason.find("out of the arm's reach"), std::string::npos) << stack.reason;
}

TEST(PlacementPlanner, UnknownRelationAndMissingLandmarkGiveReasons) {
  const CellDescription c = cell();
  const PlacementPlanner planner;
  const Placement u = planner.place(c, get(c, "cuboid"), stepOf("cuboid", rel("underneath", "star")));
  EXPECT_FALSE(u.X_world_object);
  EXPECT_NE(u.reason.find("unknown target relation 'underneath'"), std::string::npos) << u.reason;
  const Placement m = planner.place(c, get(c, "cuboid"), stepOf("cuboid", rel("left of", "hexagon")));
  EXPECT_FALSE(m.X_world_object);
  EXPECT_NE(m.reason.find("no hexagon"), std::string::npos) << m.reason;
  const Placement self = planner.place(c, get(c, "cuboid"), stepOf("cuboid", rel("left of", "cuboid")));
  EXPECT_FALSE(self.X_world_object);
}

TEST(PlacementPlanner, CheckReportsAViolatedRelation) {
  const CellDescription c = cell();
  const PlacementPlanner planner;
  // The cuboid at (0, -0.05) is right of the star at (-0.15, 0.1)? Along +x 0.15, lateral 0.15: not within 45 deg.
  const auto right = planner.check(c, get(c, "cuboid"), stepOf("cuboid", rel("right of", "star")));
  ASSERT_EQ(right.size(), 1u);
  EXPECT_FALSE(right[0].holds) << right[0].detail;
  const auto left = planner.check(c, get(c, "cuboid"), stepOf("cuboid", rel("left of", "octagon")));
  EXPECT_FALSE(left[0].holds) << left[0].detail;  // it is right of the octagon
  const auto rightOfOct = planner.check(c, get(c, "cuboid"), stepOf("cuboid", rel("right of", "octagon")));
  EXPECT_TRUE(rightOfOct[0].holds) << rightOfOct[0].detail;
  EXPECT_NEAR(rightOfOct[0].value_m, 0.15 - 0.02 - 0.025, kGeomTol_m);
  const auto onTop = planner.check(c, get(c, "cuboid"), stepOf("cuboid", rel("on top of", "octagon")));
  EXPECT_FALSE(onTop[0].holds);
}
