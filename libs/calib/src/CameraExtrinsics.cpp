#include "srp/calib/CameraExtrinsics.h"

#include <visp3/core/vpImageConvert.h>
#include <visp3/detection/vpDetectorAprilTag.h>

#include <nlohmann/json.hpp>
#include <opencv2/calib3d.hpp>
#include <opencv2/core/eigen.hpp>
#include <opencv2/imgproc.hpp>

#include "OpenCvPose.h"
#include "srp/core/Error.h"
#include "srp/core/Json.h"
#include "srp/interop/PoseConversions.h"

namespace srp::calib {

nlohmann::json CameraExtrinsics::toJson() const {
  return {{"schema_version", kSchemaVersion}, {"X_base_camera", core::poseToJson(X_base_camera)},
          {"method", method},                 {"intrinsics", intrinsicsFile},
          {"residual", residual},             {"residual_unit", residualUnit},
          {"samples", samples}};
}

CameraExtrinsics CameraExtrinsics::fromJson(const nlohmann::json& j, const std::string& context) {
  const int version = core::requireField(j, "schema_version", context).get<int>();
  if (version != kSchemaVersion)
    throw core::InvalidInputError(context + ": schema_version " + std::to_string(version) + " is not known (this build reads " +
                                  std::to_string(kSchemaVersion) + ")");
  CameraExtrinsics e;
  e.X_base_camera = core::poseFromJson(core::requireField(j, "X_base_camera", context), context + " X_base_camera");
  e.method = j.value("method", "");
  e.intrinsicsFile = j.value("intrinsics", "");
  e.residual = j.value("residual", 0.0);
  e.residualUnit = j.value("residual_unit", "");
  e.samples = j.value("samples", 0);
  return e;
}

void CameraExtrinsics::save(const std::string& path) const { core::writeJsonFile(path, toJson()); }

CameraExtrinsics CameraExtrinsics::load(const std::string& path) {
  const auto j = core::readJsonFile(path);
  try {
    return fromJson(j, "extrinsics file '" + path + "'");
  } catch (const core::InvalidInputError& e) {
    throw core::FileError(path, e.what());
  } catch (const nlohmann::json::exception& e) {
    throw core::FileError(path, std::string("bad extrinsics JSON: ") + e.what());
  }
}

namespace {

vpCameraParameters toVispCamera(const CameraCalibration& c) {
  const auto& K = c.intrinsics;
  vpCameraParameters cam;
  if (c.hasDistortion()) cam.initPersProjWithDistortion(K.fx_px, K.fy_px, K.cx_px, K.cy_px, c.kud, c.kdu);
  else cam.initPersProjWithoutDistortion(K.fx_px, K.fy_px, K.cx_px, K.cy_px);
  return cam;
}

/// ViSP's tag model: corner i at these (x, y) * tagSize in the tag frame.
constexpr double kCornerInTag[4][2] = {{-0.5, -0.5}, {0.5, -0.5}, {0.5, 0.5}, {-0.5, 0.5}};

}  // namespace

std::vector<TagObservation> detectTags(const cv::Mat& image, const CameraCalibration& camera, double tagSize_m) {
  if (!(tagSize_m > 0.0)) throw core::InvalidInputError("tag size must be positive (metres, the black square's side)");
  cv::Mat grey;
  if (image.channels() == 3) cv::cvtColor(image, grey, cv::COLOR_BGR2GRAY);
  else grey = image;
  if (grey.type() != CV_8UC1) throw core::InvalidInputError("tag detection needs an 8-bit image");
  vpImage<unsigned char> I;
  vpImageConvert::convert(grey, I);
  vpDetectorAprilTag detector(vpDetectorAprilTag::TAG_36h11);
  detector.setAprilTagPoseEstimationMethod(vpDetectorAprilTag::HOMOGRAPHY_VIRTUAL_VS);
  detector.setAprilTagQuadDecimate(1.0f);
  const vpCameraParameters cam = toVispCamera(camera);
  detector.detect(I);
  const auto ids = detector.getTagsId();
  const auto corners = detector.getTagsCorners();
  std::vector<TagObservation> tags;
  for (size_t i = 0; i < ids.size(); ++i) {
    vpHomogeneousMatrix cMo;
    if (!detector.getPose(i, tagSize_m, cam, cMo)) continue;
    TagObservation t;
    t.id = ids[i];
    t.X_camera_tag = interop::fromVisp(cMo);
    double sumSq = 0.0;
    for (int c = 0; c < 4; ++c) {
      t.corners_px.emplace_back(static_cast<float>(corners[i][c].get_u()), static_cast<float>(corners[i][c].get_v()));
      const Eigen::Vector3d p_tag(kCornerInTag[c][0] * tagSize_m, kCornerInTag[c][1] * tagSize_m, 0.0);
      const Eigen::Vector2d uv = camera.projectDistorted(t.X_camera_tag * p_tag);
      sumSq += (uv - Eigen::Vector2d(t.corners_px.back().x, t.corners_px.back().y)).squaredNorm();
    }
    t.reprojectionRms_px = std::sqrt(sumSq / 4.0);
    tags.push_back(t);
  }
  return tags;
}

std::optional<CameraExtrinsics> extrinsicsFromTags(const cv::Mat& image, const CameraCalibration& camera,
                                                   double tagSize_m, const std::map<int, core::Pose3>& X_base_tag) {
  std::vector<cv::Point3d> p_base;
  std::vector<cv::Point2d> uv;  // undistorted pixels
  for (const auto& t : detectTags(image, camera, tagSize_m)) {
    const auto known = X_base_tag.find(t.id);
    if (known == X_base_tag.end()) continue;
    for (int c = 0; c < 4; ++c) {
      const Eigen::Vector3d p = known->second * Eigen::Vector3d(kCornerInTag[c][0] * tagSize_m,
                                                                kCornerInTag[c][1] * tagSize_m, 0.0);
      p_base.emplace_back(p.x(), p.y(), p.z());
      const Eigen::Vector2d u = camera.undistortPixel({t.corners_px[c].x, t.corners_px[c].y});
      uv.emplace_back(u.x(), u.y());
    }
  }
  if (p_base.empty()) return std::nullopt;
  const auto& K = camera.intrinsics;
  const cv::Matx33d Kcv(K.fx_px, 0, K.cx_px, 0, K.fy_px, K.cy_px, 0, 0, 1);
  cv::Mat rvec, tvec;
  cv::solvePnP(p_base, uv, Kcv, cv::noArray(), rvec, tvec, false, cv::SOLVEPNP_SQPNP);
  cv::solvePnPRefineLM(p_base, uv, Kcv, cv::noArray(), rvec, tvec);
  std::vector<cv::Point2d> projected;
  cv::projectPoints(p_base, rvec, tvec, Kcv, cv::noArray(), projected);
  double sumSq = 0.0;
  for (size_t i = 0; i < uv.size(); ++i) sumSq += std::pow(cv::norm(projected[i] - uv[i]), 2);
  CameraExtrinsics e;
  e.X_base_camera = detail::poseFromRvecTvec(rvec, tvec).inverse();
  e.method = "apriltag";
  e.residual = std::sqrt(sumSq / uv.size());
  e.residualUnit = "px";
  e.samples = static_cast<int>(uv.size() / 4);
  return e;
}

std::optional<CameraExtrinsics> extrinsicsFromTag(const cv::Mat& image, const CameraCalibration& camera, int tagId,
                                                  double tagSize_m, const core::Pose3& X_base_tag) {
  return extrinsicsFromTags(image, camera, tagSize_m, {{tagId, X_base_tag}});
}

CameraExtrinsics extrinsicsFromHandEye(const std::vector<core::Pose3>& X_base_gripper,
                                       const std::vector<core::Pose3>& X_camera_target) {
  if (X_base_gripper.size() != X_camera_target.size())
    throw core::InvalidInputError("hand-eye: " + std::to_string(X_base_gripper.size()) + " gripper poses but " +
                                  std::to_string(X_camera_target.size()) + " target poses (they come in pairs)");
  if (X_base_gripper.size() < 3)
    throw core::InvalidInputError("hand-eye: need at least 3 pose pairs (got " + std::to_string(X_base_gripper.size()) + ")");
  // Eye-to-hand: OpenCV's eye-in-hand solver with the gripper poses inverted
  // (base seen from the gripper) returns the camera pose in base.
  std::vector<cv::Mat> R_g, t_g, R_t, t_t;
  const auto push = [](const core::Pose3& X, std::vector<cv::Mat>& R, std::vector<cv::Mat>& t) {
    cv::Mat r, tr;
    const Eigen::Matrix3d rot = X.linear();
    const Eigen::Vector3d trans = X.translation();
    cv::eigen2cv(rot, r);
    cv::eigen2cv(trans, tr);
    R.push_back(r);
    t.push_back(tr);
  };
  for (size_t i = 0; i < X_base_gripper.size(); ++i) {
    push(X_base_gripper[i].inverse(), R_g, t_g);
    push(X_camera_target[i], R_t, t_t);
  }
  cv::Mat R, t;
  cv::calibrateHandEye(R_g, t_g, R_t, t_t, R, t, cv::CALIB_HAND_EYE_TSAI);
  CameraExtrinsics e;
  Eigen::Matrix3d rot;
  Eigen::Vector3d trans;
  cv::cv2eigen(R, rot);
  cv::cv2eigen(t, trans);
  if (!rot.allFinite() || !trans.allFinite())
    throw core::InvalidInputError("hand-eye: degenerate poses (rotate the gripper about at least two different axes)");
  e.X_base_camera.linear() = rot;
  e.X_base_camera.translation() = trans;
  // Residual: spread of the implied (constant) target position on the gripper.
  std::vector<Eigen::Vector3d> p;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (size_t i = 0; i < X_base_gripper.size(); ++i) {
    p.push_back((X_base_gripper[i].inverse() * e.X_base_camera * X_camera_target[i]).translation());
    mean += p.back();
  }
  mean /= static_cast<double>(p.size());
  double sumSq = 0.0;
  for (const auto& x : p) sumSq += (x - mean).squaredNorm();
  e.residual = std::sqrt(sumSq / p.size());
  e.residualUnit = "m";
  e.method = "hand-eye";
  e.samples = static_cast<int>(p.size());
  return e;
}

}  // namespace srp::calib
