#pragma once
/// \file ObjectPoseFitter.h
/// \brief Fits one CAD model to a segment of the depth cloud: an object
/// standing on a support plane, free in position and in yaw about the plane
/// normal (4 DOF), by ICP from several yaw starts, then a small 6-DOF
/// refinement (tilt) of the best.

#include <Eigen/Core>
#include <memory>
#include <opencv2/core.hpp>
#include <vector>

#include "srp/core/Pose.h"
#include "srp/perception/CameraModel.h"
#include "srp/perception/ObjectModel.h"
#include "srp/perception/PlaneFit.h"

namespace srp::perception {

/// Result of a fit. X_camera_object: the model's object frame in the camera frame.
struct ObjectPoseFit {
  core::Pose3 X_camera_object = core::Pose3::Identity();
  double inlierRatio = 0.0;  ///< segment points within inlierTol of the model surface
  double coverage = 0.0;     ///< visible model surface confirmed by the depth image
  double rms_m = 0.0;        ///< RMS distance of the inlier points to the model [m]
  double score = 0.0;        ///< inlierRatio * coverage, in [0, 1]
};

/// Nearest-surface lookups are precomputed on a 3D grid around the model at
/// construction (a few MB, tens of ms), so fits are fast.
class ObjectPoseFitter {
 public:
  struct Options {
    double inlierTol_m = 0.006;
    int iterations = 30;
    double yawStep_rad = 15.0 * 3.14159265358979323846 / 180.0;  ///< start yaws within the model's symmetry
    int maxPoints = 800;     ///< segment points used (evenly subsampled)
    double gridCell_m = 0.002;
    bool refineTilt = true;      ///< finish with a 6-DOF ICP (tilt against the plane up to maxTilt_rad)
    double maxTilt_rad = 10.0 * 3.14159265358979323846 / 180.0;
  };

  ObjectPoseFitter(const ObjectModel& model, const Options& options);
  explicit ObjectPoseFitter(const ObjectModel& model);
  ~ObjectPoseFitter();
  ObjectPoseFitter(ObjectPoseFitter&&) noexcept;
  ObjectPoseFitter& operator=(ObjectPoseFitter&&) noexcept;

  /// Best 4-DOF pose of the model explaining `points_camera` (one segment),
  /// resting on or above `support`. `cloud` (organised, depthToCloud) and
  /// `camera` score the coverage. From all start yaws when `initial` is not
  /// given, else refined from `initial` only (tracking).
  /// `giveUpBelow`: when even the best coarse start scores below it, that
  /// start's coarse pose and score are returned without the fine stage (a
  /// segment no pose of this model explains costs a fraction of a full fit).
  ObjectPoseFit fit(const std::vector<Eigen::Vector3d>& points_camera, const Plane& support, const cv::Mat& cloud,
                    const CameraModel& camera, const core::Pose3* initial = nullptr, double giveUpBelow = 0.0) const;

  /// The score of the model at X_camera_object without moving it (no ICP):
  /// verifies a known pose (a fixed static object, an unchanged segment) at
  /// a fraction of a fit's cost.
  ObjectPoseFit evaluate(const std::vector<Eigen::Vector3d>& points_camera, const core::Pose3& X_camera_object,
                         const cv::Mat& cloud, const CameraModel& camera) const;

  /// What the cloud says about the model's camera-facing surface samples at
  /// X_camera_object (inside the image): `supported` within inlierTol,
  /// `seenThrough` where the measured depth is farther (the camera sees
  /// through where the surface should be: the object is not there). Samples
  /// with something in front (occlusion) or without depth are no evidence.
  struct SurfaceEvidence {
    int supported = 0;
    int seenThrough = 0;
    int total() const { return supported + seenThrough; }
  };
  SurfaceEvidence surfaceEvidence(const core::Pose3& X_camera_object, const cv::Mat& cloud,
                                  const CameraModel& camera) const;

  /// Fraction of the model surface facing the camera at X_camera_object and
  /// inside the image that the cloud confirms (depth within inlierTol), of
  /// the samples with evidence (surfaceEvidence); 0 without evidence.
  double coverage(const core::Pose3& X_camera_object, const cv::Mat& cloud, const CameraModel& camera) const;

  /// True when the model is (nearly) yaw-symmetric about a vertical axis
  /// away from its origin (e.g. the five-point star, whose frame is centred
  /// on its bounding box, 2.6 mm from the star's centre): depth cannot tell
  /// its symmetric poses apart, yet they put the origin at different places.
  bool hasOffCentreSymmetry() const;

  /// The model's symmetric poses: X_camera_object turned about the symmetry
  /// centre's vertical axis by k x yawSymmetry_rad (k = 0 first = the input).
  std::vector<core::Pose3> symmetricBranches(const core::Pose3& X_camera_object) const;

  const ObjectModel& model() const { return model_; }

 private:
  struct Impl;
  ObjectModel model_;
  Options options_;
  Eigen::Vector2d symmetryCentre_xy_ = Eigen::Vector2d::Zero();  ///< object frame, mean of the samples [m]
  std::unique_ptr<Impl> impl_;
};

}  // namespace srp::perception
