#pragma once
/// \file TagBoard.h
/// \brief A rigid board of AprilTags and its pose from all visible corners.

#include <map>
#include <optional>
#include <vector>

#include "srp/core/CameraIntrinsics.h"
#include "srp/core/Pose.h"
#include "srp/perception/AprilTagDetector.h"

namespace srp::perception {

/// Where each tag sits on the board: X_board_tag per tag id (tag frame as in
/// TagDetection). Metres.
struct TagBoardLayout {
  double tagSize_m = 0.0;
  std::map<int, core::Pose3> X_board_tag;

  /// A regular grid: tag id = firstId + ix * tagsAlongY + iy; the tag's black
  /// square spans x in [ix s, ix s + tagSize], y in [iy s, iy s + tagSize]
  /// (s = spacing_m, the centre-to-centre distance), z = 0 on the board face,
  /// board origin at the outer corner of the first tag's square; R_board_tag
  /// the (common) orientation of the tags on the board.
  static TagBoardLayout grid(double tagSize_m, double spacing_m, int tagsAlongX, int tagsAlongY, int firstId,
                             const Eigen::Matrix3d& R_board_tag);

  /// The 3 x 4 tag36h11 board (ids 0-11, 0.0955 m tags, spacing 1.25 tag
  /// sizes) of ViSP's RBT recording, in the frame of its stored board poses
  /// (datasets/real/visp-rbt-cube/apriltag_board_poses.json).
  static TagBoardLayout vispRbtBoard();
};

/// Board pose from the detected tags that belong to the board.
struct BoardPose {
  core::Pose3 X_camera_board = core::Pose3::Identity();
  int tagsUsed = 0;
  double rmsReprojection_px = 0.0;
};

/// Pose of the board from all corners of its detected tags (ViSP vpPose,
/// virtual visual servoing initialised from the best single-tag pose).
/// nullopt when no tag of the board is detected. Tags of other sizes/ids are
/// ignored.
std::optional<BoardPose> estimateBoardPose(const std::vector<TagDetection>& tags, const TagBoardLayout& layout,
                                           const core::CameraIntrinsics& intrinsics);

}  // namespace srp::perception
