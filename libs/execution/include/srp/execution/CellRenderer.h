#pragma once
/// \file CellRenderer.h
/// \brief Off-screen pictures of the simulated cell (MRPT's CFBORender, headless
/// through EGL), seen from an orbit camera around the table: the table, the
/// containers, the parts with their catalogue meshes (boxes when a class has no
/// mesh file), the UR5 drawn from its URDF link meshes at the snapshot's joints
/// (forward kinematics through the URDF joint chain, UR light grey), the suction
/// gripper on tool0, and, as an option, the safety checker's arm spheres.
///
/// Gripper model (the URDF's `suction_tool`, tool0 -> tcp = 0.10 m along z): a
/// cylinder r = 20 mm from tool0 to 85 mm (dark grey), then a suction cup
/// r = 12 -> 18 mm from 85 mm to the tcp at 100 mm (black).

#include <Eigen/Core>
#include <memory>
#include <optional>
#include <string>
#include <utility>

#include "srp/execution/CellDescription.h"
#include "srp/execution/CellSimulator.h"
#include "srp/execution/RobotModel.h"

namespace srp::execution {

/// Off-screen pictures of the simulated cell (robot, parts, containers) from an orbit camera.
class CellRenderer {
 public:
  /// The picture's size and the orbit camera.
  struct Options {
    int width_px = 640;
    int height_px = 480;
    double azimuth_deg = -60.0;   ///< orbit camera around the world z axis
    double elevation_deg = 35.0;
    double distance_m = 1.9;  ///< far enough for the whole UR5 above the default cell
    Eigen::Vector3d lookAt_world_m = Eigen::Vector3d(0.0, -0.05, 0.22);
    /// Draw the SafetyChecker's arm spheres (translucent blue) over the meshes.
    bool drawSafetySpheres = false;
  };

  /// Loads the link meshes (RobotModel collision meshes; the UR5 has no separate
  /// visual meshes in srp) and the part meshes. Throws FileError naming a link mesh
  /// that cannot be read, srp::core::Error when no off-screen OpenGL context can be created.
  CellRenderer(RobotModel model, CellDescription cell, Options options);
  CellRenderer(RobotModel model, CellDescription cell)
      : CellRenderer(std::move(model), std::move(cell), Options{}) {}
  ~CellRenderer();

  /// Renders one snapshot into a PNG file; throws FileError when it cannot be written.
  void renderPng(const CellSnapshot& snapshot, const std::string& path);

  /// Pixel (u right, v down, from the top-left corner) and depth [m] of a world point
  /// in the pictures, from the camera of the last render; nullopt behind the camera.
  /// Throws InvalidInputError before the first render.
  std::optional<Eigen::Vector3d> project(const Eigen::Vector3d& p_world_m) const;

  const Options& options() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace srp::execution
