#pragma once
/// \file ObjectDetector.h
/// \brief Objects of the CAD knowledge base in one RGB-D frame: depth
/// segmentation above the support plane, then each segment explained by the
/// best-fitting class model (shape by ICP, colour when the class has one).

#include <Eigen/Core>
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "srp/core/ObjectCatalogue.h"
#include "srp/core/Pose.h"
#include "srp/perception/CameraModel.h"
#include "srp/perception/ObjectModel.h"
#include "srp/perception/ObjectPoseFitter.h"
#include "srp/perception/PlaneFit.h"
#include "srp/rawlog/RgbdFrame.h"

namespace srp::perception {

/// One detected object. Poses in the camera optical frame, metres, radians.
struct ObjectDetection {
  std::string className;
  int classId = -1;
  core::Pose3 X_camera_object = core::Pose3::Identity();  ///< catalogue object frame (bottom centre, z up)
  double yaw_rad = 0.0;            ///< about the support-plane normal, in the plane frame (Plane::X_camera_plane)
  Eigen::Vector3d size_m = Eigen::Vector3d::Zero();  ///< oriented bounding box = the model's box at X_camera_object
  std::array<Eigen::Vector2d, 4> obb_px;             ///< the segment's rotated rectangle in the image
  Eigen::Vector3d p_camera_median_m = Eigen::Vector3d::Zero();  ///< median of the segment's valid points
  double confidence = 0.0;         ///< fit score x colour agreement, [0, 1]
  int segmentPixels = 0;
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
    PlaneFitOptions plane;
    ObjectPoseFitter::Options fit;
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

  /// The support plane of the last detect() call, if one was found.
  const std::optional<Plane>& lastPlane() const { return lastPlane_; }
  const std::vector<ObjectPoseFitter>& fitters() const { return fitters_; }
  const Options& options() const { return options_; }

  /// Segments above the plane: label image (CV_32S, 0 = none) and the count.
  int segment(const cv::Mat& cloud, const Plane& plane, cv::Mat& labels) const;

 private:
  std::vector<ObjectPoseFitter> fitters_;
  Options options_;
  mutable std::optional<Plane> lastPlane_;
};

}  // namespace srp::perception
