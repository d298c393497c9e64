#pragma once
/// \file CameraFiles.h
/// \brief Reading and writing camera calibration files: ViSP camera XML
/// (vpXmlParserCamera), ROS `camera_info` YAML, OpenCV YAML, and the JSON
/// intrinsics found next to RGB-D recordings. Every srp app reads its camera
/// through loadCameraXml / loadCameraFile.
///
/// The three calibration formats hold the same camera: ViSP's kud is OpenCV's
/// and ROS' first radial coefficient k1 (plumb_bob D = [kud, 0, 0, 0, 0]); a
/// file with other non-zero distortion coefficients is refused when read, since
/// srp models one radial coefficient (CameraCalibration).

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

/// The calibration file formats `srp calibrate --format` writes.
enum class CameraFileFormat {
  Visp,    ///< ViSP camera XML (vpXmlParserCamera), what srp's commands read by default
  Ros,     ///< ROS `camera_info` YAML as camera_calibration_parsers writes it (plumb_bob)
  OpenCv,  ///< OpenCV FileStorage YAML: camera_matrix, distortion_coefficients (as OpenCV's calibration sample)
};

/// "visp", "ros" or "opencv"; throws InvalidInputError naming the bad name.
CameraFileFormat cameraFileFormatFromName(const std::string& name);

/// The file name `srp calibrate` writes by default in the current folder:
/// camera.xml, camera_info.yaml, camera_opencv.yaml.
std::string defaultCameraFileName(CameraFileFormat format);

/// Writes `camera` to `path` (atomically) in `format`. `comment` goes into the
/// ViSP XML and as a YAML comment; `rms_px` (when positive) is stored as the
/// OpenCV file's avg_reprojection_error. Throws FileError when it cannot.
void saveCameraFile(const std::string& path, const CameraCalibration& camera, CameraFileFormat format,
                    const std::string& comment = "", double rms_px = 0.0);

/// Intrinsics from a JSON camera file and the depth scale it may carry. Two
/// layouts are understood: ViSP's RGB-D recordings (`cam.json`: px, py, u0,
/// v0, w, h, optional depthScale [m per depth unit]) and srp's
/// CameraIntrinsics JSON (fx, fy, cx, cy, width, height, optional
/// depth_scale_m), either at top level or under "intrinsics".
struct CameraFile {
  CameraCalibration camera;
  std::optional<double> depthScale_m;
};

/// Reads a camera from `path`: `.xml` through loadCameraXml; `.yaml`/`.yml` as
/// an OpenCV YAML file (first line `%YAML:1.0`) or a ROS camera_info file;
/// anything else as JSON (see CameraFile). Errors name the file and the
/// missing field.
CameraFile loadCameraFile(const std::string& path);

}  // namespace srp::calib
