#include "srp/perception/DepthCloud.h"

#include <cmath>
#include <vector>

#include "srp/core/Error.h"

namespace srp::perception {

cv::Mat depthToCloud(const cv::Mat& depth_m, const CameraModel& camera, double maxDepth_m) {
  cv::Mat cloud;
  depthToCloud(depth_m, camera, cloud, maxDepth_m);
  return cloud;
}

void depthToCloud(const cv::Mat& depth_m, const CameraModel& camera, cv::Mat& cloud, double maxDepth_m) {
  core::require(depth_m.type() == CV_32FC1, "depthToCloud: depth must be CV_32FC1 metres");
  // Normalised coordinates per column and row through ViSP once; then Z scales them.
  std::vector<float> xs(static_cast<std::size_t>(depth_m.cols)), ys(static_cast<std::size_t>(depth_m.rows));
  for (int u = 0; u < depth_m.cols; ++u) xs[u] = static_cast<float>(camera.pixelToCamera(u, 0, 1.0).x());
  for (int v = 0; v < depth_m.rows; ++v) ys[v] = static_cast<float>(camera.pixelToCamera(0, v, 1.0).y());
  cloud.create(depth_m.size(), CV_32FC3);
  const float zMax = static_cast<float>(maxDepth_m);
  for (int v = 0; v < depth_m.rows; ++v) {
    const float* d = depth_m.ptr<float>(v);
    cv::Vec3f* out = cloud.ptr<cv::Vec3f>(v);
    for (int u = 0; u < depth_m.cols; ++u) {
      const float z = d[u];
      if (z > 0.f && z < zMax && std::isfinite(z)) out[u] = cv::Vec3f(xs[u] * z, ys[v] * z, z);
      else out[u] = cv::Vec3f(0.f, 0.f, 0.f);
    }
  }
}

}  // namespace srp::perception
