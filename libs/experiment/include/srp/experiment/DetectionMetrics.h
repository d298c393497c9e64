#pragma once
/// \file DetectionMetrics.h
/// \brief Object-detection scores as the thesis reports them (section 2.2.4,
/// 6.2.2; tables 8.3/8.4): precision, recall, AP (eq. 2.6), mAP50 and
/// mAP50-95, over oriented image boxes matched by IoU (eq. 6.1).

#include <array>
#include <utility>
#include <vector>

#include "srp/experiment/OrientedBox.h"

namespace srp::experiment {

/// A detection of one class in one image, with the detector's confidence in [0, 1].
struct ScoredBox
{
  int image = 0;
  double confidence = 0.0;
  OrientedBox2d box;
};

/// A ground-truth instance of one class in one image.
struct TruthBox
{
  int image = 0;
  OrientedBox2d box;
};

/// The IoU thresholds of mAP50-95: 0.50, 0.55, ..., 0.95.
constexpr std::array<double, 10> kIouThresholds{0.50, 0.55, 0.60, 0.65, 0.70, 0.75, 0.80, 0.85, 0.90, 0.95};

/// Scores of one class.
struct ClassDetectionScores
{
  int instances = 0;        ///< ground-truth boxes
  int detections = 0;       ///< predicted boxes
  double precision = 0.0;   ///< TP / detections at IoU 0.5, every detection kept (NaN without detections)
  double recall = 0.0;      ///< TP / instances at IoU 0.5 (NaN without instances)
  double ap50 = 0.0;        ///< AP at IoU 0.5 (NaN without instances)
  double ap50_95 = 0.0;     ///< mean AP over kIouThresholds (NaN without instances)
  std::array<double, kIouThresholds.size()> apPerThreshold{};
};

/// Marks each detection true (TP) or false positive at `iouThreshold`: per
/// image, detections in falling confidence each take the unmatched truth box
/// of highest IoU, and are TP when that IoU reaches the threshold (the
/// VOC/COCO rule; one truth box matches at most one detection). Returns
/// (confidence, is TP) per detection, in the input's order.
std::vector<std::pair<double, bool>> matchDetections(const std::vector<ScoredBox>& detections,
                                                     const std::vector<TruthBox>& truths, double iouThreshold);

/// Thesis eq. 2.6, AP = Σ_n (R_n − R_{n−1}) P_n over the detections ranked by
/// falling confidence, with P_n the interpolated precision (the best precision
/// at recall ≥ R_n: the all-point rule of VOC 2010+). `scored` = (confidence,
/// is TP); `truthCount` = ground-truth instances (0 -> NaN). Ties in
/// confidence keep the input order.
double averagePrecision(std::vector<std::pair<double, bool>> scored, int truthCount);

/// All scores of one class over a set of images.
ClassDetectionScores scoreDetections(const std::vector<ScoredBox>& detections, const std::vector<TruthBox>& truths);

}  // namespace srp::experiment
