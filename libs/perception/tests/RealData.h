#pragma once
// Shared helpers of the tests on datasets/real/visp-rbt-cube (ViSP's RBT
// RealSense recording; credits in datasets/real/README.md).
#include <string>
#include <vector>

#include "srp/core/Json.h"
#include "srp/core/Pose.h"

namespace srp::perception::testing {

inline std::string rbtFolder() { return std::string(SRP_DATASETS_DIR) + "/real/visp-rbt-cube"; }

inline core::Pose3 poseFromRows(const nlohmann::json& m) {
  core::Pose3 X = core::Pose3::Identity();
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) X.linear()(r, c) = m[r][c].get<double>();
    X.translation()[r] = m[r][3].get<double>();
  }
  return X;
}

/// The stored board pose of every frame (X_camera_board).
inline std::vector<core::Pose3> storedBoardPoses() {
  const auto j = core::readJsonFile(rbtFolder() + "/apriltag_board_poses.json");
  std::vector<core::Pose3> out;
  for (const auto& m : j.at("grid_pose_in_camera_per_frame")) out.push_back(poseFromRows(m));
  return out;
}

/// The cube's stored frame-0 pose (its centre, X_camera_cube).
inline core::Pose3 storedCubePoseFrame0() {
  return poseFromRows(core::readJsonFile(rbtFolder() + "/cube_pose_frame0.json"));
}

}  // namespace srp::perception::testing
