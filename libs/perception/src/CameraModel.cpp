#include "srp/perception/CameraModel.h"

#include <visp3/core/vpCameraParameters.h>
#include <visp3/core/vpMeterPixelConversion.h>
#include <visp3/core/vpPixelMeterConversion.h>
#include <visp3/core/vpXmlParserCamera.h>

#include <filesystem>

#include "srp/core/Error.h"

namespace srp::perception {

struct CameraModel::Impl {
  vpCameraParameters cam;
};

CameraModel::CameraModel(const core::CameraIntrinsics& intrinsics)
    : impl_(std::make_unique<Impl>()), intrinsics_(intrinsics) {
  intrinsics.validate("camera intrinsics");
  impl_->cam.initPersProjWithoutDistortion(intrinsics.fx_px, intrinsics.fy_px, intrinsics.cx_px,
                                           intrinsics.cy_px);
}

CameraModel::~CameraModel() = default;
CameraModel::CameraModel(const CameraModel& o)
    : impl_(std::make_unique<Impl>(*o.impl_)), intrinsics_(o.intrinsics_) {}
CameraModel& CameraModel::operator=(const CameraModel& o) {
  if (this != &o) {
    *impl_ = *o.impl_;
    intrinsics_ = o.intrinsics_;
  }
  return *this;
}

CameraModel CameraModel::fromVispXml(const std::string& path, const std::string& cameraName, int width_px,
                                     int height_px) {
  if (!std::filesystem::is_regular_file(path))
    throw core::FileError(path, "camera XML not found (make one with 'srp calibrate')");
  vpXmlParserCamera parser;
  vpCameraParameters cam;
  // The file may store either model; read the undistorted one first, then the distorted one.
  int status = parser.parse(cam, path, cameraName, vpCameraParameters::perspectiveProjWithoutDistortion,
                            static_cast<unsigned>(width_px), static_cast<unsigned>(height_px));
  if (status != vpXmlParserCamera::SEQUENCE_OK)
    status = parser.parse(cam, path, cameraName, vpCameraParameters::perspectiveProjWithDistortion,
                          static_cast<unsigned>(width_px), static_cast<unsigned>(height_px));
  if (status != vpXmlParserCamera::SEQUENCE_OK)
    throw core::FileError(path, "no camera '" + cameraName + "' of size " + std::to_string(width_px) + "x" +
                                    std::to_string(height_px) + " in this ViSP camera XML");
  return CameraModel(core::CameraIntrinsics{cam.get_px(), cam.get_py(), cam.get_u0(), cam.get_v0(), width_px,
                                            height_px});
}

Eigen::Vector3d CameraModel::pixelToCamera(double u_px, double v_px, double depth_m) const {
  double x = 0.0, y = 0.0;
  vpPixelMeterConversion::convertPoint(impl_->cam, u_px, v_px, x, y);
  return {x * depth_m, y * depth_m, depth_m};
}

Eigen::Vector2d CameraModel::cameraToPixel(const Eigen::Vector3d& p_camera_m) const {
  double u = 0.0, v = 0.0;
  vpMeterPixelConversion::convertPoint(impl_->cam, p_camera_m.x() / p_camera_m.z(), p_camera_m.y() / p_camera_m.z(),
                                       u, v);
  return {u, v};
}

}  // namespace srp::perception
