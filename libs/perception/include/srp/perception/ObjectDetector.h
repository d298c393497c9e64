#pragma once
/// \file ObjectDetector.h
/// \brief Objects of the CAD knowledge base in one RGB-D frame: depth
/// segmentation above the support plane, then each segment explained by the
/// best-fitting class model (shape by ICP, colour when the class has one).

#include <Eigen/Core>
#include <array>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "srp/core/ObjectCatalogue.h"
#include "srp/core/Pose.h"
#include "srp/perception/CameraModel.h"
#include "srp/perception/EdgeYawRefiner.h"
#include "srp/perception/ObjectModel.h"
#include "srp/perception/ObjectPoseFitter.h"
#include "srp/perception/PlaneFit.h"
#include "srp/perception/SilhouetteBranchPicker.h"
#include "srp/rawlog/RgbdFrame.h"

namespace srp::perception {

/// One detected object. Poses in the camera optical frame, metres, radians.
struct ObjectDetection {
  /// The perception key of what was detected: the detector model's name, i.e.
  /// the instance id for a per-instance model (PlanObject::key()), else the class name.
  std::string key;
  int classId = -1;
  core::Pose3 X_camera_object = core::Pose3::Identity();  ///< catalogue object frame (bottom centre, z up)
  double yaw_rad = 0.0;            ///< about the support-plane normal, in the plane frame (Plane::X_camera_plane)
  Eigen::Vector3d size_m = Eigen::Vector3d::Zero();  ///< oriented bounding box = the model's box at X_camera_object
  std::array<Eigen::Vector2d, 4> obb_px;             ///< the segment's rotated rectangle in the image
  Eigen::Vector3d p_camera_median_m = Eigen::Vector3d::Zero();  ///< median of the segment's valid points
  double confidence = 0.0;         ///< fit score x colour agreement, [0, 1]
  int segmentPixels = 0;
};

/// One depth segment above the support plane (a candidate object). Points in
/// the camera optical frame; extent in the plane frame (Plane::X_camera_plane),
/// 2nd to 98th percentile so flying pixels at the edges do not count.
struct ObjectSegment {
  std::vector<Eigen::Vector3d> points_camera_m;
  std::vector<cv::Point> pixels;
  Eigen::Vector3d meanRgb = Eigen::Vector3d::Zero();  ///< [0, 1]; zero without colour
  bool hasColour = false;
  cv::Mat colour_bgr8;  ///< the frame's colour image (shared, not copied); empty without colour
  Eigen::Vector3d lo_plane_m = Eigen::Vector3d::Zero(), hi_plane_m = Eigen::Vector3d::Zero();
  Eigen::Vector3d centre_plane_m() const { return 0.5 * (lo_plane_m + hi_plane_m); }
};

/// Detector over a fixed set of class models (built once).
class ObjectDetector {
 public:
  struct Options {
    double minHeight_m = 0.010;   ///< above the support plane, to leave the table (and box floors) out
    double maxHeight_m = 0.40;
    double depthEdge_m = 0.015;   ///< neighbouring depths further apart split segments
    int minPixels = 80;
    double maxElevation_m = 0.10;  ///< objects stand at most this high above the plane (in a box, on another part)
    double minConfidence = 0.35;
    double trackConfidence = 0.75;  ///< a tracked refinement this good skips the full search
    double trackRadius_m = 0.04;    ///< previous pose to segment centre, along the plane
    double colourChromaSigma = 0.1; ///< colour agreement exp(-d^2 / 2 sigma^2) of the chromaticity distance d [1]
    double extentTrim = 0.02;       ///< a segment's extent from this to 1 minus this percentile (flying pixels)
    /// Gates before a full fit: the segment's extent along the plane at most
    /// maxExtentPerDiagonal x the model's footprint diagonal + extentSlack_m
    /// and at least minExtentPerSide x its shorter side; its top at most the
    /// model's height + maxElevation_m + extentSlack_m and at least
    /// minTopPerHeight x the model's height; colour agreement at least minColour.
    double maxExtentPerDiagonal = 1.5;
    double extentSlack_m = 0.02;
    double minExtentPerSide = 0.25;
    double minTopPerHeight = 0.4;
    double minColour = 0.05;
    /// A full search gives up after the coarse stage when even a perfect fine
    /// stage could not lift its score to this share of the acceptance.
    double giveUpShare = 0.5;
    PlaneFitOptions plane;
    /// Each segment is fitted on the support plane refitted to the table
    /// around it (fitLocalPlane), when enough of the table is seen there.
    /// Off: on the real cube's development frames 0-29 it changed no frame's
    /// verdict and the median by < 0.3 mm (perception README).
    bool localSupport = false;
    LocalPlaneOptions localPlane;
    ObjectPoseFitter::Options fit;
    /// Parts with an m-fold outline (cuboid, octagon): yaw from the colour
    /// edges (EdgeYawRefiner), which depth alone barely shows.
    bool refineYawByEdges = true;
    EdgeYawRefiner::Options edges;
    /// Parts symmetric about an axis off their origin (the star): the
    /// symmetric turn whose outline matches the colour silhouette
    /// (SilhouetteBranchPicker), which depth cannot tell.
    bool pickBranchBySilhouette = true;
    SilhouetteBranchPicker::Options branches;
  };

  ObjectDetector(std::vector<ObjectModel> models, const Options& options);
  explicit ObjectDetector(std::vector<ObjectModel> models);

  /// Models of the named catalogue classes (all when `classNames` is empty).
  static std::vector<ObjectModel> modelsFromCatalogue(const core::ObjectCatalogue& catalogue,
                                                      const std::vector<std::string>& classNames = {});

  /// Detections in one frame, best first. The support plane is fitted when not
  /// given (nullopt result -> no detections). Throws InvalidInputError for a
  /// frame without depth.
  std::vector<ObjectDetection> detect(const rawlog::RgbdFrame& frame, const Plane* support = nullptr) const;

  /// As detect(), tracking: a segment near a class' previous pose (`previous`,
  /// class name -> X_camera_object) is first refined from that pose alone and
  /// kept when its confidence reaches `trackConfidence`; only the other
  /// segments get the full search over classes and start yaws.
  std::vector<ObjectDetection> detect(const rawlog::RgbdFrame& frame, const Plane* support,
                                      const std::map<std::string, core::Pose3>& previous) const;

  /// The segments of a frame: `cloud` = depthToCloud(frame.depth_m), segments
  /// with fewer than Options::minPixels pixels left out.
  std::vector<ObjectSegment> segments(const rawlog::RgbdFrame& frame, const cv::Mat& cloud, const Plane& plane) const;

  /// The best class for one segment (nullopt below Options::minConfidence):
  /// classes with a `previous` pose near the segment are refined from it first
  /// (tracking), the full search over start yaws runs only when that fails.
  /// Classes in `excluded` are not tried (already assigned, or fixed).
  std::optional<ObjectDetection> explain(const ObjectSegment& segment, const Plane& plane, const cv::Mat& cloud,
                                         const CameraModel& camera, const std::map<std::string, core::Pose3>& previous,
                                         const std::set<std::string>& excluded = {}) const;

  /// A detection of `fitter`'s class at a fitted pose, with the segment's
  /// yaw, image box and median filled in.
  ObjectDetection makeDetection(const ObjectPoseFitter& fitter, const core::Pose3& X_camera_object, double confidence,
                                const ObjectSegment& segment, const Plane& plane) const;

  /// Colour agreement [0, 1] of the segment with the class (1 when the class'
  /// colour is not discriminative or the frame has none).
  double colourScore(const ObjectSegment& segment, const ObjectModel& model) const;

  /// The support plane of the last detect() call, if one was found.
  const std::optional<Plane>& lastPlane() const { return lastPlane_; }
  const std::vector<ObjectPoseFitter>& fitters() const { return fitters_; }
  /// The fitter of class `className`; nullptr when the detector has no such model.
  const ObjectPoseFitter* fitterFor(const std::string& className) const;

  /// Classes of `detections` that cannot be where they are said to be: of two
  /// parts (ObjectKind::Part) whose origins are closer along `plane` than half
  /// the smaller footprint diagonal and whose height ranges share more than
  /// half the smaller height, the less confident one (a part's fragment read
  /// as a neighbour: the orange octagon as the yellow star, colour 0.47).
  /// Stacked parts and parts in containers are left alone.
  std::set<std::string> overlappingParts(const std::vector<ObjectDetection>& detections, const Plane& plane) const;
  const Options& options() const { return options_; }

  /// Segments above the plane: label image (CV_32S, 0 = none) and the count.
  int segment(const cv::Mat& cloud, const Plane& plane, cv::Mat& labels) const;

 private:
  std::vector<ObjectPoseFitter> fitters_;
  std::vector<EdgeYawRefiner> refiners_;  ///< one per fitter
  SilhouetteBranchPicker branchPicker_;
  Options options_;
  mutable std::optional<Plane> lastPlane_;
};

}  // namespace srp::perception
