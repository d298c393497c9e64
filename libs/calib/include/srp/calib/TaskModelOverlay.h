#pragma once
/// \file TaskModelOverlay.h
/// \brief Draws a task model's hand and object trajectories, its per-frame
/// object detections and the current skill on the frames of the demonstration
/// it was programmed from (srp replay --overlay).

#include <opencv2/core.hpp>

#include "srp/rawlog/RgbdFrame.h"
#include "srp/taskdb/TaskModel.h"

namespace srp::calib {

/// Overlay for one task model. Positions of the model are in its frame
/// (TaskModelInfo::frame): "camera" (the optical frame, used as is) or "base"
/// (mapped to the camera with X_base_camera, which the model must then have).
/// Frame `index` of the rawlog is TimeId `index + firstTimeId` of the model.
/// Drawn: the hand track (white) and each grounded object's track (one colour
/// per class) up to the current frame, the current object positions (filled
/// when detected in this frame, hollow when carried forward) with the class
/// name and the skill the object is in.
class TaskModelOverlay {
 public:
  /// Throws InvalidInputError for a frame other than camera/base, or "base" without X_base_camera.
  explicit TaskModelOverlay(srp::taskdb::TaskModel model, int firstTimeId = 0);

  /// Draws onto `bgr8` (the colour image of `frame`, same size as its intrinsics).
  void draw(cv::Mat& bgr8, const srp::rawlog::RgbdFrame& frame) const;

 private:
  Eigen::Vector3d toCamera(const Eigen::Vector3d& p_model_m) const;
  srp::taskdb::TaskModel model_;
  srp::core::Pose3 X_camera_model_ = srp::core::Pose3::Identity();
  int firstTimeId_ = 0;
};

}  // namespace srp::calib
