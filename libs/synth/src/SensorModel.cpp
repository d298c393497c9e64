#include "srp/synth/SensorModel.h"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

namespace srp::synth {

SensorModel::SensorModel(const SensorModel::Options& options, std::uint32_t seed)
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

namespace {

constexpr int kBlobCell_px = 6;  // dropout blobs: a coarse random grid of this pitch, interpolated

// Standard normal quantile Φ⁻¹(p) by bisection on the CDF (a few calls per frame).
double normalQuantile(double p) {
  if (p <= 0.0) return -1e9;
  if (p >= 1.0) return 1e9;
  double lo = -10.0, hi = 10.0;
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (lo + hi);
    (0.5 * std::erfc(-mid / std::sqrt(2.0)) < p ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

// Bilinear interpolation from a coarse grid of pitch kBlobCell_px, per axis:
// the lower grid index, the upper sample's weight, and 1/sqrt(sum of squared
// weights), which brings the interpolated Gaussian back to unit variance.
struct AxisWeights {
  std::vector<int> index;
  std::vector<float> weight, norm;
  explicit AxisWeights(int n) : index(n), weight(n), norm(n) {
    for (int i = 0; i < n; ++i) {
      const double u = (i + 0.5) / kBlobCell_px;
      index[i] = static_cast<int>(std::floor(u));
      const double w = u - index[i];
      weight[i] = static_cast<float>(w);
      norm[i] = static_cast<float>(1.0 / std::sqrt((1.0 - w) * (1.0 - w) + w * w));
    }
  }
};

}  // namespace

// Smooth random field with a standard normal distribution at every pixel:
// coarse Gaussian noise interpolated, so that dropout forms blobs of a few
// pixels like a real sensor's, not salt and pepper; "field < Φ⁻¹(p)" then
// drops exactly a fraction p of the pixels.
cv::Mat SensorModel::blobField(int rows, int cols) {
  cv::Mat coarse(rows / kBlobCell_px + 2, cols / kBlobCell_px + 2, CV_32FC1);
  rng_.fill(coarse, cv::RNG::NORMAL, 0.0, 1.0);
  const AxisWeights across(cols), down(rows);
  cv::Mat field(rows, cols, CV_32FC1);
  for (int r = 0; r < rows; ++r) {
    const float wy = down.weight[r];
    const float* c0 = coarse.ptr<float>(down.index[r]);
    const float* c1 = coarse.ptr<float>(down.index[r] + 1);
    float* out = field.ptr<float>(r);
    for (int c = 0; c < cols; ++c) {
      const int j = across.index[c];
      const float wx = across.weight[c];
      const float top = c0[j] + wx * (c0[j + 1] - c0[j]), bottom = c1[j] + wx * (c1[j + 1] - c1[j]);
      out[c] = (top + wy * (bottom - top)) * across.norm[c] * down.norm[r];
    }
  }
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
  const float edgeJump = static_cast<float>(options_.edgeJump_m);
  for (int r = 0; r < rows; ++r) {
    const float* d = depth.ptr<float>(r);
    const float* below = depth.ptr<float>(std::min(r + 1, rows - 1));
    unsigned char* e = edge.ptr<unsigned char>(r);
    unsigned char* eBelow = edge.ptr<unsigned char>(std::min(r + 1, rows - 1));
    for (int c = 0; c < cols; ++c) {
      const int cr = std::min(c + 1, cols - 1);
      if (std::abs(d[c] - d[cr]) > edgeJump) e[c] = e[cr] = 255;  // both sides of the jump
      if (std::abs(d[c] - below[c]) > edgeJump) e[c] = eBelow[c] = 255;
    }
  }

  // The blob field is read only under a mask: frames without hand or parts skip it.
  const bool anyMasked = (!handMask.empty() && cv::countNonZero(handMask) > 0) ||
                         (!partMask.empty() && cv::countNonZero(partMask) > 0) ||
                         (!movingMask.empty() && cv::countNonZero(movingMask) > 0);
  const cv::Mat blobs = anyMasked ? blobField(rows, cols) : cv::Mat();
  const cv::Mat uniform = noiseWindow(uniformTable_, rows, cols);
  const cv::Mat gauss = noiseWindow(gaussTable_, rows, cols);

  const double pHand = std::min(0.97, options_.handDropProbability + options_.motionDropPerSpeed_s_per_m * handSpeed_mps);
  const double pPart = options_.objectDropProbability;
  const double pMoving = std::min(0.9, options_.objectDropProbability + options_.motionDropPerSpeed_s_per_m * movingSpeed_mps);
  const bool haveHand = !handMask.empty(), haveParts = !partMask.empty(), haveMoving = !movingMask.empty();
  // Single precision and truncation instead of std::round: this loop runs on
  // every pixel of every frame (depths and steps are positive).
  const float step = static_cast<float>(options_.depthStep_m);
  const float invStep = step > 0.f ? 1.f / step : 0.f;
  const float sigmaBase = static_cast<float>(options_.depthNoiseBase_m);
  const float sigmaPerZ2 = static_cast<float>(options_.depthNoisePerSquareMetre);
  const float pEdge = static_cast<float>(options_.edgeDropProbability);
  // The blob field is standard normal: its p-quantile drops a fraction p.
  const float handThreshold = static_cast<float>(normalQuantile(pHand)), partThreshold = static_cast<float>(normalQuantile(pPart)),
              movingThreshold = static_cast<float>(normalQuantile(pMoving));
  // Noise and blob dropout are drawn per block (2x2 by default, as the colour
  // noise): neighbours at the same depth get the same reading, as when a
  // coarser depth image is registered to the colour camera. Each pixel keeps
  // its own depth, quantisation and σ(z); only the spatial correlation changes.
  // Identical rows compress well: the rawlog shrinks.
  const int block = std::max(1, options_.depthNoiseBlock_px);
  std::vector<int> blockCol(cols);
  for (int c = 0; c < cols; ++c) blockCol[c] = c - c % block;
  for (int r = 0; r < rows; ++r) {
    float* d = depth.ptr<float>(r);
    const unsigned char* e = edge.ptr<unsigned char>(r);
    const float* b = anyMasked ? blobs.ptr<float>(r - r % block) : nullptr;  // read only under a mask
    const float* u = uniform.ptr<float>(r);
    const float* g = gauss.ptr<float>(r - r % block);
    const unsigned char* hm = haveHand ? handMask.ptr<unsigned char>(r) : nullptr;
    const unsigned char* pm = haveParts ? partMask.ptr<unsigned char>(r) : nullptr;
    const unsigned char* mm = haveMoving ? movingMask.ptr<unsigned char>(r) : nullptr;
    for (int c = 0; c < cols; ++c) {
      const float z = d[c];
      if (z <= 0.f) continue;
      const int cb = blockCol[c];
      bool drop = e[c] && u[c] < pEdge;
      if (hm && hm[c]) drop = drop || b[cb] < handThreshold;
      else if (mm && mm[c]) drop = drop || b[cb] < movingThreshold;
      else if (pm && pm[c]) drop = drop || b[cb] < partThreshold;
      if (drop) {
        d[c] = 0.f;
        continue;
      }
      float noisy = z + (sigmaBase + sigmaPerZ2 * z * z) * g[cb];
      if (step > 0.f) noisy = static_cast<float>(static_cast<int>(noisy * invStep + 0.5f)) * step;
      d[c] = noisy > 0.f ? noisy : 0.f;
    }
  }

  if (options_.motionBlur && !previousColour.empty() && previousColour.size() == frame.colour_bgr8.size())
    cv::addWeighted(frame.colour_bgr8, 0.5, previousColour, 0.5, 0.0, frame.colour_bgr8);
  if (options_.colourNoiseSigma > 0.0) {
    // Noise on blocks (2x2 by default, as after demosaicing): a quarter of the
    // entropy of independent pixels, which keeps the rawlog smaller.
    const int block = std::max(1, options_.colourNoiseBlock_px);
    const int blockRows = (rows + block - 1) / block, blockCols = (cols + block - 1) / block;
    cv::Mat noise;
    cv::resize(noiseWindow(colourTable_, blockRows, blockCols), noise, cv::Size(blockCols * block, blockRows * block), 0,
               0, cv::INTER_NEAREST);
    noise = noise(cv::Rect(0, 0, cols, rows));
    cv::add(frame.colour_bgr8, noise, frame.colour_bgr8, cv::noArray(), CV_8UC3);  // saturating, one pass
  }
}

}  // namespace srp::synth
