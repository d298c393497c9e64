#pragma once
/// \file CameraFiles.h
/// \brief Reading and writing camera calibration files: ViSP camera XML
/// (vpXmlParserCamera) and the JSON intrinsics found next to RGB-D recordings.
/// Every srp app reads its camera through loadCameraXml / loadCameraFile.

#include <optional>
#include <string>
#include <vector>

#include "srp/calib/CameraCalibration.h"

namespace srp::calib {

/// Names of the <camera> entries of a ViSP camera XML file, in file order.
/// Throws FileError naming the file when it is missing or has no camera.
std::vector<std::string> cameraNamesInXml(const std::string& path);

/// Reads one camera of a ViSP camera XML file with vpXmlParserCamera: the
/// camera named `cameraName`, or the first one when the name is empty.
/// Reads the model with distortion when the file has one, else the one without.
/// Throws FileError naming the file (and the cameras it has) on failure.
CameraCalibration loadCameraXml(const std::string& path, const std::string& cameraName = "");

/// Writes `camera` as a ViSP camera XML file (model with distortion when it
/// has distortion, else without; doubles with 17 significant digits, so
/// reading back gives the same numbers). Replaces an existing file. Throws
/// FileError when it cannot.
void saveCameraXml(const std::string& path, const CameraCalibration& camera,
                   const std::string& comment = "");

/// Intrinsics from a JSON camera file and the depth scale it may carry. Two
/// layouts are understood: ViSP's RGB-D recordings (`cam.json`: px, py, u0,
/// v0, w, h, optional depthScale [m per depth unit]) and srp's
/// CameraIntrinsics JSON (fx, fy, cx, cy, width, height, optional
/// depth_scale_m), either at top level or under "intrinsics".
struct CameraFile {
  CameraCalibration camera;
  std::optional<double> depthScale_m;
};

/// Reads a camera from `path`: `.xml` through loadCameraXml, anything else as
/// JSON (see CameraFile). Errors name the file and the missing field.
CameraFile loadCameraFile(const std::string& path);

}  // namespace srp::calib
