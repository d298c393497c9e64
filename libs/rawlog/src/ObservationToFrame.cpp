#include "srp/rawlog/ObservationToFrame.h"

#include <mrpt/obs/CObservation3DRangeScan.h>

#include <cmath>
#include <memory>
#include <mutex>
#include <opencv2/imgproc.hpp>
#include <sstream>

#include "srp/core/Error.h"

namespace srp::rawlog {
namespace {

DepthRegistration::Camera cameraOf(const mrpt::img::TCamera& cam, int cols, int rows) {
  DepthRegistration::Camera out;
  // Some grabbers leave ncols/nrows unset: the image size is what counts.
  out.K = {cam.fx(), cam.fy(), cam.cx(), cam.cy(), cols, rows};
  out.distortion = {cam.k1(), cam.k2(), cam.p1(), cam.p2(), cam.k3()};
  return out;
}

bool sameCamera(const DepthRegistration::Camera& a, const DepthRegistration::Camera& b) {
  return a.K == b.K && a.distortion == b.distortion;
}

// Building a DepthRegistration undistorts every depth pixel's ray once; a
// recording keeps its cameras, so each decoding thread keeps the last one.
const DepthRegistration& cachedRegistration(const ObservationCameras& cams) {
  thread_local std::unique_ptr<DepthRegistration> cached;
  if (!cached || !sameCamera(cached->depthCamera(), cams.depth) || !sameCamera(cached->colourCamera(), cams.colour) ||
      !cached->X_colour_depth().isApprox(cams.X_colour_depth, 0.0))
    cached = std::make_unique<DepthRegistration>(cams.depth, cams.colour, cams.X_colour_depth);
  return *cached;
}

}  // namespace

ObservationCameras observationCameras(const mrpt::obs::CObservation3DRangeScan& obs) {
  ObservationCameras c;
  const int rows = static_cast<int>(obs.rangeImage.rows()), cols = static_cast<int>(obs.rangeImage.cols());
  c.depth = cameraOf(obs.cameraParams, cols, rows);
  const bool hasColour = obs.hasIntensityImage && !obs.intensityImage.isEmpty();
  const int colourCols = hasColour ? static_cast<int>(obs.intensityImage.getWidth()) : cols;
  const int colourRows = hasColour ? static_cast<int>(obs.intensityImage.getHeight()) : rows;
  c.colour = cameraOf(obs.cameraParamsIntensity, colourCols, colourRows);
  c.sameSize = colourCols == cols && colourRows == rows;
  c.mrptCoincide = obs.doDepthAndIntensityCamerasCoincide();
  // relativePoseIntensityWRTDepth is the colour optical frame in the depth
  // sensor's frame (x forward, y left, z up); the depth optical frame sits in
  // that frame at MRPT's reference rotation (yaw -90, pitch 0, roll -90 deg).
  const mrpt::poses::CPose3D depthOptical(0, 0, 0, -M_PI / 2, 0, -M_PI / 2);
  const mrpt::poses::CPose3D X_depthOptical_colour = -depthOptical + obs.relativePoseIntensityWRTDepth;
  const auto H = X_depthOptical_colour.getHomogeneousMatrixVal<mrpt::math::CMatrixDouble44>();
  srp::core::Pose3 X_depth_colour = srp::core::Pose3::Identity();
  for (int r = 0; r < 3; ++r)
    for (int k = 0; k < 4; ++k) X_depth_colour.matrix()(r, k) = H(r, k);
  c.X_colour_depth = X_depth_colour.inverse();
  c.baseline_m = X_depth_colour.translation().norm();
  c.rotation_rad = Eigen::AngleAxisd(X_depth_colour.linear()).angle();
  return c;
}

bool needsRegistration(const ObservationCameras& c, std::string* reason) {
  std::ostringstream why;
  bool need = true;
  if (!c.sameSize) {
    why << "depth " << c.depth.K.width_px << "x" << c.depth.K.height_px << " and colour " << c.colour.K.width_px << "x"
        << c.colour.K.height_px << " differ in size";
  } else if (c.baseline_m > kCoincideBaseline_m || c.rotation_rad > kCoincideRotation_rad) {
    why << "colour camera " << 1e3 * c.baseline_m << " mm and " << c.rotation_rad * 180.0 / M_PI
        << " deg from the depth camera";
  } else {
    need = false;
    why << "depth and colour cameras coincide (" << 1e3 * c.baseline_m << " mm, " << c.rotation_rad * 180.0 / M_PI
        << " deg apart; MRPT's coincide flag: " << (c.mrptCoincide ? "yes" : "no") << ")";
  }
  if (reason) *reason = why.str();
  return need;
}

RgbdFrame frameFromObservation(const mrpt::obs::CObservation3DRangeScan& obs, int index, DepthRegistrationMode mode) {
  RgbdFrame f;
  f.index = index;
  f.t_s = mrpt::Clock::toDouble(obs.timestamp);
  const ObservationCameras cams = observationCameras(obs);
  f.intrinsics = cams.depth.K;
  const int rows = cams.depth.K.height_px, cols = cams.depth.K.width_px;
  cv::Mat depth(rows, cols, CV_32FC1);
  const float units = obs.rangeUnits;
  const auto& K = cams.depth.K;
  for (int r = 0; r < rows; ++r) {
    float* d = depth.ptr<float>(r);
    for (int c = 0; c < cols; ++c) d[c] = static_cast<float>(obs.rangeImage(r, c)) * units;
    if (!obs.range_is_depth)  // range along the ray: Z = range / |(x, y, 1)|
      for (int c = 0; c < cols; ++c) {
        const double x = (c - K.cx_px) / K.fx_px, y = (r - K.cy_px) / K.fy_px;
        d[c] = static_cast<float>(d[c] / std::sqrt(1.0 + x * x + y * y));
      }
  }
  const bool hasColour = obs.hasIntensityImage && !obs.intensityImage.isEmpty();
  cv::Mat bgr;
  if (hasColour) {
    cv::Mat img = obs.intensityImage.asCvMat<cv::Mat>(mrpt::img::SHALLOW_COPY);
    if (img.channels() == 1) cv::cvtColor(img, bgr, cv::COLOR_GRAY2BGR);
    else bgr = img.clone();
  }
  const bool doRegister = hasColour && (mode == DepthRegistrationMode::Register ||
                                        (mode == DepthRegistrationMode::Auto && needsRegistration(cams)));
  if (doRegister) {
    f.depth_m = cachedRegistration(cams).registerDepth(depth);
    f.intrinsics = cams.colour.K;
    f.depthRegisteredOnRead = true;
    f.colour_bgr8 = bgr;
    return f;
  }
  f.depth_m = depth;
  if (hasColour) {
    if (bgr.cols != cols || bgr.rows != rows) cv::resize(bgr, bgr, cv::Size(cols, rows), 0, 0, cv::INTER_LINEAR);
    f.colour_bgr8 = bgr;
  }
  return f;
}

}  // namespace srp::rawlog
