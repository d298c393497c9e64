#pragma once
/// \file CameraExtrinsics.h
/// \brief Camera-to-robot extrinsics: the pose of the camera's optical frame
/// (x right, y down, z forward) in the robot base frame, estimated from an
/// AprilTag at a known pose or by hand-eye calibration, stored as JSON next to
/// the intrinsics (calib/extrinsics.json).

#include <nlohmann/json_fwd.hpp>
#include <opencv2/core.hpp>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "srp/calib/CameraCalibration.h"
#include "srp/core/Pose.h"

namespace srp::calib {

/// X_base_camera and how it was obtained. File format (schema_version 1):
/// \code{.json}
/// {"schema_version": 1, "X_base_camera": {"translation": [..], "quaternion": [w, x, y, z]},
///  "method": "apriltag", "intrinsics": "camera.xml", "residual": 0.12, "residual_unit": "px", "samples": 1}
/// \endcode
struct CameraExtrinsics {
  static constexpr int kSchemaVersion = 1;
  srp::core::Pose3 X_base_camera = srp::core::Pose3::Identity();
  std::string method;          ///< "apriltag", "hand-eye" or "scene"
  std::string intrinsicsFile;  ///< the camera file used (as given)
  double residual = 0.0;       ///< apriltag: corner reprojection RMS [px]; hand-eye: target position spread [m]
  std::string residualUnit;    ///< "px" or "m"
  int samples = 0;             ///< tags or pose pairs used

  nlohmann::json toJson() const;
  static CameraExtrinsics fromJson(const nlohmann::json& j, const std::string& context);
  /// Atomic write; throws FileError when it cannot.
  void save(const std::string& path) const;
  /// Throws FileError naming the file for a missing file, a bad field or an unknown schema_version.
  static CameraExtrinsics load(const std::string& path);
};

/// One detected tag36h11 tag. Tag frame as ViSP's vpDetectorAprilTag::getPose
/// defines it: origin at the centre of the black square, z out of the tag face
/// (towards the camera that sees it), x and y in the tag plane (on a tag drawn
/// by CalibrationPattern::renderBoard: x towards the print's left edge, y
/// towards its bottom edge). Lengths in metres.
struct TagObservation {
  int id = -1;
  srp::core::Pose3 X_camera_tag = srp::core::Pose3::Identity();
  std::vector<cv::Point2f> corners_px;  ///< ViSP's corner order
  double reprojectionRms_px = 0.0;      ///< of the 4 corners with the estimated pose
};

/// Detects tag36h11 tags in an 8-bit grey or BGR image and estimates each
/// pose for tags whose black square is `tagSize_m` wide.
std::vector<TagObservation> detectTags(const cv::Mat& image, const CameraCalibration& camera, double tagSize_m);

/// X_base_camera from tags lying at known poses (black squares `tagSize_m`
/// wide): one PnP over the corners of every visible tag of `X_base_tag` (ids
/// -> poses, tag frame as in TagObservation). Several tags far apart are much
/// better than one: a single small tag seen face-on leaves the tilt weakly
/// determined (about 0.6 deg and 1 cm for a 0.1 m tag at 0.85 m). nullopt when
/// none of the tags is visible. The residual is the corner reprojection RMS [px].
std::optional<CameraExtrinsics> extrinsicsFromTags(const cv::Mat& image, const CameraCalibration& camera,
                                                   double tagSize_m, const std::map<int, srp::core::Pose3>& X_base_tag);

/// extrinsicsFromTags with one tag.
std::optional<CameraExtrinsics> extrinsicsFromTag(const cv::Mat& image, const CameraCalibration& camera, int tagId,
                                                  double tagSize_m, const srp::core::Pose3& X_base_tag);

/// Eye-to-hand calibration (camera fixed, target held by the robot): from
/// pairs of the gripper pose in base (robot forward kinematics) and the target
/// pose seen by the camera, the camera pose in base (OpenCV's
/// calibrateHandEye, Tsai's method). Needs >= 3 pairs with rotations about
/// different axes; throws InvalidInputError otherwise.
CameraExtrinsics extrinsicsFromHandEye(const std::vector<srp::core::Pose3>& X_base_gripper,
                                       const std::vector<srp::core::Pose3>& X_camera_target);

}  // namespace srp::calib
