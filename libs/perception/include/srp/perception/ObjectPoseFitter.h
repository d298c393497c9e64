#pragma once
/// \file ObjectPoseFitter.h
/// \brief Fits one CAD model to a segment of the depth cloud: an object
/// standing on a support plane, free in position and in yaw about the plane
/// normal (4 DOF), by ICP from several yaw starts, then a small 6-DOF
/// refinement (tilt) of the best.

#include <Eigen/Core>
#include <memory>
#include <optional>
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
    /// Bound on the nearest-sample grid (4 bytes a cell): a larger model gets
    /// coarser cells rather than more memory (the default catalogue needs < 1.2 M).
    std::size_t maxGridCells = 16'000'000;
    bool refineTilt = true;      ///< finish with a 6-DOF ICP (tilt against the plane up to maxTilt_rad)
    double maxTilt_rad = 10.0 * 3.14159265358979323846 / 180.0;
    int minPoints = 10;              ///< a segment with fewer points is not fitted (score 0)
    double topPercentile = 0.98;     ///< the segment's top height: this percentile (flying pixels above edges)
    double onPlaneStartMinHeight_m = 0.005;  ///< starts also on the plane when the top-derived height exceeds this
    // 4-DOF ICP
    double earlyGate_m = 0.05;       ///< first half of the iterations: matches within this [m]
    double lateGate_tol = 4.0;       ///< second half: within this many inlierTol_m (outliers: other objects, the hand)
    double pointToPointWeight = 0.1; ///< weak point-to-point term next to point-to-plane (keeps faces from sliding)
    double heightPriorWeight = 0.05; ///< prior on the start's height, x the translation's information [1]
    double icpDamping = 1e-6;        ///< added to the normal equations' diagonal
    double maxYawStep_rad = 0.3;     ///< yaw change per iteration at most
    double icpConvergence = 1e-5;    ///< stop when the step is below this [m] and [rad]
    int coarseIterations = 12;       ///< coarse stage: iterations per start (several starts)
    int coarseStride = 4;            ///< coarse stage: every this-many-th point
    int fineStarts = 4;              ///< fine stage: this many best coarse starts, all points, `iterations`
    double heightCheck_m = 0.003;    ///< a fine pose this far above the plane is also tried standing on it
    // 6-DOF tilt refinement
    double tiltGate_tol = 3.0;       ///< matches within this many inlierTol_m
    double tiltDamping = 1e-4;       ///< added to the normal equations' diagonal
    double tiltConvergence = 1e-6;   ///< stop when the step's norm is below this
    double tiltScoreSlack = 0.01;    ///< kept when its score is at least the 4-DOF score minus this
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
    int inView = 0;    ///< camera-facing samples inside the image, with or without depth
    int occluded = 0;  ///< measured depth nearer than the model by more than the occluder margin
    int total() const { return supported + seenThrough; }
  };
  SurfaceEvidence surfaceEvidence(const core::Pose3& X_camera_object, const cv::Mat& cloud,
                                  const CameraModel& camera) const;
  /// The same from a depth image [m] (CV_32F, 0 = no depth), with samples
  /// whose measured depth lies more than occluderMargin_m in front of the
  /// model counted as `occluded` (checked before support).
  SurfaceEvidence surfaceEvidenceInDepth(const core::Pose3& X_camera_object, const cv::Mat& depth_m,
                                         const core::CameraIntrinsics& intrinsics, double occluderMargin_m) const;

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
  /// The segment in the plane frame, evenly subsampled to Options::maxPoints,
  /// with its centroid and robust top (Options::topPercentile) [m].
  struct PlanePoints {
    std::vector<Eigen::Vector3d> q;
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    double top_m = 0.0;
  };
  PlanePoints toPlaneFrame(const std::vector<Eigen::Vector3d>& points_camera, const core::Pose3& X_plane_camera) const;
  /// ICP starts (x, y, z, yaw in the plane frame): `initial` alone, else every
  /// yawStep_rad within the model's symmetry at the centroid, top-derived
  /// height and on the plane.
  std::vector<Eigen::Vector4d> startPoses(const PlanePoints& points, const core::Pose3& X_plane_camera,
                                          const core::Pose3* initial) const;
  /// 4-DOF ICP (x, y, z, yaw in the plane frame) from `start` on every
  /// `stride`-th point of `q`.
  Eigen::Vector4d icpFourDof(const std::vector<Eigen::Vector3d>& q, const Eigen::Vector4d& start, int iterations,
                             std::size_t stride) const;
  /// The fit (inliers, coverage, score) of the 4-DOF pose x.
  ObjectPoseFit scoreFourDof(const std::vector<Eigen::Vector3d>& q, const Eigen::Vector4d& x,
                             const core::Pose3& X_camera_plane, const cv::Mat& cloud, const CameraModel& camera) const;
  /// 6-DOF ICP from `best`; nullopt when it tilts beyond maxTilt_rad.
  std::optional<ObjectPoseFit> refineTiltSixDof(const std::vector<Eigen::Vector3d>& q, const ObjectPoseFit& best,
                                                const core::Pose3& X_camera_plane, const cv::Mat& cloud,
                                                const CameraModel& camera) const;

  struct Impl;
  ObjectModel model_;
  Options options_;
  Eigen::Vector2d symmetryCentre_xy_ = Eigen::Vector2d::Zero();  ///< object frame, mean of the samples [m]
  std::unique_ptr<Impl> impl_;
};

}  // namespace srp::perception
