#pragma once
/// \file CameraYaml.h
/// \brief The YAML camera files behind loadCameraFile and saveCameraFile
/// (CameraFiles.h): ROS `camera_info` (yaml-cpp) and OpenCV FileStorage YAML.

#include <string>

#include "srp/calib/CameraCalibration.h"

namespace srp::calib {

/// Reads an OpenCV FileStorage YAML (first line `%YAML:1.0`) or a ROS
/// camera_info YAML camera file. Throws FileError naming the file and the
/// missing field, or the distortion srp cannot model.
CameraCalibration loadCameraYaml(const std::string& path);

/// The ROS `camera_info` YAML text of `camera` (yaml-cpp): image size, camera
/// name, K, D (plumb_bob, [kud, 0, 0, 0, 0]), R = identity and the rectified
/// projection P = [K' | 0] with K' = cv::getOptimalNewCameraMatrix(K, D, size,
/// alpha 0), as ROS' camera_calibration computes it for a monocular camera
/// (K' = K without distortion).
/// Doubles with 17 significant digits.
std::string cameraInfoYaml(const CameraCalibration& camera);

/// The OpenCV FileStorage YAML text of `camera` (camera_matrix,
/// distortion_coefficients, image size; `comment` as a YAML comment, `rms_px`
/// as avg_reprojection_error when positive).
std::string openCvYaml(const CameraCalibration& camera, const std::string& comment, double rms_px);

}  // namespace srp::calib
