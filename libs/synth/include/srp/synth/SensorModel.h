#pragma once
/// \file SensorModel.h
/// \brief Degrades a clean rendered RGB-D frame the way a real depth camera
/// (RealSense L515-like) does, with per-pixel knowledge of hand and objects.

#include <cstdint>
#include <opencv2/core.hpp>

#include "srp/rawlog/RgbdFrame.h"

namespace srp::synth {

/// Applies its Options (sensor realism) to frames, reproducibly from a seed.
class SensorModel {
 public:
  /// Sensor realism parameters. Depth noise σ(z) = depthNoiseBase_m +
  /// depthNoisePerSquareMetre * z² (metres), then quantisation to depthStep_m.
  /// Invalid depth (0): at depth discontinuities, in blobs on the hand (skin and
  /// glove return little signal; the thesis saw < 50 % valid depth there) and on
  /// objects, and more on fast-moving surfaces. The probabilities are the
  /// expected fractions of pixels lost (blobs ~6 px across, from a smooth random
  /// field with a standard normal distribution at every pixel, cut at its quantile).
  struct Options {
    bool enabled = true;
    double depthNoiseBase_m = 5e-4;
    double depthNoisePerSquareMetre = 2e-3;   ///< σ at 1 m: 2.5 mm
    double depthStep_m = 1e-3;
    /// Depth noise and dropout drawn per block of this many pixels squared (1:
    /// per pixel). Each pixel keeps its own depth, σ(z) and quantisation; 2x2
    /// blocks (a coarser depth sensor registered to colour) make the rawlog's
    /// depth 40 % smaller but double the perception module's cuboid yaw error
    /// (fewer independent depth samples), hence per pixel by default.
    int depthNoiseBlock_px = 1;
    double edgeJump_m = 0.01;                 ///< neighbour depth jump that marks an edge
    double edgeDropProbability = 0.7;
    double handDropProbability = 0.45;        ///< blob dropout on the hand at rest
    double objectDropProbability = 0.08;      ///< blob dropout on parts at rest
    double motionDropPerSpeed_s_per_m = 0.4;  ///< extra dropout per m/s of surface speed
    double colourNoiseSigma = 2.0;            ///< 8-bit levels, per colourNoiseBlock_px block
    /// Colour noise drawn per block of this many pixels squared: noise in real
    /// cameras is correlated over several pixels (demosaicing, denoising,
    /// compression); 4x4 blocks make the rawlog's colour less than half of 2x2's.
    int colourNoiseBlock_px = 4;
    bool motionBlur = false;                  ///< average with the previous frame's colour
  };

  SensorModel(const Options& options, std::uint32_t seed);

  /// Degrades `frame` in place. Masks are CV_8UC1, non-zero where the hand /
  /// a resting part / the moving (carried) part is visible; any may be empty.
  /// handSpeed_mps and movingSpeed_mps raise the dropout there.
  /// previousColour: the clean colour of the previous frame for motion blur (may be empty).
  void apply(srp::rawlog::RgbdFrame& frame, const cv::Mat& handMask, double handSpeed_mps, const cv::Mat& partMask,
             const cv::Mat& movingMask, double movingSpeed_mps, const cv::Mat& previousColour);

  const Options& options() const { return options_; }

 private:
  cv::Mat blobField(int rows, int cols);  ///< standard normal at every pixel, smooth over ~6 px
  cv::Mat noiseWindow(cv::Mat& table, int rows, int cols);
  void prepareTables(int rows, int cols);
  Options options_;
  cv::RNG rng_;
  cv::Mat gaussTable_, uniformTable_, colourTable_;
};

}  // namespace srp::synth
