#pragma once
// Shared helpers of the tests on datasets/real/visp-rbt-cube (ViSP's RBT
// RealSense recording; credits in datasets/real/README.md).
#include <algorithm>
#include <string>
#include <vector>

#include "srp/core/Json.h"
#include "srp/core/Pose.h"

namespace srp::perception::testing {

inline std::string rbtFolder() { return std::string(SRP_DATASETS_DIR) + "/real/visp-rbt-cube"; }

inline core::Pose3 poseFromRows(const nlohmann::json& m) {
  return core::poseFromJson(nlohmann::json{{"matrix", m}}, "4x4 row-major pose");
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

/// The second reference: the stored frame-0 pose carried by the scene's own
/// motion (RGB-D odometry, no tags, cube masked; notebooks_cpp/real_cube),
/// X_camera_cube per frame 0-49.
inline std::vector<core::Pose3> storedScenePoses() {
  const auto j = core::readJsonFile(rbtFolder() + "/scene_odometry_cube_poses.json");
  std::vector<core::Pose3> out;
  for (const auto& m : j.at("cube_pose_in_camera_per_frame")) out.push_back(poseFromRows(m));
  return out;
}

/// The 24 rotations of a cube: a CAD model alone cannot tell its faces apart.
inline std::vector<Eigen::Matrix3d> cubeSymmetries() {
  std::vector<Eigen::Matrix3d> out;
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) {
      if (a == b) continue;
      for (int sa : {-1, 1})
        for (int sb : {-1, 1}) {
          Eigen::Matrix3d R;
          R.col(0) = sa * I.col(a);
          R.col(1) = sb * I.col(b);
          R.col(2) = R.col(0).cross(R.col(1));
          out.push_back(R);
        }
    }
  return out;
}

/// Rotation between two cube orientations modulo the cube's 24 rotations [rad].
inline double cubeAngleError(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
  double best = 1e9;
  for (const auto& S : cubeSymmetries()) best = std::min(best, core::rotationAngleBetween(a * S, b));
  return best;
}

/// The cube's true pose (its centre = cube.obj's frame) in frame i: the board
/// is fixed to the table, so X_ci_cube = X_ci_board X_c0_board^-1 X_c0_cube.
inline core::Pose3 trueCubePose(const std::vector<core::Pose3>& boards, const core::Pose3& X_c0_cube, std::size_t i) {
  return boards.at(i) * boards.at(0).inverse() * X_c0_cube;
}

}  // namespace srp::perception::testing
