#pragma once
/// \file PlaneFit.h
/// \brief The support plane (table) in an organised cloud, by RANSAC.

#include <Eigen/Core>
#include <optional>
#include <opencv2/core.hpp>

#include "srp/core/Pose.h"

namespace srp::perception {

/// Plane n . p + d = 0 in the camera frame; n is a unit normal pointing to
/// the camera's side (d > 0), so n . p + d is the height of p above the plane [m].
struct Plane {
  Eigen::Vector3d n = Eigen::Vector3d::UnitZ();
  double d = 0.0;
  int inliers = 0;
  double height(const Eigen::Vector3d& p) const { return n.dot(p) + d; }
  /// Where the camera ray through `ray` (a direction from the camera centre,
  /// e.g. a pixel's normalised coordinates (x, y, 1)) meets the plane raised
  /// by `height_m` along n: the scale s such that height(s * ray) ==
  /// height_m (with ray.z() == 1, s is that point's depth [m]). nullopt when
  /// the ray runs parallel to the plane or meets it behind the camera (s <= 0).
  std::optional<double> rayScaleAtHeight(const Eigen::Vector3d& ray, double height_m = 0.0) const;
  /// A frame on the plane: origin = the foot of the camera's optical axis
  /// projected on the plane, z = n, x = the camera x axis projected on the plane.
  core::Pose3 X_camera_plane() const;
};

struct PlaneFitOptions {
  double inlierTol_m = 0.008;
  int iterations = 300;
  int sampleStride_px = 4;  ///< pixels between the samples RANSAC considers
  /// When set, only planes whose normal is within maxTilt_rad of this camera-frame direction.
  std::optional<Eigen::Vector3d> expectedNormal;
  double maxTilt_rad = 0.5;
  unsigned seed = 1;
  /// fitSupportPlane: a second plane, at least secondPlaneMinTurn_rad from the
  /// dominant one and with at least secondPlaneMinShare of its inliers, is the
  /// support instead when its normal points up in the image (camera -y) by
  /// secondPlaneMinUpward more than the dominant one's (a wall behind the table).
  double secondPlaneMinTurn_rad = 30.0 * 3.14159265358979323846 / 180.0;
  double secondPlaneMinShare = 0.3;
  double secondPlaneMinUpward = 0.5;
  int secondPlaneIterationFactor = 4;  ///< RANSAC iterations for the second plane: this x `iterations`
};

/// The plane with the most inliers (refined by least squares on them);
/// nullopt when fewer than 3 valid points or no plane fits the constraint.
std::optional<Plane> fitDominantPlane(const cv::Mat& cloud, const PlaneFitOptions& options = {});

/// The support plane (the table the objects stand on): the dominant plane,
/// unless a second large plane at an angle to it faces up in the image more
/// (PlaneFitOptions::secondPlane*): a camera that looks across a table at a
/// wall sees more wall than table, and a wall faces the camera, not up.
/// A camera is taken to be upright (image up is roughly world up) or to look
/// down; a camera looking straight down sees one dominant plane, the table.
/// With `expectedNormal` set it is fitDominantPlane (the caller has chosen).
std::optional<Plane> fitSupportPlane(const cv::Mat& cloud, const PlaneFitOptions& options = {});

/// The support plane where one object stands: a dominant plane fitted over
/// the whole image is a compromise over a table seen at a grazing angle (its
/// depth error grows with distance: 5-10 mm and 3-6 deg off at the part in
/// the real RealSense recording), so it is refitted to the table around the part.
struct LocalPlaneOptions {
  double margin = 1.0;           ///< the part's image box grown by this x its larger side on each side [-]
  double band_m = 0.015;         ///< candidate table points: within this of the global plane [m]
  double inlierTol_m = 0.003;    ///< RANSAC inlier distance to the local plane [m]
  double maxTurn_rad = 10.0 * 3.14159265358979323846 / 180.0;  ///< local normal within this of the global one
  double maxShift_m = 0.012;     ///< local plane within this of the global one below the part [m]
  int minInliers = 150;          ///< fewer: the global plane is kept
  int iterations = 60;
  int stride_px = 2;
  unsigned seed = 1;
};

/// `global` refitted (RANSAC, then least squares) to the cloud points within
/// band_m of it in `roi_px` grown by LocalPlaneOptions::margin, which are not
/// the part (`excluded`, e.g. its segment's pixels, may be empty); nullopt
/// when too few points agree or the local plane turns or shifts (at the roi's
/// centre) more than allowed.
std::optional<Plane> fitLocalPlane(const cv::Mat& cloud, const Plane& global, const cv::Rect& roi_px,
                                   const LocalPlaneOptions& options = {});

}  // namespace srp::perception
