#include "srp/perception/CameraMotionEstimator.h"

#include <Eigen/Geometry>
#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>
#include <opencv2/rgbd.hpp>

#include "srp/core/Error.h"

namespace srp::perception {

struct CameraMotionEstimator::Impl {
  cv::Ptr<cv::rgbd::ICPOdometry> odometry;
  cv::Ptr<cv::rgbd::OdometryFrame> key;
  core::Pose3 X_camera0_key = core::Pose3::Identity();
  core::Pose3 X_key_last = core::Pose3::Identity();  ///< the last aligned frame's camera in the key frame's
  cv::Size size;
};

namespace {

double rotationAngle(const core::Pose3& X) { return Eigen::AngleAxisd(X.linear()).angle(); }

cv::Mat toCv(const core::Pose3& X) {
  cv::Mat m(4, 4, CV_64FC1);
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) m.at<double>(r, c) = X.matrix()(r, c);
  return m;
}

core::Pose3 fromCv(const cv::Mat& m) {
  core::Pose3 X = core::Pose3::Identity();
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) X.matrix()(r, c) = m.at<double>(r, c);
  return X;
}

}  // namespace

CameraMotionEstimator::CameraMotionEstimator(const core::CameraIntrinsics& intrinsics)
    : CameraMotionEstimator(intrinsics, Options{}) {}

CameraMotionEstimator::CameraMotionEstimator(const core::CameraIntrinsics& k, const Options& o)
    : impl_(std::make_unique<Impl>()), options_(o) {
  if (o.downscale < 1 || o.checkStride < 1 || o.iterations.empty())
    throw core::InvalidInputError("camera motion options: downscale and checkStride must be >= 1 and iterations "
                                  "non-empty (got downscale " + std::to_string(o.downscale) + ", checkStride " +
                                  std::to_string(o.checkStride) + ")");
  const double s = o.downscale;
  const cv::Mat K = (cv::Mat_<double>(3, 3) << k.fx_px / s, 0, (k.cx_px + 0.5) / s - 0.5, 0, k.fy_px / s,
                     (k.cy_px + 0.5) / s - 0.5, 0, 0, 1);
  impl_->odometry = cv::rgbd::ICPOdometry::create(K, static_cast<float>(o.minDepth_m), static_cast<float>(o.maxDepth_m),
                                                  static_cast<float>(o.maxDepthDiff_m),
                                                  static_cast<float>(o.maxPointsPart), o.iterations);
  impl_->size = cv::Size(k.width_px / o.downscale, k.height_px / o.downscale);
}

CameraMotionEstimator::~CameraMotionEstimator() = default;

core::Pose3 CameraMotionEstimator::add(const rawlog::RgbdFrame& frame, const cv::Mat& mask) {
  Impl& m = *impl_;
  const int i = static_cast<int>(poses_.size());
  const core::Pose3 previous = poses_.empty() ? core::Pose3::Identity() : poses_.back();
  if (i > 0 && !moved() && i % options_.checkStride != 0) {
    poses_.push_back(previous);
    return previous;
  }
  // The reduced depth (nearest pixel: no depth mixed across an edge), invalid = NaN.
  cv::Mat depth;
  cv::resize(frame.depth_m, depth, m.size, 0, 0, cv::INTER_NEAREST);
  depth.setTo(std::numeric_limits<float>::quiet_NaN(), depth <= 0.0f);
  cv::Mat small(m.size, CV_8UC1, cv::Scalar(255));
  if (!mask.empty()) cv::resize(mask, small, m.size, 0, 0, cv::INTER_NEAREST);
  auto current = cv::rgbd::OdometryFrame::create(cv::Mat(), depth, small);
  if (i == 0) {
    m.odometry->prepareFrameCache(current, cv::rgbd::OdometryFrame::CACHE_SRC);
    m.key = current;
    poses_.push_back(core::Pose3::Identity());
    return poses_.back();
  }
  m.odometry->prepareFrameCache(current, cv::rgbd::OdometryFrame::CACHE_ALL);
  cv::Mat Rt;  // X_current_key: key-frame points into the current camera
  const bool ok = m.odometry->compute(m.key, current, Rt, toCv(m.X_key_last.inverse()));
  core::Pose3 pose = previous;
  if (ok) {
    m.X_key_last = fromCv(Rt).inverse();
    pose = m.X_camera0_key * m.X_key_last;
  } else {
    ++failures_;
  }
  poses_.push_back(pose);
  // A new key frame after a failure (the chain goes on from the last pose) or far from the key.
  if (!ok || m.X_key_last.translation().norm() > options_.keyFrameTranslation_m ||
      rotationAngle(m.X_key_last) > options_.keyFrameRotation_rad) {
    m.key = current;
    m.X_camera0_key = pose;
    m.X_key_last = core::Pose3::Identity();
  }
  const double t = pose.translation().norm(), r = rotationAngle(pose);
  maxTranslation_m_ = std::max(maxTranslation_m_, t);
  maxRotation_rad_ = std::max(maxRotation_rad_, r);
  if (movedAt_ < 0 && (t > options_.movedTranslation_m || r > options_.movedRotation_rad)) movedAt_ = i;
  return pose;
}

}  // namespace srp::perception
