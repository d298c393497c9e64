#pragma once
/// \file SilhouetteBranchPicker.h
/// \brief Picks among the symmetric poses of a nearly symmetric part the one
/// whose projected outline matches the part's colour silhouette.

#include <Eigen/Core>
#include <optional>
#include <opencv2/core.hpp>
#include <vector>

#include "srp/core/Pose.h"
#include "srp/perception/CameraModel.h"
#include "srp/kb/TriangleMesh.h"

namespace srp::perception {

/// The five-point star of the knowledge base is 5-fold symmetric only
/// roughly: its frame sits on its bounding box's centre, 2.6 mm from the
/// star's centre, and it is stretched 5 % along y. Depth (noise ~2.5 mm at
/// 0.85 m) fits every one of its five 72-degree turns equally well, but each
/// puts the object origin elsewhere (3.1 or 5.0 mm away). The colour image
/// shows the outline to a pixel: this picks the pose (camera optical frame)
/// whose projected mesh agrees best (intersection over union) with the pixels
/// of the part's colour around its depth segment.
class SilhouetteBranchPicker {
 public:
  struct Options {
    int margin_px = 8;               ///< around the segment's bounding box
    double maxColourDifference = 0.1;  ///< colour mask: every channel within this of the top face's colour, [0, 1]
    double minIoU = 0.8;     ///< best agreement needed to trust the colour mask at all
    double minMargin = 0.01; ///< ... and its lead over the second best (else a partial view)
  };

  SilhouetteBranchPicker() = default;
  explicit SilhouetteBranchPicker(const Options& options) : options_(options) {}

  /// Index into `candidates` of the best-agreeing pose; nullopt without
  /// colour, or when no candidate agrees with the colour mask by minIoU and
  /// by minMargin more than every other (a partial view, a colour like the
  /// background's). `iou`: when given, every candidate's agreement.
  /// `segmentPixels`: the part's depth segment (its median colour is the top face's).
  std::optional<std::size_t> pick(const kb::TriangleMesh& mesh_object, const std::vector<core::Pose3>& candidates,
                                  const std::vector<cv::Point>& segmentPixels, const cv::Mat& colour_bgr8,
                                  const CameraModel& camera,
                                  std::vector<double>* iou = nullptr) const;

 private:
  Options options_;
};

}  // namespace srp::perception
