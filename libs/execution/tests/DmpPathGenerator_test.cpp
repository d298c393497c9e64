#include "srp/execution/DmpPathGenerator.h"

#include <gtest/gtest.h>

#include <sstream>

#include "srp/core/Error.h"
#include "srp/core/Json.h"
#include "srp/core/Scene.h"
#include "srp/execution/CellDescription.h"
#include "srp/execution/ExecutionSession.h"
#include "srp/execution/TaskExecutor.h"
#include "srp/execution/UrScriptExporter.h"
#include "srp/motion/SkillLearner.h"

using srp::core::Pose3;
using srp::core::SkillType;
using namespace srp::execution;

namespace {
constexpr double kEndpointTol_m = 1e-9;    // the path starts and ends exactly at the given poses
constexpr double kShapeTol_m = 0.01;       // a DMP replayed with its own start/goal stays on the demo

Pose3 toolDown(const Eigen::Vector3d& p_world_m, double yaw_rad = 0.0) {
  Pose3 X = Pose3::Identity();
  X.linear() = (Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitX()))
                   .toRotationMatrix();
  X.translation() = p_world_m;
  return X;
}

/// A demo in a camera frame looking down from 0.85 m: lift 0.12 m towards the camera
/// while crossing 0.3 m along camera x (a half sine), 2 s at 100 Hz.
struct ArcDemo {
  Pose3 X_world_camera = Pose3::Identity();
  Eigen::VectorXd t_s;
  Eigen::MatrixXd p_camera_m;
  ArcDemo() {
    X_world_camera.linear() = Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitX()).toRotationMatrix();
    X_world_camera.translation() = Eigen::Vector3d(0.0, 0.05, 0.85);
    const int n = 201;
    t_s.resize(n);
    p_camera_m.resize(n, 3);
    for (int i = 0; i < n; ++i) {
      const double s = i / double(n - 1);
      const double m = s * s * s * (10 - 15 * s + 6 * s * s);
      t_s(i) = 2.0 * s;
      p_camera_m.row(i) << -0.15 + 0.3 * m, 0.1, 0.8 - 0.12 * std::sin(M_PI * m);
    }
  }
  Eigen::Vector3d world(int i) const { return X_world_camera * Eigen::Vector3d(p_camera_m.row(i).transpose()); }
};

}  // namespace

TEST(DmpPathGenerator, ReplaysTheDemoInTheWorldAndRetargetsExactly) {
  const ArcDemo demo;
  std::map<std::string, LearnedPathSkills> skills;
  skills["cuboid"].move = srp::motion::Dmp::imitate(demo.t_s, demo.p_camera_m, srp::motion::Dmp::Options{});
  const DmpPathGenerator gen(skills, demo.X_world_camera, {}, 0.0);  // the Move DMP end to end
  EXPECT_EQ(gen.name(), "dmp");
  EXPECT_EQ(gen.sourceFor(SkillType::Move, "cuboid"), "dmp");
  EXPECT_EQ(gen.sourceFor(SkillType::Reach, "cuboid"), "minimum-jerk");
  EXPECT_EQ(gen.sourceFor(SkillType::Move, "star"), "minimum-jerk");

  // Own start and goal (in the world): the path follows the demo's arc, lifted in world z.
  const int last = static_cast<int>(demo.t_s.size()) - 1;
  const Pose3 start = toolDown(demo.world(0)), goal = toolDown(demo.world(last), 0.5);
  const CartesianPath path = gen.generate(SkillType::Move, "cuboid", start, goal, 0.01);
  ASSERT_GE(path.size(), 3u);
  EXPECT_LT((path.front().X_world_tcp.translation() - start.translation()).norm(), kEndpointTol_m);
  EXPECT_LT((path.back().X_world_tcp.translation() - goal.translation()).norm(), kEndpointTol_m);
  EXPECT_LT(srp::core::rotationAngleBetween(path.back().X_world_tcp.linear(), goal.linear()), 1e-9);
  EXPECT_NEAR(path.back().t_s, demo.t_s(last), 0.011) << "the demo's duration is kept when it is long enough";
  double maxDeviation_m = 0.0, peakZ_m = -1.0;
  for (std::size_t i = 0; i < path.size(); ++i) {
    const int k = std::min(last, static_cast<int>(std::lround(path[i].t_s / 0.01)));
    maxDeviation_m = std::max(maxDeviation_m, (path[i].X_world_tcp.translation() - demo.world(k)).norm());
    peakZ_m = std::max(peakZ_m, path[i].X_world_tcp.translation().z());
  }
  EXPECT_LT(maxDeviation_m, kShapeTol_m);
  EXPECT_NEAR(peakZ_m, demo.world(0).z() + 0.12, kShapeTol_m) << "the lift is world up (camera looks down)";

  // A new start and goal: exact endpoints, a lift, and a longer duration for a longer chord.
  const Pose3 a = toolDown({0.2, 0.1, 0.05}), b = toolDown({-0.35, 0.25, 0.08});
  const CartesianPath moved = gen.generate(SkillType::Move, "cuboid", a, b, 0.01);
  EXPECT_LT((moved.front().X_world_tcp.translation() - a.translation()).norm(), kEndpointTol_m);
  EXPECT_LT((moved.back().X_world_tcp.translation() - b.translation()).norm(), kEndpointTol_m);
  double top_m = 0.0;
  for (const auto& s : moved) top_m = std::max(top_m, s.X_world_tcp.translation().z());
  EXPECT_GT(top_m, 0.08 + 0.05) << "the re-targeted DMP keeps the demo's lift";
  EXPECT_GE(moved.back().t_s,
            (b.translation() - a.translation()).norm() / MinimumJerkPathGenerator::Options{}.meanSpeed_mps - 0.011);

  // No learned skill: the minimum-jerk fallback, sample for sample.
  const CartesianPath fallback = gen.generate(SkillType::Reach, "cuboid", a, b, 0.01);
  const CartesianPath expected = MinimumJerkPathGenerator().generate(SkillType::Reach, "cuboid", a, b, 0.01);
  ASSERT_EQ(fallback.size(), expected.size());
  EXPECT_LT((fallback[fallback.size() / 2].X_world_tcp.translation() -
             expected[expected.size() / 2].X_world_tcp.translation()).norm(), 1e-12);
  // With the default raised ends the carried part leaves and enters vertically.
  const DmpPathGenerator raised(skills, demo.X_world_camera);
  const CartesianPath lifted = raised.generate(SkillType::Move, "cuboid", a, b, 0.01);
  EXPECT_LT((lifted.back().X_world_tcp.translation() - b.translation()).norm(), kEndpointTol_m);
  for (const auto& s : lifted) {
    const Eigen::Vector3d p = s.X_world_tcp.translation();
    if (p.z() < DmpPathGenerator::kDefaultEndHeight_m - 1e-6) {
      const Eigen::Vector2d nearEnd = (p - a.translation()).head<2>().norm() < (p - b.translation()).head<2>().norm()
                                          ? a.translation().head<2>()
                                          : b.translation().head<2>();
      EXPECT_LT((p.head<2>() - nearEnd).norm(), 1e-6) << "below the end height only straight above an end, t = " << s.t_s;
    }
  }
  EXPECT_THROW(gen.generate(SkillType::Grasp, "cuboid", a, b, 0.01), srp::core::InvalidInputError);
}

// Known geometry: a 18.8 cm toy held at its top, carried from the table into a bin
// with 14.9 cm walls. At the cell's carry height (CellDescription::carryHeight_m) the
// toy's bottom clears the wall top by the clearance wherever the tcp is not straight
// above an end, for the learned Move (the demo's arc between raised ends) and for the
// minimum-jerk fallback; at the default end height the learned Move would sweep the toy
// through the wall (the check can fail).
TEST(DmpPathGenerator, AMoveAtTheCarryHeightCarriesTheTallestPartOverTheWall) {
  constexpr double kClearanceTol_m = 1e-6;  // the raised ends are exact; the DMP between them lifts
  constexpr double kToyHeight_m = 0.188, kWall_m = 0.149, kFloor_m = 0.006;
  CellDescription cell;
  CellObject bin;
  bin.name = "bin";
  bin.kind = CellObjectKind::Container;
  bin.size_m = {0.40, 0.31, kWall_m};
  bin.wallThickness_m = kFloor_m;
  bin.X_world_object.translation() = Eigen::Vector3d(0.3, 0.0, 0.0);
  CellObject toy;
  toy.name = "toy";
  toy.size_m = {0.22, 0.13, kToyHeight_m};
  toy.X_world_object.translation() = Eigen::Vector3d(-0.15, 0.05, 0.0);
  cell.objects = {bin, toy};
  const double carry_m = cell.carryHeight_m();
  ASSERT_NEAR(carry_m, kWall_m + kToyHeight_m + CellDescription::kCarriedAboveWalls_m, 1e-9);

  const ArcDemo demo;
  std::map<std::string, LearnedPathSkills> skills;
  skills["toy"].move = srp::motion::Dmp::imitate(demo.t_s, demo.p_camera_m, srp::motion::Dmp::Options{});
  MinimumJerkPathGenerator::Options fallback;
  fallback.clearanceHeight_m = std::max(fallback.clearanceHeight_m, carry_m);
  const DmpPathGenerator gen(skills, demo.X_world_camera, fallback, DmpPathGenerator::kDefaultEndHeight_m, carry_m);
  const Pose3 start = toolDown({-0.15, 0.05, kToyHeight_m}), goal = toolDown({0.3, 0.0, kFloor_m + kToyHeight_m});
  // The lowest bottom of the toy [m] while the tcp is not straight above an end.
  const auto lowestCrossing_m = [&](const CartesianPath& path) {
    double lowest = 1e9;
    for (const auto& s : path) {
      const Eigen::Vector3d p = s.X_world_tcp.translation();
      if ((p - start.translation()).head<2>().norm() < 1e-6 || (p - goal.translation()).head<2>().norm() < 1e-6) continue;
      lowest = std::min(lowest, p.z() - kToyHeight_m);
    }
    return lowest;
  };
  const double wallClear_m = kWall_m + CellDescription::kCarriedAboveWalls_m;
  for (const std::string object : {"toy", "star"}) {  // learned; the minimum-jerk fallback
    const CartesianPath path = gen.generate(srp::core::SkillType::Move, object, start, goal, 0.01);
    EXPECT_LT((path.back().X_world_tcp.translation() - goal.translation()).norm(), kEndpointTol_m) << object;
    EXPECT_GE(lowestCrossing_m(path), wallClear_m - kClearanceTol_m) << object << ": the toy's bottom over the wall";
  }
  const DmpPathGenerator low(skills, demo.X_world_camera);
  EXPECT_LT(lowestCrossing_m(low.generate(srp::core::SkillType::Move, "toy", start, goal, 0.01)), kWall_m)
      << "at the default end height the toy would cross through the wall";
}

// A hand that moves 5 cm sideways onto a part but dips 4 cm on the way (a short
// demonstrated chord with a detour almost as large), re-targeted to a 0.5 m Reach in
// the same direction 0.2 m above the table: the spatial scaling alone would scale the
// 4 cm dip tenfold, through the table. The re-targeted detour stays within the
// demonstrator's own (kShapeTol_m for the DMP's reproduction), so the path stays above
// the table, and still ends exactly on its goal.
TEST(DmpPathGenerator, ShortDemoRetargetedFarKeepsTheDemonstratorsDetour) {
  Pose3 X_world_camera = Pose3::Identity();
  X_world_camera.linear() = Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitX()).toRotationMatrix();
  X_world_camera.translation() = Eigen::Vector3d(0.0, 0.0, 0.85);  // looks down: world z = 0.85 - camera z
  const int n = 201;
  Eigen::VectorXd t_s(n);
  Eigen::MatrixXd p_camera_m(n, 3);
  for (int i = 0; i < n; ++i) {
    const double s = i / double(n - 1), m = s * s * s * (10 - 15 * s + 6 * s * s);
    t_s(i) = 2.0 * s;
    p_camera_m.row(i) << -0.025 + 0.05 * m, 0.0, 0.6 + 0.04 * std::sin(M_PI * m);  // 5 cm along, dipping 4 cm
  }
  std::map<std::string, LearnedPathSkills> skills;
  srp::motion::Dmp::Options spatial;  // as fromTaskModel executes a learned DMP
  spatial.scaling = srp::motion::ForcingScaling::Spatial;
  skills["toy"].reach = srp::motion::Dmp::imitate(t_s, p_camera_m, spatial);
  const DmpPathGenerator gen(skills, X_world_camera, {}, 0.0);
  constexpr double kDemoDetour_m = 0.04;
  const Pose3 a = toolDown({-0.25, 0.0, 0.2}), b = toolDown({0.25, 0.0, 0.2});
  const CartesianPath path = gen.generate(SkillType::Reach, "toy", a, b, 0.01);
  EXPECT_LT((path.back().X_world_tcp.translation() - b.translation()).norm(), kEndpointTol_m);
  double lowest_m = 1.0, detour_m = 0.0;
  for (const auto& s : path) {
    const Eigen::Vector3d p = s.X_world_tcp.translation();
    lowest_m = std::min(lowest_m, p.z());
    detour_m = std::max(detour_m, std::hypot(p.y(), p.z() - 0.2));  // off the straight line a -> b
  }
  EXPECT_LE(detour_m, kDemoDetour_m + kShapeTol_m);
  EXPECT_GE(lowest_m, 0.2 - kDemoDetour_m - kShapeTol_m) << "the re-targeted Reach dips through the table";
}

// A Reach demonstrated 10 cm long whose hand passes the part by 5 cm and comes back
// to it (as a demonstrator's hand that starts near the part and hovers beyond it
// does), re-targeted to the robot's 50 cm from its own start: the spatial scaling alone
// passes the pre-grasp by 17 cm (HRT1 task3's Reach: 6 cm past the toy in the demo,
// 29 cm past the pre-grasp re-targeted, out of the arm's reach). The overshoot stays within the demonstrator's own, and the path still
// ends exactly on its goal.
TEST(DmpPathGenerator, ShortDemoRetargetedFarKeepsTheDemonstratorsOvershoot) {
  Pose3 X_world_camera = Pose3::Identity();
  X_world_camera.linear() = Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitX()).toRotationMatrix();
  X_world_camera.translation() = Eigen::Vector3d(0.0, 0.0, 0.85);
  const int n = 201;
  constexpr double kDemoLength_m = 0.10, kDemoOvershoot_m = 0.05;
  Eigen::VectorXd t_s(n);
  Eigen::MatrixXd p_camera_m(n, 3);
  for (int i = 0; i < n; ++i) {
    const double s = i / double(n - 1);
    t_s(i) = 2.0 * s;
    // Along camera x: 5 cm past the part by 60 % of the time, then back to it, still
    // moving when the demonstration's Reach ends (the hand closes on the way back).
    const double a = std::min(1.0, s / 0.6), mj = a * a * a * (10 - 15 * a + 6 * a * a);
    const double x = (kDemoLength_m + kDemoOvershoot_m) * mj - kDemoOvershoot_m * std::max(0.0, (s - 0.6) / 0.4);
    p_camera_m.row(i) << x, 0.0, 0.6;
  }
  std::map<std::string, LearnedPathSkills> skills;
  srp::motion::Dmp::Options spatial;  // as fromTaskModel executes a learned DMP
  spatial.scaling = srp::motion::ForcingScaling::Spatial;
  skills["toy"].reach = srp::motion::Dmp::imitate(t_s, p_camera_m, spatial);
  const DmpPathGenerator gen(skills, X_world_camera, {}, 0.0);
  const Pose3 a = toolDown({-0.25, 0.0, 0.25}), b = toolDown({0.25, 0.0, 0.25});
  const CartesianPath path = gen.generate(SkillType::Reach, "toy", a, b, 0.01);
  EXPECT_LT((path.front().X_world_tcp.translation() - a.translation()).norm(), kEndpointTol_m);
  EXPECT_LT((path.back().X_world_tcp.translation() - b.translation()).norm(), kEndpointTol_m);
  double past_m = 0.0, behind_m = 0.0;
  for (const auto& s : path) {
    past_m = std::max(past_m, s.X_world_tcp.translation().x() - b.translation().x());
    behind_m = std::max(behind_m, a.translation().x() - s.X_world_tcp.translation().x());
  }
  EXPECT_GT(past_m, 0.5 * kDemoOvershoot_m) << "the demonstrator's overshoot is kept, not flattened";
  EXPECT_LE(past_m, kDemoOvershoot_m + kShapeTol_m) << "the re-targeted Reach passes its goal farther than the demo";
  EXPECT_LE(behind_m, kShapeTol_m);
}

TEST(DmpPathGenerator, WithoutLearnedSkillsTheAppendixCModelFallsBackToMinimumJerk) {
  const auto j = srp::core::readJsonFile(std::string(SRP_DATASETS_DIR) + "/examples/appendix_c_instruction1.json");
  const auto model = srp::taskdb::taskModelFromJson(j, "appendix C");
  const DmpPathGenerator gen = DmpPathGenerator::fromTaskModel(model, Pose3::Identity());
  EXPECT_FALSE(gen.hasSkills());
  EXPECT_EQ(gen.name(), "minimum-jerk");
  EXPECT_EQ(gen.sourceFor(SkillType::Reach, "cuboid"), "minimum-jerk");
}
