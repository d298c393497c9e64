#include <gtest/gtest.h>

#include "srp/execution/CellDescription.h"
#include "srp/execution/SceneGrounder.h"

using namespace srp::execution;

namespace {

// The acceptance scene (sim/scenes/two_cuboids_two_stars.json), demonstrator's view:
// right = world +x, front = world -y. Left to right: cuboid_blue (-0.15, -0.01),
// star_yellow (-0.13, -0.10), cuboid_red (0.00, 0.02), star_green (0.09, -0.09);
// blue box at (-0.16, 0.12), gray box at (0.16, 0.12).
CellDescription acceptanceScene() {
  return CellDescription::loadScene(std::string(SRP_SIM_DIR) + "/scenes/two_cuboids_two_stars.json");
}

ObjectReference ref(const std::string& name, std::optional<std::string> colour = {}) { return {name, colour}; }

ObjectReference withOrdinal(ObjectReference r, int ordinal) {
  r.ordinal = ordinal;
  return r;
}
ObjectReference withSuperlative(ObjectReference r, const std::string& s) {
  r.superlative = s;
  return r;
}
ObjectReference withRelation(ObjectReference r, const std::string& relation, ObjectReference landmark) {
  r.relations.push_back({relation, landmark});
  return r;
}

std::string groundError(const SceneGrounder& g, const ObjectReference& r, std::vector<std::string>* ids = nullptr) {
  try {
    const CellObject& o = g.ground(r);
    ADD_FAILURE() << "'" << r.describe() << "' grounded to " << o.name << " instead of failing";
  } catch (const GroundingError& e) {
    if (ids) *ids = e.candidates();
    return e.what();
  }
  return "";
}

void move(CellDescription& cell, const std::string& id, double x, double y, double z = 0.0) {
  for (auto& o : cell.objects)
    if (o.name == id) o.X_world_object.translation() = Eigen::Vector3d(x, y, z);
}

}  // namespace

TEST(SceneGrounder, InstancesOfOneClassKeepTheirSceneColour) {
  const CellDescription cell = acceptanceScene();
  ASSERT_NE(cell.find("cuboid_red"), nullptr);
  EXPECT_EQ(cell.find("cuboid_red")->colour, "red");
  EXPECT_EQ(cell.find("cuboid_blue")->colour, "blue");
  EXPECT_EQ(cell.find("cuboid_blue")->className, "cuboid");
  EXPECT_GT((cell.find("cuboid_blue")->rgb - cell.find("cuboid_red")->rgb).norm(), 0.5);
  ASSERT_TRUE(cell.X_world_camera.has_value());
}

TEST(SceneGrounder, ColourPicksOneInstance) {
  const CellDescription cell = acceptanceScene();
  const SceneGrounder g(cell);
  EXPECT_EQ(g.ground(ref("cuboid", "red")).name, "cuboid_red");
  EXPECT_EQ(g.ground(ref("cuboid", "blue")).name, "cuboid_blue");
  EXPECT_EQ(g.ground(ref("star", "green")).name, "star_green");
  EXPECT_EQ(g.ground(ref("star", "yellow")).name, "star_yellow");
  EXPECT_EQ(g.ground(ref("box", "grey"), {}, CellObjectKind::Container).name, "gray box");
  // The colour alone is not a kind: a blue box is no answer to "the blue cuboid".
  EXPECT_EQ(g.ground(ref("box", "blue")).name, "blue box");
}

TEST(SceneGrounder, OrdinalsCountLeftToRightInTheDemonstratorsView) {
  const CellDescription cell = acceptanceScene();
  const SceneGrounder g(cell);
  EXPECT_EQ(g.ground(withOrdinal(ref("cuboid"), 1)).name, "cuboid_blue");
  EXPECT_EQ(g.ground(withOrdinal(ref("cuboid"), 2)).name, "cuboid_red");
  EXPECT_EQ(g.ground(withOrdinal(ref("star"), -1)).name, "star_green");
  EXPECT_EQ(g.ground(withOrdinal(ref("star"), 1)).name, "star_yellow");
  // The robot's view is the same here (base at y = -0.3 looking at the table centre);
  // a robot on the far side of the table sees left and right swapped.
  CellDescription far = cell;
  far.X_world_base.linear() = Eigen::AngleAxisd(-M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  far.X_world_base.translation().y() = -cell.X_world_base.translation().y();
  ASSERT_GT(far.X_world_base.translation().y(), 0.1);
  SceneGrounder::Options robot;
  robot.viewpoint = srp::core::Viewpoint::Robot;
  EXPECT_EQ(SceneGrounder(far, robot).ground(withOrdinal(ref("cuboid"), 1)).name, "cuboid_red");
  EXPECT_EQ(SceneGrounder(far).ground(withOrdinal(ref("cuboid"), 1)).name, "cuboid_blue");
  // Out of range: says how many there are.
  const std::string message = groundError(g, withOrdinal(ref("cuboid"), 3));
  EXPECT_NE(message.find("only two cuboids"), std::string::npos) << message;
}

TEST(SceneGrounder, SuperlativesTakeTheExtreme) {
  const CellDescription cell = acceptanceScene();
  const SceneGrounder g(cell);
  EXPECT_EQ(g.ground(withSuperlative(ref("star"), "leftmost")).name, "star_yellow");
  EXPECT_EQ(g.ground(withSuperlative(ref("star"), "rightmost")).name, "star_green");
  EXPECT_EQ(g.ground(withSuperlative(ref("cuboid"), "frontmost")).name, "cuboid_blue");  // y -0.01 vs 0.02
  EXPECT_EQ(g.ground(withSuperlative(ref("cuboid"), "backmost")).name, "cuboid_red");
  EXPECT_EQ(g.ground(withRelation(ref("star"), "closest to", ref("box", "blue"))).name, "star_yellow");
  EXPECT_EQ(g.ground(withRelation(ref("cuboid"), "closest to", ref("star", "green"))).name, "cuboid_red");
  EXPECT_EQ(g.ground(withRelation(ref("cuboid"), "farthest from", ref("star", "green"))).name, "cuboid_blue");
  // Two level instances are no superlative: both are named.
  CellDescription level = cell;
  move(level, "cuboid_red", 0.0, -0.01);
  std::vector<std::string> ids;
  const std::string message = groundError(SceneGrounder(level), withSuperlative(ref("cuboid"), "frontmost"), &ids);
  EXPECT_EQ(ids.size(), 2u) << message;
}

TEST(SceneGrounder, LandmarkRelationsReadWhereTheObjectIsNow) {
  CellDescription cell = acceptanceScene();
  const SceneGrounder g(cell);
  EXPECT_EQ(g.ground(withRelation(ref("cuboid"), "behind", ref("star", "yellow"))).name, "cuboid_blue");
  EXPECT_EQ(g.ground(withRelation(ref("star"), "in front of", ref("cuboid", "red"))).name, "star_green");
  EXPECT_EQ(g.ground(withRelation(ref("star"), "to the right of", ref("cuboid", "blue"))).name, "star_green");
  EXPECT_EQ(g.ground(withRelation(ref("cuboid"), "left of", ref("star", "green"))).name, "cuboid_blue");
  // A landmark several instances fit: the relation must hold with one of them.
  EXPECT_EQ(g.ground(withRelation(ref("cuboid"), "left of", ref("star"))).name, "cuboid_blue");
  // Step source locations work the same way ("take the cuboid from the gray box").
  CellDescription boxed = cell;
  move(boxed, "cuboid_red", 0.16, 0.12, 0.006);
  const SceneGrounder gb(boxed);
  EXPECT_EQ(gb.ground(ref("cuboid"), {{"from", ref("box", "gray")}}).name, "cuboid_red");
  EXPECT_EQ(gb.ground(withRelation(ref("cuboid"), "in", ref("box"))).name, "cuboid_red");
  // Stacked: the star on the red cuboid.
  CellDescription stacked = cell;
  move(stacked, "star_green", 0.0, 0.02, 0.03);
  const SceneGrounder gs(stacked);
  EXPECT_EQ(gs.ground(withRelation(ref("star"), "on top of", ref("cuboid"))).name, "star_green");
  EXPECT_EQ(gs.ground(withRelation(ref("cuboid"), "under", ref("star"))).name, "cuboid_red");
  EXPECT_TRUE(gs.holds("on", *stacked.find("star_green"), *stacked.find("cuboid_red")));
  EXPECT_FALSE(gs.holds("on", *stacked.find("star_yellow"), *stacked.find("cuboid_red")));
}

TEST(SceneGrounder, AmbiguityNamesEveryCandidateWithItsPosition) {
  const CellDescription cell = acceptanceScene();
  const SceneGrounder g(cell);
  std::vector<std::string> ids;
  const std::string message = groundError(g, ref("cuboid"), &ids);
  EXPECT_NE(message.find("two cuboids match 'the cuboid'"), std::string::npos) << message;
  EXPECT_NE(message.find("'cuboid_blue' at (-0.150, -0.010)"), std::string::npos) << message;
  EXPECT_NE(message.find("'cuboid_red' at (0.000, 0.020)"), std::string::npos) << message;
  EXPECT_NE(message.find("say which"), std::string::npos) << message;
  EXPECT_EQ(ids, (std::vector<std::string>{"cuboid_blue", "cuboid_red"}));
  // Two red cuboids: the colour does not decide.
  CellDescription twoRed = cell;
  for (auto& o : twoRed.objects)
    if (o.name == "cuboid_blue") o.colour = "red";
  const std::string red = groundError(SceneGrounder(twoRed), ref("cuboid", "red"));
  EXPECT_NE(red.find("two red cuboids match 'the red cuboid': 'cuboid_blue' at (-0.150, -0.010) and 'cuboid_red' at "
                     "(0.000, 0.020)"),
            std::string::npos)
      << red;
}

TEST(SceneGrounder, NoSuchObjectSaysWhatIsThere) {
  const CellDescription cell = acceptanceScene();
  const SceneGrounder g(cell);
  const std::string none = groundError(g, ref("octagon"));
  EXPECT_NE(none.find("no octagon in the scene"), std::string::npos) << none;
  EXPECT_NE(none.find("'star_green' at"), std::string::npos) << none;
  const std::string colour = groundError(g, ref("cuboid", "green"));
  EXPECT_NE(colour.find("no green cuboid"), std::string::npos) << colour;
  EXPECT_NE(colour.find("red 'cuboid_red'"), std::string::npos) << colour;
  const std::string relation = groundError(g, withRelation(ref("star"), "behind", ref("cuboid", "red")));
  EXPECT_NE(relation.find("no star is behind the red cuboid"), std::string::npos) << relation;
  const std::string landmark = groundError(g, withRelation(ref("star"), "next to", ref("octagon")));
  EXPECT_NE(landmark.find("no octagon"), std::string::npos) << landmark;
  EXPECT_THROW(g.ground(withRelation(ref("star"), "between", ref("cuboid", "red"))), GroundingError);
  // A container is no part: "the blue box" as the moved part fits nothing.
  EXPECT_THROW(g.ground(ref("box", "blue"), {}, CellObjectKind::Part), GroundingError);
}
