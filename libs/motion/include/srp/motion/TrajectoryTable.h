#pragma once
/// \file TrajectoryTable.h
/// \brief Hand and object trajectories as one CSV table, for data recorded by
/// other systems (`srp segment --trajectories demo.csv`).
///
/// Header: `frame,hand_x,hand_y,hand_z,<name>_x,<name>_y,<name>_z,<name>_rz,...`
/// (one group of four columns per object, any order of groups). Camera frame,
/// metres, radians (rz = yaw about the camera's z axis). A sample of exact
/// zeros (x = y = z = 0) means "not detected". Frames must increase; sample
/// times are frame / frameRate.

#include <string>
#include <vector>

#include "srp/motion/Segmenter.h"

namespace srp::motion {

struct TrajectoryTable {
  core::PositionTrajectory hand;
  std::vector<ObjectTrack> objects;

  /// Throws FileError (missing/unreadable file) or InvalidInputError naming the
  /// line and column (bad header, wrong column count, text, NaN/inf values,
  /// frames not increasing, fewer than 2 rows).
  static TrajectoryTable readCsv(const std::string& path, double frameRate_hz = 30.0);
  /// Writes the table (`%.17g`, undetected samples as zeros); throws FileError.
  void writeCsv(const std::string& path) const;
};

}  // namespace srp::motion
