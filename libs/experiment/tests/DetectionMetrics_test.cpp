#include "srp/experiment/DetectionMetrics.h"

#include <gtest/gtest.h>

#include <cmath>

#include "srp/core/Error.h"

using namespace srp::experiment;

namespace {

constexpr double kScoreTol = 1e-12;

OrientedBox2d square(double x, double y, double side = 1.0)
{
  return {{Eigen::Vector2d(x, y), Eigen::Vector2d(x + side, y), Eigen::Vector2d(x + side, y + side),
           Eigen::Vector2d(x, y + side)}};
}

}  // namespace

TEST(DetectionMetrics, HandcraftedListGivesHandComputedAP)
{
  // Three instances (images 0, 1, 2); four detections, by falling confidence:
  // exact hit (TP), a box beside the truth (FP), a hit (TP), a duplicate of
  // the first (FP, its truth is taken). Image 2's instance is missed.
  const std::vector<TruthBox> truths{{0, square(0, 0)}, {1, square(10, 10)}, {2, square(20, 20)}};
  const std::vector<ScoredBox> detections{
      {0, 0.9, square(0, 0)}, {1, 0.8, square(12, 10)}, {1, 0.7, square(10.05, 10)}, {0, 0.6, square(0.1, 0)}};
  const auto matched = matchDetections(detections, truths, 0.5);
  ASSERT_EQ(matched.size(), 4u);
  EXPECT_TRUE(matched[0].second);
  EXPECT_FALSE(matched[1].second);
  EXPECT_TRUE(matched[2].second);
  EXPECT_FALSE(matched[3].second);
  // Precision 1, 1/2, 2/3, 1/2 at recall 1/3, 1/3, 2/3, 2/3; interpolated
  // 1, 2/3, 2/3, 1/2: AP = 1/3 * 1 + 1/3 * 2/3 = 5/9.
  EXPECT_NEAR(averagePrecision(matched, 3), 5.0 / 9.0, kScoreTol);
  const ClassDetectionScores s = scoreDetections(detections, truths);
  EXPECT_EQ(s.instances, 3);
  EXPECT_EQ(s.detections, 4);
  EXPECT_NEAR(s.precision, 0.5, kScoreTol);
  EXPECT_NEAR(s.recall, 2.0 / 3.0, kScoreTol);
  EXPECT_NEAR(s.ap50, 5.0 / 9.0, kScoreTol);
}

TEST(DetectionMetrics, MeanOverIouThresholdsCountsWhereTheMatchHolds)
{
  // Shifted by s along x: IoU = (1 - s) / (1 + s) = 0.72 for s = 0.28 / 1.72:
  // a hit at IoU 0.50 ... 0.70 (5 of the 10 thresholds), a miss above.
  const double s = 0.28 / 1.72;
  const std::vector<TruthBox> truths{{0, square(0, 0)}};
  const std::vector<ScoredBox> detections{{0, 0.8, square(s, 0)}};
  EXPECT_NEAR(orientedBoxIoU(detections[0].box, truths[0].box), 0.72, 1e-12);
  const ClassDetectionScores scores = scoreDetections(detections, truths);
  EXPECT_NEAR(scores.ap50, 1.0, kScoreTol);
  EXPECT_NEAR(scores.apPerThreshold[4], 1.0, kScoreTol);  // IoU 0.70
  EXPECT_NEAR(scores.apPerThreshold[5], 0.0, kScoreTol);  // IoU 0.75
  EXPECT_NEAR(scores.ap50_95, 0.5, kScoreTol);
}

TEST(DetectionMetrics, EmptyCasesAndBadThreshold)
{
  EXPECT_TRUE(std::isnan(averagePrecision({}, 0)));
  EXPECT_NEAR(averagePrecision({}, 2), 0.0, kScoreTol);  // nothing detected: AP 0
  const ClassDetectionScores none = scoreDetections({}, {{0, square(0, 0)}});
  EXPECT_TRUE(std::isnan(none.precision));
  EXPECT_NEAR(none.recall, 0.0, kScoreTol);
  // Detections in an image without truth are false positives.
  const ClassDetectionScores fp = scoreDetections({{3, 0.9, square(0, 0)}}, {{0, square(0, 0)}});
  EXPECT_NEAR(fp.precision, 0.0, kScoreTol);
  EXPECT_THROW(matchDetections({}, {}, 0.0), srp::core::InvalidInputError);
  EXPECT_THROW(matchDetections({}, {}, 1.5), srp::core::InvalidInputError);
}
