#include "srp/motion/Segmenter.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include "srp/core/Error.h"
#include "srp/motion/SyntheticPickPlace.h"

namespace srp::motion {
namespace {

constexpr int kFrameTol = 3;  // issue 6: grasp and release within +-3 frames of the truth

// motion::SyntheticPickPlaceGenerator's truth is the thesis' definition (grasp in the
// middle of the hand's hold at the object), so these tests run the thesis'
// estimator; the default (hand-dwell boundaries) is checked against
// srp::synth's ground truth (grasp = end of the hold) in the programming tests.
Segmenter thesisSegmenter() {
  Segmenter::Options c;
  c.events = Segmenter::EventEstimator::Thesis;
  return Segmenter(c);
}

// Harder cases than the acceptance (measured worst errors, see README):
constexpr int kHeavyFlickerTol = 8;  // 8 % of frames flicker for 1-3 frames
constexpr int kPutBackGraspTol = 8;  // the hand lingers near the object before a short reach

void expectWithinTolerance(const motion::SyntheticPickPlace& demo, const Segmentation& seg, const std::string& tag,
                           int graspTol = kFrameTol, int releaseTol = kFrameTol) {
  ASSERT_EQ(seg.objects.size(), demo.planOrder.size()) << tag;
  int worstGrasp = 0, worstRelease = 0;
  for (std::size_t i = 0; i < demo.planOrder.size(); ++i) {
    worstGrasp = std::max(worstGrasp, std::abs(seg.objects[i].graspIndex - demo.graspIndex[i]));
    worstRelease = std::max(worstRelease, std::abs(seg.objects[i].releaseIndex - demo.releaseIndex[i]));
  }
  std::cout << tag << ": worst grasp error " << worstGrasp << ", release " << worstRelease << " frames\n";
  for (std::size_t i = 0; i < demo.planOrder.size(); ++i) {
    const auto& o = seg.objects[i];
    EXPECT_TRUE(o.moved) << tag << " " << o.name;
    EXPECT_LE(std::abs(o.graspIndex - demo.graspIndex[i]), graspTol)
        << tag << " " << o.name << " grasp " << o.graspIndex << " truth " << demo.graspIndex[i];
    EXPECT_LE(std::abs(o.releaseIndex - demo.releaseIndex[i]), releaseTol)
        << tag << " " << o.name << " release " << o.releaseIndex << " truth " << demo.releaseIndex[i];
  }
}

TEST(Segmenter, FindsGraspAndReleaseOnNoisyDemosWithFlicker) {
  int worstGrasp = 0, worstRelease = 0;
  for (std::uint32_t seed = 1; seed <= 12; ++seed) {
    motion::SyntheticPickPlaceGenerator::Options c;
    c.seed = seed;
    const auto demo = motion::SyntheticPickPlaceGenerator(c).generate();
    const auto seg = thesisSegmenter().segment(demo.hand, demo.objects, demo.planOrder);
    expectWithinTolerance(demo, seg, "seed " + std::to_string(seed));
    for (std::size_t i = 0; i < seg.objects.size(); ++i) {
      worstGrasp = std::max(worstGrasp, std::abs(seg.objects[i].graspIndex - demo.graspIndex[i]));
      worstRelease = std::max(worstRelease, std::abs(seg.objects[i].releaseIndex - demo.releaseIndex[i]));
    }
  }
  std::cout << "worst grasp error " << worstGrasp << " frames, worst release error " << worstRelease << " frames\n";
}

TEST(Segmenter, ToleratesHeavyFlickerBetweenTwoPositions) {
  motion::SyntheticPickPlaceGenerator::Options c;
  c.flickerRate = 0.08;
  c.objectDropoutRate = 0.10;
  for (std::uint32_t seed = 20; seed < 24; ++seed) {
    c.seed = seed;
    const auto demo = motion::SyntheticPickPlaceGenerator(c).generate();
    expectWithinTolerance(demo, thesisSegmenter().segment(demo.hand, demo.objects, demo.planOrder),
                          "heavy flicker seed " + std::to_string(seed), kHeavyFlickerTol, kHeavyFlickerTol);
  }
}

TEST(Segmenter, ReportsAnObjectThatNeverMoves) {
  motion::SyntheticPickPlaceGenerator::Options c;
  c.movedObjects = {"cuboid", "star"};
  c.staticObjects = {"octagon"};
  const auto demo = motion::SyntheticPickPlaceGenerator(c).generate();
  const std::vector<std::string> plan = {"cuboid", "octagon", "star"};
  const auto seg = thesisSegmenter().segment(demo.hand, demo.objects, plan);
  ASSERT_EQ(seg.objects.size(), 3u);
  EXPECT_FALSE(seg.objects[1].moved);
  EXPECT_EQ(seg.objects[1].graspIndex, -1);
  EXPECT_NE(seg.objects[1].note.find("never moves"), std::string::npos) << seg.objects[1].note;
  ASSERT_EQ(seg.warnings.size(), 1u);
  // The static object does not disturb the others.
  EXPECT_LE(std::abs(seg.objects[0].releaseIndex - demo.releaseIndex[0]), kFrameTol);
  EXPECT_LE(std::abs(seg.objects[2].graspIndex - demo.graspIndex[1]), kFrameTol);
  EXPECT_LE(std::abs(seg.objects[2].releaseIndex - demo.releaseIndex[1]), kFrameTol);
}

TEST(Segmenter, ObjectsPutBackWhereTheyWereAreSegmented) {
  // Source = target: the "before" and "after" mixture components are the same
  // place, so the components are not in temporal order.
  motion::SyntheticPickPlaceGenerator::Options c;
  c.putBackWhereTaken = true;
  c.lift_m = 0.2;
  for (std::uint32_t seed = 30; seed < 34; ++seed) {
    c.seed = seed;
    const auto demo = motion::SyntheticPickPlaceGenerator(c).generate();
    expectWithinTolerance(demo, thesisSegmenter().segment(demo.hand, demo.objects, demo.planOrder),
                          "put back, seed " + std::to_string(seed), kPutBackGraspTol, kFrameTol);
  }
}

TEST(Segmenter, RejectsBadInput) {
  const auto demo = motion::SyntheticPickPlaceGenerator().generate();
  // A plan object without trajectory.
  EXPECT_THROW(Segmenter().segment(demo.hand, demo.objects, {"cuboid", "banana"}), core::InvalidInputError);
  // Empty and single-sample hand.
  EXPECT_THROW(Segmenter().segment(core::PositionTrajectory("camera"), demo.objects, demo.planOrder),
               core::InvalidInputError);
  core::PositionTrajectory single("camera");
  single.append({0, 0.0, Eigen::Vector3d(0.1, 0.2, 0.3), true});
  EXPECT_THROW(Segmenter().segment(single, demo.objects, demo.planOrder), core::InvalidInputError);
  // NaN sample.
  auto objects = demo.objects;
  objects[1].positions.samples()[40].p_m(2) = std::numeric_limits<double>::infinity();
  EXPECT_THROW(Segmenter().segment(demo.hand, objects, demo.planOrder), core::InvalidInputError);
  // Frames that do not match.
  objects = demo.objects;
  objects[0].positions.samples().pop_back();
  EXPECT_THROW(Segmenter().segment(demo.hand, objects, demo.planOrder), core::InvalidInputError);
  EXPECT_THROW(Segmenter().segment(demo.hand, demo.objects, {}), core::InvalidInputError);
}

}  // namespace
}  // namespace srp::motion
