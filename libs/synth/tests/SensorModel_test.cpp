// The documented sensor statistics (SensorModel::Options, README "Sensor
// realism"): depth noise σ(z), quantisation, dropout rates on edges, hand and
// parts, colour noise; fresh noise every frame, reproducible from the seed.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include <cmath>

#include "srp/synth/SensorModel.h"

using srp::synth::SensorModel;

namespace {

const srp::core::CameraIntrinsics kK{525.0, 525.0, 319.5, 239.5, 640, 480};
constexpr double kSigmaRelTol = 0.08;       // relative tolerance on a measured σ (≥ 10^4 samples)
constexpr double kMeanTol_m = 2e-4;         // depth bias
constexpr double kBlobRateTol = 0.03;       // absolute tolerance on a blob dropout fraction (~10^4 blobs)
constexpr double kEdgeRateTol = 0.05;       // on the edge dropout fraction (960 edge pixels)
constexpr double kColourMeanTol = 0.15;     // colour bias [levels]

srp::rawlog::RgbdFrame flatFrame(double z_m, const cv::Scalar& bgr = cv::Scalar(120, 130, 140)) {
  srp::rawlog::RgbdFrame f;
  f.intrinsics = kK;
  f.colour_bgr8 = cv::Mat(kK.height_px, kK.width_px, CV_8UC3, bgr);
  f.depth_m = cv::Mat(kK.height_px, kK.width_px, CV_32FC1, cv::Scalar(static_cast<float>(z_m)));
  return f;
}

struct Stats {
  double mean = 0.0, sigma = 0.0, validFraction = 0.0;
};

Stats depthStats(const cv::Mat& noisy, double z_m, const cv::Mat& mask = cv::Mat()) {
  double sum = 0.0, sumSq = 0.0;
  int n = 0, total = 0;
  for (int r = 0; r < noisy.rows; ++r)
    for (int c = 0; c < noisy.cols; ++c) {
      if (!mask.empty() && !mask.at<unsigned char>(r, c)) continue;
      ++total;
      const float d = noisy.at<float>(r, c);
      if (d <= 0.f) continue;
      const double e = d - z_m;
      sum += e;
      sumSq += e * e;
      ++n;
    }
  Stats s;
  s.validFraction = total ? static_cast<double>(n) / total : 0.0;
  if (n > 1) {
    s.mean = sum / n;
    s.sigma = std::sqrt(sumSq / n - s.mean * s.mean);
  }
  return s;
}

}  // namespace

// σ(z) = base + k z², then quantised: measured σ² = σ(z)² + step²/12.
TEST(SensorModel, DepthNoiseGrowsWithDistanceAsDocumented) {
  const SensorModel::Options options;
  SensorModel sensor(options, 7);
  for (const double z : {0.5, 0.9, 1.4}) {
    // Between quantisation levels, so that rounding adds no bias.
    const double z_m = std::floor(z / options.depthStep_m) * options.depthStep_m + 0.37 * options.depthStep_m;
    auto f = flatFrame(z_m);
    sensor.apply(f, cv::Mat(), 0.0, cv::Mat(), cv::Mat(), 0.0, cv::Mat());
    const Stats s = depthStats(f.depth_m, z_m);
    const double sigma = options.depthNoiseBase_m + options.depthNoisePerSquareMetre * z_m * z_m;
    const double expected = std::sqrt(sigma * sigma + options.depthStep_m * options.depthStep_m / 12.0);
    std::cout << "[measured] z " << z_m << " m: depth sigma " << 1e3 * s.sigma << " mm (expected " << 1e3 * expected
              << "), bias " << 1e3 * s.mean << " mm\n";
    EXPECT_NEAR(s.sigma, expected, kSigmaRelTol * expected) << "z " << z_m;
    EXPECT_NEAR(s.mean, 0.0, kMeanTol_m) << "z " << z_m;
    EXPECT_EQ(s.validFraction, 1.0) << "a flat surface without hand or parts keeps all its depth";
  }
}

TEST(SensorModel, DepthIsQuantisedToTheStep) {
  const SensorModel::Options options;
  SensorModel sensor(options, 3);
  auto f = flatFrame(0.8123);
  sensor.apply(f, cv::Mat(), 0.0, cv::Mat(), cv::Mat(), 0.0, cv::Mat());
  constexpr double kFloatTol_m = 1e-6;
  int offGrid = 0;
  for (int r = 0; r < f.depth_m.rows; ++r)
    for (int c = 0; c < f.depth_m.cols; ++c) {
      const double d = f.depth_m.at<float>(r, c);
      if (std::abs(d / options.depthStep_m - std::round(d / options.depthStep_m)) * options.depthStep_m > kFloatTol_m)
        ++offGrid;
    }
  EXPECT_EQ(offGrid, 0);
}

// Depth discontinuities lose about edgeDropProbability of their pixels.
TEST(SensorModel, EdgesLoseDepthAtTheDocumentedRate) {
  const SensorModel::Options options;
  SensorModel sensor(options, 5);
  auto f = flatFrame(0.9);
  f.depth_m(cv::Rect(0, 0, kK.width_px / 2, kK.height_px)).setTo(0.7f);  // a 20 cm step at the middle column
  sensor.apply(f, cv::Mat(), 0.0, cv::Mat(), cv::Mat(), 0.0, cv::Mat());
  const cv::Mat edge = f.depth_m.colRange(kK.width_px / 2 - 1, kK.width_px / 2 + 1);
  const double invalid = 1.0 - cv::countNonZero(edge) / static_cast<double>(edge.total());
  EXPECT_NEAR(invalid, options.edgeDropProbability, kEdgeRateTol);
  const cv::Mat away = f.depth_m.colRange(0, kK.width_px / 2 - 2);
  EXPECT_EQ(cv::countNonZero(away), static_cast<int>(away.total())) << "no dropout away from the edge";
}

// Blob dropout: hand at rest ~handDropProbability, more when it moves; parts objectDropProbability.
TEST(SensorModel, HandAndPartsLoseDepthAtTheDocumentedRates) {
  const SensorModel::Options options;
  cv::Mat hand(kK.height_px, kK.width_px, CV_8UC1, cv::Scalar(0)), part = hand.clone(), moving = hand.clone();
  hand(cv::Rect(0, 0, 320, 240)).setTo(255);
  part(cv::Rect(320, 0, 320, 240)).setTo(255);
  moving(cv::Rect(0, 240, 320, 240)).setTo(255);
  constexpr double kHandSpeed_mps = 0.5, kMovingSpeed_mps = 0.4;
  double handRest = 0.0, handMoving = 0.0, parts = 0.0, carried = 0.0;
  constexpr int kFrames = 6;
  SensorModel sensor(options, 11);
  for (int k = 0; k < kFrames; ++k) {
    auto still = flatFrame(0.85);
    sensor.apply(still, hand, 0.0, part, moving, kMovingSpeed_mps, cv::Mat());
    handRest += depthStats(still.depth_m, 0.85, hand).validFraction / kFrames;
    parts += depthStats(still.depth_m, 0.85, part).validFraction / kFrames;
    carried += depthStats(still.depth_m, 0.85, moving).validFraction / kFrames;
    auto fast = flatFrame(0.85);
    sensor.apply(fast, hand, kHandSpeed_mps, cv::Mat(), cv::Mat(), 0.0, cv::Mat());
    handMoving += depthStats(fast.depth_m, 0.85, hand).validFraction / kFrames;
  }
  std::cout << "[measured] valid depth: hand at rest " << handRest << ", hand at " << kHandSpeed_mps << " m/s "
            << handMoving << ", parts " << parts << ", carried part " << carried << "\n";
  EXPECT_NEAR(1.0 - handRest, options.handDropProbability, kBlobRateTol);
  EXPECT_NEAR(1.0 - handMoving, options.handDropProbability + options.motionDropPerSpeed_s_per_m * kHandSpeed_mps,
              kBlobRateTol);
  EXPECT_NEAR(1.0 - parts, options.objectDropProbability, kBlobRateTol);
  EXPECT_NEAR(1.0 - carried, options.objectDropProbability + options.motionDropPerSpeed_s_per_m * kMovingSpeed_mps,
              kBlobRateTol);
}

// Colour noise: zero mean, σ = colourNoiseSigma levels per channel.
TEST(SensorModel, ColourNoiseHasTheDocumentedSigma) {
  const SensorModel::Options options;
  SensorModel sensor(options, 13);
  const cv::Scalar clean(120, 130, 140);
  auto f = flatFrame(0.85, clean);
  sensor.apply(f, cv::Mat(), 0.0, cv::Mat(), cv::Mat(), 0.0, cv::Mat());
  cv::Mat diff;
  f.colour_bgr8.convertTo(diff, CV_32FC3);
  diff -= cv::Scalar(clean[0], clean[1], clean[2]);
  cv::Scalar mean, sigma;
  cv::meanStdDev(diff, mean, sigma);
  for (int ch = 0; ch < 3; ++ch) {
    EXPECT_NEAR(mean[ch], 0.0, kColourMeanTol) << "channel " << ch;
    EXPECT_NEAR(sigma[ch], options.colourNoiseSigma, kSigmaRelTol * options.colourNoiseSigma) << "channel " << ch;
  }
  // One noise value per colourNoiseBlock_px block; neighbouring blocks independent.
  const int block = options.colourNoiseBlock_px;
  int uniformBlocks = 0, blocks = 0, differingNeighbours = 0;
  for (int r = 0; r + block <= kK.height_px; r += block)
    for (int c = 0; c + 2 * block <= kK.width_px; c += block, ++blocks) {
      const cv::Vec3b v = f.colour_bgr8.at<cv::Vec3b>(r, c);
      bool same = true;
      for (int dr = 0; dr < block; ++dr)
        for (int dc = 0; dc < block; ++dc) same = same && f.colour_bgr8.at<cv::Vec3b>(r + dr, c + dc) == v;
      uniformBlocks += same;
      differingNeighbours += f.colour_bgr8.at<cv::Vec3b>(r, c + block) != v;
    }
  EXPECT_EQ(uniformBlocks, blocks);
  EXPECT_GT(differingNeighbours, blocks / 2);
}

// Fresh noise every frame (uncorrelated in time), the same sequence for the same seed.
TEST(SensorModel, NoiseIsFreshPerFrameAndReproducible) {
  const SensorModel::Options options;
  SensorModel a(options, 21), b(options, 21), c(options, 22);
  auto a1 = flatFrame(0.9), a2 = flatFrame(0.9), b1 = flatFrame(0.9), c1 = flatFrame(0.9);
  a.apply(a1, cv::Mat(), 0.0, cv::Mat(), cv::Mat(), 0.0, cv::Mat());
  a.apply(a2, cv::Mat(), 0.0, cv::Mat(), cv::Mat(), 0.0, cv::Mat());
  b.apply(b1, cv::Mat(), 0.0, cv::Mat(), cv::Mat(), 0.0, cv::Mat());
  c.apply(c1, cv::Mat(), 0.0, cv::Mat(), cv::Mat(), 0.0, cv::Mat());
  EXPECT_EQ(cv::norm(a1.depth_m, b1.depth_m, cv::NORM_INF), 0.0);
  EXPECT_EQ(cv::norm(a1.colour_bgr8, b1.colour_bgr8, cv::NORM_INF), 0.0);
  EXPECT_GT(cv::norm(a1.depth_m, c1.depth_m, cv::NORM_INF), 0.0);
  // Correlation of the depth noise between consecutive frames.
  cv::Mat n1 = a1.depth_m - 0.9f, n2 = a2.depth_m - 0.9f;
  const double corr = n1.dot(n2) / std::sqrt(n1.dot(n1) * n2.dot(n2));
  constexpr double kMaxTemporalCorrelation = 0.05;
  EXPECT_LT(std::abs(corr), kMaxTemporalCorrelation);
}

// Depth noise is drawn per depthNoiseBlock_px block: on a flat surface the
// pixels of a 2x2 block read the same; with blocks of 1 px (the default)
// neighbours are independent.
TEST(SensorModel, DepthNoiseBlocksAreUniformOnFlatSurfaces) {
  SensorModel::Options options;
  options.depthNoiseBlock_px = 2;
  SensorModel blocky(options, 31);
  auto f = flatFrame(0.85);
  blocky.apply(f, cv::Mat(), 0.0, cv::Mat(), cv::Mat(), 0.0, cv::Mat());
  int uniformBlocks = 0, blocks = 0, differingPairs = 0;
  for (int r = 0; r < kK.height_px; r += 2)
    for (int c = 0; c < kK.width_px; c += 2, ++blocks) {
      const float v = f.depth_m.at<float>(r, c);
      uniformBlocks += v == f.depth_m.at<float>(r, c + 1) && v == f.depth_m.at<float>(r + 1, c) &&
                       v == f.depth_m.at<float>(r + 1, c + 1);
      differingPairs += v != f.depth_m.at<float>(r, c + 2 < kK.width_px ? c + 2 : 0);
    }
  EXPECT_EQ(uniformBlocks, blocks);
  EXPECT_GT(differingPairs, blocks / 2) << "neighbouring blocks are independent";

  options.depthNoiseBlock_px = 1;
  SensorModel perPixel(options, 31);
  auto g = flatFrame(0.85);
  perPixel.apply(g, cv::Mat(), 0.0, cv::Mat(), cv::Mat(), 0.0, cv::Mat());
  const cv::Mat n = g.depth_m - 0.85f;
  const cv::Mat left = n.colRange(0, kK.width_px - 1), right = n.colRange(1, kK.width_px);
  const double corr = left.dot(right) / std::sqrt(left.dot(left) * right.dot(right));
  constexpr double kMaxNeighbourCorrelation = 0.05;
  EXPECT_LT(std::abs(corr), kMaxNeighbourCorrelation);
}
