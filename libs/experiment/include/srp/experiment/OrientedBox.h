#pragma once
/// \file OrientedBox.h
/// \brief Oriented bounding boxes in the image (the thesis' OBB annotations,
/// YOLOv8-OBB) and their Intersection over Union, thesis eq. 6.1:
/// IoU = area(B_p ∩ B_gt) / area(B_p ∪ B_gt).

#include <Eigen/Core>
#include <array>
#include <vector>

#include "srp/core/CameraIntrinsics.h"
#include "srp/core/Pose.h"

namespace srp::experiment {

/// A rotated rectangle in the image: four corners in order around it
/// (either sense), pixels, pixel centres at integers (srp's convention).
struct OrientedBox2d
{
  std::array<Eigen::Vector2d, 4> corners_px{};

  /// Area [px²] (shoelace; independent of the corners' sense).
  double area_px2() const;
  Eigen::Vector2d centre_px() const;
};

/// The smallest-area rectangle around `points_px` (at least one point; a
/// rectangle of a minimal-area enclosing set has a side on a hull edge, so
/// every pair of points is tried as that side's direction: exact, O(n³) for
/// the few points of a projected box). Throws InvalidInputError when empty.
OrientedBox2d minAreaBox(const std::vector<Eigen::Vector2d>& points_px);

/// Eq. 6.1 for two oriented boxes (convex polygon clipping,
/// Sutherland–Hodgman). 0 when they do not overlap or a box has no area.
double orientedBoxIoU(const OrientedBox2d& a, const OrientedBox2d& b);

/// Area [px²] of the intersection of two convex polygons (corners in order, either sense).
double convexIntersectionArea(const std::vector<Eigen::Vector2d>& a, const std::vector<Eigen::Vector2d>& b);

/// The image OBB of an object: the 8 corners of its catalogue bounding box
/// (object frame: bottom-face centre, z up; x ∈ ±dx/2, y ∈ ±dy/2, z ∈ [0, dz])
/// at `X_camera_object`, projected with the pinhole model, enclosed by
/// minAreaBox(). This is how both the ground truth (true pose) and a
/// detection (estimated pose) become comparable image boxes, as the thesis'
/// BlenderProc annotations were made from the CAD models' poses. Throws
/// InvalidInputError when a corner is not in front of the camera (z <= 0).
OrientedBox2d projectObjectBox(const core::CameraIntrinsics& intrinsics, const core::Pose3& X_camera_object,
                               const Eigen::Vector3d& dimensions_m);

}  // namespace srp::experiment
