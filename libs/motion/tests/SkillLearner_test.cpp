#include "srp/motion/SkillLearner.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "srp/core/Error.h"
#include "srp/motion/SyntheticPickPlace.h"

namespace srp::motion {
namespace {

constexpr double kOffsetTol_m = 1e-12;
constexpr double kDmpFollowTol_m = 2e-3;  // the learned DMP follows the smoothed hand segment
constexpr double kGoalTol_m = 1e-3;

struct Learned {
  motion::SyntheticPickPlace demo;
  Segmentation seg;
  std::vector<SkillSet> skills;
};

Learned learnDemo(motion::SyntheticPickPlaceGenerator::Options c) {
  Learned l;
  l.demo = motion::SyntheticPickPlaceGenerator(std::move(c)).generate();
  l.seg = Segmenter().segment(l.demo.hand, l.demo.objects, l.demo.planOrder);
  l.skills = SkillLearner().learn(l.seg, l.demo.objects);
  return l;
}

TEST(SkillLearner, LearnsReachAndMoveWithPrePostPoses) {
  const Learned l = learnDemo(motion::SyntheticPickPlaceGenerator::Options{});
  ASSERT_EQ(l.skills.size(), 4u);
  int previousRelease = -1;
  for (const auto& s : l.skills) {
    EXPECT_GT(s.graspIndex, s.reachStartIndex);
    EXPECT_GT(s.releaseIndex, s.graspIndex);
    EXPECT_GE(s.reachStartIndex, previousRelease);
    previousRelease = s.releaseIndex;
    // Pre/post poses: 2 cm back along the approach axis, same orientation.
    EXPECT_NEAR((s.X_frame_grasp.translation() - s.X_frame_preGrasp.translation()).norm(), 0.02, kOffsetTol_m);
    EXPECT_NEAR((s.X_frame_grasp.translation() - s.X_frame_preGrasp.translation()).normalized().dot(s.graspApproachAxis), 1.0, 1e-9);
    EXPECT_NEAR((s.X_frame_release.translation() - s.X_frame_preRelease.translation()).norm(), 0.02, kOffsetTol_m);
    EXPECT_LE(core::rotationAngleBetween(s.X_frame_grasp.linear(), s.X_frame_preGrasp.linear()), 1e-12);
    // The generator's reach is a straight line: the approach axis is its direction.
    constexpr double kAxisTol_rad = 25.0 * M_PI / 180.0;
    const Eigen::Vector3d reachDirection =
        (l.seg.hand[s.graspIndex].p_m - l.seg.hand[s.reachStartIndex].p_m).normalized();
    EXPECT_LE(std::acos(std::clamp(reachDirection.dot(s.graspApproachAxis), -1.0, 1.0)), kAxisTol_rad)
        << s.objectName << " axis " << s.graspApproachAxis.transpose() << " reach " << reachDirection.transpose();
    // The Reach DMP follows the smoothed hand and ends at the grasp.
    ASSERT_TRUE(s.reach && s.move && s.moveOrientation);
    const DmpRollout r = s.reach->rollout();
    double worst = 0.0;
    for (Eigen::Index i = 0; i < r.y.rows(); ++i)
      worst = std::max(worst, (r.y.row(i).transpose() - l.seg.hand[s.reachStartIndex + i].p_m).norm());
    EXPECT_LE(worst, kDmpFollowTol_m) << s.objectName;
    EXPECT_LE((r.y.row(r.y.rows() - 1).transpose() - s.X_frame_grasp.translation()).norm(), kDmpFollowTol_m);
    // Re-targeted Move from post-grasp to pre-release ends at pre-release.
    Dmp move = *s.move;
    move.configure(s.X_frame_preGrasp.translation(), s.X_frame_preRelease.translation(), 2.0);
    const DmpRollout m = move.rollout(0.01);
    EXPECT_LE((m.y.row(m.y.rows() - 1).transpose() - s.X_frame_preRelease.translation()).norm(), kGoalTol_m);
  }
}

TEST(SkillLearner, RecordsCarryDmpsThatRollOutIdentically) {
  const Learned l = learnDemo(motion::SyntheticPickPlaceGenerator::Options{});
  const auto records = skillRecords(l.skills[1]);
  ASSERT_EQ(records.size(), 4u);
  EXPECT_EQ(records[0].skill, core::SkillType::Reach);
  EXPECT_EQ(records[3].skill, core::SkillType::Release);
  EXPECT_EQ(records[2].startIndex, l.skills[1].graspIndex);
  EXPECT_EQ(records[2].endIndex, l.skills[1].releaseIndex);
  const std::string stored = records[2].parameters.dump();  // what the Skills table keeps
  const Dmp back = Dmp::fromJson(nlohmann::json::parse(stored).at("dmp"));
  EXPECT_TRUE(back.rollout(0.01).y == l.skills[1].move->rollout(0.01).y);
}

TEST(SkillLearner, SkipsObjectsThatNeverMoved) {
  motion::SyntheticPickPlaceGenerator::Options c;
  c.movedObjects = {"cuboid", "star"};
  c.staticObjects = {"octagon"};
  auto demo = motion::SyntheticPickPlaceGenerator(c).generate();
  const auto seg = Segmenter().segment(demo.hand, demo.objects, {"cuboid", "octagon", "star"});
  const auto skills = SkillLearner().learn(seg, demo.objects);
  ASSERT_EQ(skills.size(), 2u);
  EXPECT_EQ(skills[0].objectName, "cuboid");
  EXPECT_EQ(skills[1].objectName, "star");
}

}  // namespace
}  // namespace srp::motion
