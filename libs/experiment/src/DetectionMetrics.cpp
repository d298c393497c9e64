#include "srp/experiment/DetectionMetrics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>

#include "srp/core/Error.h"

namespace srp::experiment {

namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
}

std::vector<std::pair<double, bool>> matchDetections(const std::vector<ScoredBox>& detections,
                                                     const std::vector<TruthBox>& truths, double iouThreshold)
{
  if (!(iouThreshold > 0.0 && iouThreshold <= 1.0))
    throw core::InvalidInputError("matchDetections: iouThreshold " + std::to_string(iouThreshold) +
                                  " is outside (0, 1]; use e.g. 0.5");
  std::map<int, std::vector<std::size_t>> truthsByImage;
  for (std::size_t t = 0; t < truths.size(); ++t) truthsByImage[truths[t].image].push_back(t);

  std::vector<std::size_t> order(detections.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return detections[a].confidence > detections[b].confidence; });

  std::vector<bool> truthTaken(truths.size(), false);
  std::vector<std::pair<double, bool>> result(detections.size());
  for (const std::size_t d : order) {
    const ScoredBox& det = detections[d];
    double bestIoU = 0.0;
    std::size_t best = truths.size();
    if (const auto it = truthsByImage.find(det.image); it != truthsByImage.end())
      for (const std::size_t t : it->second) {
        if (truthTaken[t]) continue;
        const double iou = orientedBoxIoU(det.box, truths[t].box);
        if (iou > bestIoU) {
          bestIoU = iou;
          best = t;
        }
      }
    const bool tp = best < truths.size() && bestIoU >= iouThreshold;
    if (tp) truthTaken[best] = true;
    result[d] = {det.confidence, tp};
  }
  return result;
}

double averagePrecision(std::vector<std::pair<double, bool>> scored, int truthCount)
{
  if (truthCount <= 0) return kNaN;
  std::stable_sort(scored.begin(), scored.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  std::vector<double> precision, recall;
  int tp = 0;
  for (std::size_t n = 0; n < scored.size(); ++n) {
    tp += scored[n].second ? 1 : 0;
    precision.push_back(static_cast<double>(tp) / static_cast<double>(n + 1));
    recall.push_back(static_cast<double>(tp) / truthCount);
  }
  // Interpolated precision: the best precision at this recall or beyond.
  for (std::size_t n = precision.size(); n-- > 1;) precision[n - 1] = std::max(precision[n - 1], precision[n]);
  double ap = 0.0, previousRecall = 0.0;
  for (std::size_t n = 0; n < precision.size(); ++n) {
    ap += (recall[n] - previousRecall) * precision[n];
    previousRecall = recall[n];
  }
  return ap;
}

ClassDetectionScores scoreDetections(const std::vector<ScoredBox>& detections, const std::vector<TruthBox>& truths)
{
  ClassDetectionScores s;
  s.instances = static_cast<int>(truths.size());
  s.detections = static_cast<int>(detections.size());
  double apSum = 0.0;
  for (std::size_t k = 0; k < kIouThresholds.size(); ++k) {
    const auto matched = matchDetections(detections, truths, kIouThresholds[k]);
    s.apPerThreshold[k] = averagePrecision(matched, s.instances);
    apSum += s.apPerThreshold[k];
    if (k == 0) {
      const auto tp = std::count_if(matched.begin(), matched.end(), [](const auto& m) { return m.second; });
      s.precision = s.detections ? static_cast<double>(tp) / s.detections : kNaN;
      s.recall = s.instances ? static_cast<double>(tp) / s.instances : kNaN;
      s.ap50 = s.apPerThreshold[0];
    }
  }
  s.ap50_95 = s.instances ? apSum / static_cast<double>(kIouThresholds.size()) : kNaN;
  return s;
}

}  // namespace srp::experiment
