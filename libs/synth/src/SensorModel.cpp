#include "srp/synth/SensorModel.h"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>

namespace srp::synth {

SensorModel::SensorModel(const SensorRealismOptions& options, std::uint32_t seed)
    : options_(options), rng_(static_cast<std::uint64_t>(seed) * 2654435761ull + 1ull) {}

// Drawing fresh Gaussian numbers for every pixel costs more than rendering;
// instead each frame reads a randomly placed window of a table four frames
// large, which is statistically indistinguishable for our purposes.
cv::Mat SensorModel::noiseWindow(cv::Mat& table, int rows, int cols) {
  if (table.empty()) return cv::Mat();
  const int maxRow = table.rows - rows;
  const int row0 = rng_.uniform(0, maxRow + 1);
  const int col0 = rng_.uniform(0, table.cols - cols + 1);
  return table(cv::Rect(col0, row0, cols, rows));
}

void SensorModel::prepareTables(int rows, int cols) {
  if (!gaussTable_.empty() && gaussTable_.rows >= 2 * rows && gaussTable_.cols >= 2 * cols) return;
  gaussTable_.create(2 * rows, 2 * cols, CV_32FC1);
  rng_.fill(gaussTable_, cv::RNG::NORMAL, 0.0, 1.0);
  uniformTable_.create(2 * rows, 2 * cols, CV_32FC1);
  rng_.fill(uniformTable_, cv::RNG::UNIFORM, 0.0, 1.0);
  colourTable_.create(2 * rows, 2 * cols, CV_16SC3);
  rng_.fill(colourTable_, cv::RNG::NORMAL, 0.0, options_.colourNoiseSigma);
}

// Smooth uniform-ish random field in [0, 1]: coarse noise upsampled, so that
// dropout forms blobs of a few pixels like a real sensor's, not salt and pepper.
cv::Mat SensorModel::blobField(int rows, int cols) {
  cv::Mat coarse((rows + 5) / 6, (cols + 5) / 6, CV_32FC1);
  rng_.fill(coarse, cv::RNG::UNIFORM, 0.0, 1.0);
  cv::Mat field;
  cv::resize(coarse, field, cv::Size(cols, rows), 0, 0, cv::INTER_LINEAR);
  return field;
}

void SensorModel::apply(srp::rawlog::RgbdFrame& frame, const cv::Mat& handMask, double handSpeed_mps,
                        const cv::Mat& partMask, const cv::Mat& movingMask, double movingSpeed_mps,
                        const cv::Mat& previousColour) {
  if (!options_.enabled) return;
  const int rows = frame.depth_m.rows, cols = frame.depth_m.cols;
  cv::Mat& depth = frame.depth_m;
  prepareTables(rows, cols);

  // Edges: a depth jump to a neighbour (flying pixels get discarded by real sensors).
  cv::Mat edge(rows, cols, CV_8UC1, cv::Scalar(0));
  for (int r = 0; r < rows; ++r) {
    const float* d = depth.ptr<float>(r);
    const float* below = depth.ptr<float>(std::min(r + 1, rows - 1));
    unsigned char* e = edge.ptr<unsigned char>(r);
    unsigned char* eBelow = edge.ptr<unsigned char>(std::min(r + 1, rows - 1));
    for (int c = 0; c < cols; ++c) {
      const int cr = std::min(c + 1, cols - 1);
      if (std::abs(d[c] - d[cr]) > options_.edgeJump_m) e[c] = e[cr] = 255;  // both sides of the jump
      if (std::abs(d[c] - below[c]) > options_.edgeJump_m) e[c] = eBelow[c] = 255;
    }
  }

  const cv::Mat blobs = blobField(rows, cols);
  const cv::Mat uniform = noiseWindow(uniformTable_, rows, cols);
  const cv::Mat gauss = noiseWindow(gaussTable_, rows, cols);

  const double pHand = std::min(0.97, options_.handDropProbability + options_.motionDropPerSpeed_s_per_m * handSpeed_mps);
  const double pPart = options_.objectDropProbability;
  const double pMoving = std::min(0.9, options_.objectDropProbability + options_.motionDropPerSpeed_s_per_m * movingSpeed_mps);
  const bool haveHand = !handMask.empty(), haveParts = !partMask.empty(), haveMoving = !movingMask.empty();
  const double step = options_.depthStep_m;
  for (int r = 0; r < rows; ++r) {
    float* d = depth.ptr<float>(r);
    const unsigned char* e = edge.ptr<unsigned char>(r);
    const float* b = blobs.ptr<float>(r);
    const float* u = uniform.ptr<float>(r);
    const float* g = gauss.ptr<float>(r);
    const unsigned char* hm = haveHand ? handMask.ptr<unsigned char>(r) : nullptr;
    const unsigned char* pm = haveParts ? partMask.ptr<unsigned char>(r) : nullptr;
    const unsigned char* mm = haveMoving ? movingMask.ptr<unsigned char>(r) : nullptr;
    for (int c = 0; c < cols; ++c) {
      if (d[c] <= 0.f) continue;
      bool drop = e[c] && u[c] < options_.edgeDropProbability;
      if (hm && hm[c]) drop = drop || b[c] < pHand;
      else if (mm && mm[c]) drop = drop || b[c] < pMoving;
      else if (pm && pm[c]) drop = drop || b[c] < pPart;
      if (drop) {
        d[c] = 0.f;
        continue;
      }
      const double z = d[c];
      const double sigma = options_.depthNoiseBase_m + options_.depthNoisePerSquareMetre * z * z;
      double noisy = z + sigma * g[c];
      if (step > 0.0) noisy = std::round(noisy / step) * step;
      d[c] = static_cast<float>(std::max(noisy, 0.0));
    }
  }

  if (options_.motionBlur && !previousColour.empty() && previousColour.size() == frame.colour_bgr8.size())
    cv::addWeighted(frame.colour_bgr8, 0.5, previousColour, 0.5, 0.0, frame.colour_bgr8);
  if (options_.colourNoiseSigma > 0.0) {
    // Noise on 2x2 pixel blocks (as after demosaicing): a quarter of the entropy
    // of independent pixels, which keeps the rawlog a quarter smaller.
    cv::Mat noise;
    cv::resize(noiseWindow(colourTable_, (rows + 1) / 2, (cols + 1) / 2), noise, cv::Size(cols, rows), 0, 0,
               cv::INTER_NEAREST);
    cv::add(frame.colour_bgr8, noise, frame.colour_bgr8, cv::noArray(), CV_8UC3);  // saturating, one pass
  }
}

}  // namespace srp::synth
