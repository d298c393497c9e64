#pragma once
// Private to libs/calib: the YAML reader behind loadCameraFile (CameraFiles.h).
#include <string>

#include "srp/calib/CameraCalibration.h"

namespace srp::calib {

/// Reads an OpenCV FileStorage YAML (first line `%YAML:1.0`) or a ROS
/// camera_info YAML camera file. Throws FileError naming the file and the
/// missing field, or the distortion srp cannot model.
CameraCalibration loadCameraYaml(const std::string& path);

}  // namespace srp::calib
