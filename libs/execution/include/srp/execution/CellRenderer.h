#pragma once
/// \file CellRenderer.h
/// \brief Off-screen pictures of the simulated cell (MRPT's CFBORender, headless
/// through EGL): table, containers, parts at their simulated poses and the arm
/// drawn as its collision spheres, seen from an orbit camera around the table.

#include <memory>
#include <string>

#include "srp/execution/CellDescription.h"
#include "srp/execution/CellSimulator.h"
#include "srp/execution/RobotModel.h"

namespace srp::execution {

struct CellRendererOptions {
  int width_px = 640;
  int height_px = 480;
  double azimuth_deg = -60.0;   ///< orbit camera around the world z axis
  double elevation_deg = 35.0;
  double distance_m = 1.5;
  Eigen::Vector3d lookAt_world_m = Eigen::Vector3d(0.0, 0.0, 0.1);
};

class CellRenderer {
 public:
  /// Throws srp::core::Error when no off-screen OpenGL context can be created.
  CellRenderer(RobotModel model, CellDescription cell, CellRendererOptions options = {});
  ~CellRenderer();

  /// Renders one snapshot into a PNG file; throws FileError when it cannot be written.
  void renderPng(const CellSnapshot& snapshot, const std::string& path);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace srp::execution
