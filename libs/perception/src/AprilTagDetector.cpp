#include "srp/perception/AprilTagDetector.h"

#include <visp3/core/vpCameraParameters.h>
#include <visp3/core/vpImage.h>
#include <visp3/core/vpMeterPixelConversion.h>
#include <visp3/core/vpPoint.h>
#include <visp3/detection/vpDetectorAprilTag.h>

#include <cmath>
#include <cstring>
#include <map>
#include <opencv2/imgproc.hpp>

#include "srp/core/Error.h"
#include "srp/interop/PoseConversions.h"

namespace srp::perception {

struct AprilTagDetector::Impl {
  vpDetectorAprilTag detector{vpDetectorAprilTag::TAG_36h11, vpDetectorAprilTag::HOMOGRAPHY_VIRTUAL_VS};
  vpImage<unsigned char> grey;
  cv::Mat greyMat;
};

AprilTagDetector::AprilTagDetector(const Options& options) : impl_(std::make_unique<Impl>()), options_(options) {
  core::require(options.tagSize_m > 0.0, "AprilTagDetector: tag size must be positive (metres), got " +
                                             std::to_string(options.tagSize_m));
  impl_->detector.setAprilTagQuadDecimate(options.quadDecimate);
  impl_->detector.setAprilTagNbThreads(std::max(1, options.threads));
  impl_->detector.setDisplayTag(false);
}

AprilTagDetector::~AprilTagDetector() = default;

std::vector<TagDetection> AprilTagDetector::detect(const cv::Mat& image, const core::CameraIntrinsics& k) {
  core::require(!image.empty() && (image.type() == CV_8UC3 || image.type() == CV_8UC1),
                "AprilTagDetector: image must be CV_8UC3 (BGR) or CV_8UC1");
  if (image.channels() == 3) cv::cvtColor(image, impl_->greyMat, cv::COLOR_BGR2GRAY);
  else impl_->greyMat = image;
  if (!impl_->greyMat.isContinuous()) impl_->greyMat = impl_->greyMat.clone();
  impl_->grey.resize(static_cast<unsigned>(impl_->greyMat.rows), static_cast<unsigned>(impl_->greyMat.cols));
  std::memcpy(impl_->grey.bitmap, impl_->greyMat.data, impl_->greyMat.total());

  vpCameraParameters cam;
  cam.initPersProjWithoutDistortion(k.fx_px, k.fy_px, k.cx_px, k.cy_px);
  std::vector<vpHomogeneousMatrix> cMo;
  impl_->detector.detect(impl_->grey, options_.tagSize_m, cam, cMo);

  const std::vector<int> ids = impl_->detector.getTagsId();
  const std::vector<std::vector<vpImagePoint>> corners = impl_->detector.getTagsCorners();
  std::map<int, double> sizes;
  for (int id : ids) sizes[id] = options_.tagSize_m;
  const std::vector<std::vector<vpPoint>> points3d = impl_->detector.getTagsPoints3D(ids, sizes);

  std::vector<TagDetection> out;
  for (std::size_t i = 0; i < ids.size() && i < cMo.size(); ++i) {
    if (corners[i].size() != 4 || points3d[i].size() != 4) continue;
    TagDetection t;
    t.id = ids[i];
    // ViSP's tag frame has y up and z out of the tag (towards the camera);
    // AprilTag's, used here: y down as read, z into the tag.
    const Eigen::Matrix3d F = Eigen::Vector3d(1, -1, -1).asDiagonal();
    t.X_camera_tag = interop::fromVisp(cMo[i]);
    t.X_camera_tag.linear() = t.X_camera_tag.linear() * F;
    double sq = 0.0;
    for (int c = 0; c < 4; ++c) {
      t.corners_px[c] = {corners[i][c].get_u(), corners[i][c].get_v()};
      t.corners_tag_m[c] = F * Eigen::Vector3d(points3d[i][c].get_oX(), points3d[i][c].get_oY(), points3d[i][c].get_oZ());
      t.centre_px += t.corners_px[c] / 4.0;
      const Eigen::Vector3d p = t.X_camera_tag * t.corners_tag_m[c];
      if (p.z() > 0) {
        const Eigen::Vector2d uv(k.fx_px * p.x() / p.z() + k.cx_px, k.fy_px * p.y() / p.z() + k.cy_px);
        sq += (uv - t.corners_px[c]).squaredNorm();
      }
    }
    t.reprojectionError_px = std::sqrt(sq / 4.0);
    out.push_back(t);
  }
  return out;
}

}  // namespace srp::perception
