#pragma once
/// \file EdgeYawRefiner.h
/// \brief A part's yaw from the orientations of its outline's colour edges,
/// for shapes whose yaw depth barely shows (an octagon's corners move ~1 px
/// over 10 deg at 0.85 m) but whose straight outline edges the colour image
/// shows sharply.

#include <optional>
#include <opencv2/core.hpp>
#include <vector>

#include "srp/core/Pose.h"
#include "srp/perception/CameraModel.h"
#include "srp/perception/ObjectModel.h"
#include "srp/perception/PlaneFit.h"

namespace srp::perception {

/// Refines the yaw (about the support-plane normal) of a fitted pose with the
/// colour image. Applies to models whose side faces' horizontal normals are
/// m-fold regular (m = 4: cuboids, boxes; m = 8: octagons; `order()` 0
/// otherwise): the outline's edges then have orientations yaw + k 2pi/m, and
/// the circular mean of exp(i m angle) over the edge pixels gives the yaw
/// modulo 2pi/m, the fitted pose picking the branch. Other outlines of a few
/// straight sides (the parallelogram: 2 directions; depth noise and the lost
/// depth along its edges turn its depth-only yaw by 3-4 deg in some scenes):
/// the turn within maxCorrection_rad that lines the model's side normals up
/// with the edge normals (each edge pixel votes through a ~3 deg kernel).
///
/// Edge pixels: a ring of +-ringWidth_px around the depth segment's outline,
/// each weighted by its colour structure-tensor strength (Sobel on the three
/// channels: edges between colours of equal brightness count). The edge
/// tangent is mapped to the plane through the camera (perspective-correct, at
/// the model's top height).
class EdgeYawRefiner {
 public:
  struct Options {
    double maxCorrection_rad = 12.0 * 3.14159265358979323846 / 180.0;  ///< larger: distrusted
    double minCoherence = 0.25; ///< |mean exp(i m angle)| of the edge pixels, [0, 1]
    int ringWidth_px = 2;
    int minEdgePixels = 20;
    int maxOutlineDirections = 4;  ///< order 0: at most this many distinct side directions (modulo pi)
    double colourLikeness = 0.12;  ///< order 0: colour distance [0, 1] at which a pixel is 1/e like the top face
    /// Order 0: share of the edge weight the model's directions must explain
    /// at the best turn (0.63-0.65 on clean outlines; 0.35 where the outline
    /// seen is not the model's, e.g. seed 3's parallelogram against its box wall).
    double minOutlineCoherence = 0.5;
    double sideMaxNormalZ = 0.1;            ///< a model sample is on a side face when |n.z| <= this
    double regularOutlineCoherence = 0.95;  ///< |mean exp(i m angle)| of the side normals for an m-fold outline
    double minDirectionShare = 0.03;        ///< order 0: a side direction holds at least this share of the side samples
    double minDirectionsCover = 0.9;        ///< order 0: the directions found cover at least this share of them
    /// Order 0: squared 5x5 Sobel gradient of the top-face likeness [0, 1]
    /// an edge pixel needs (a full step gives ~48^2).
    double minLikenessGradient2 = 25.0;
    /// m-fold: structure-tensor strength of the colour gradient an edge pixel
    /// needs (5x5 Sobel of 8-bit values: a 10-level step gives ~2.6e4 per channel).
    double minStructureStrength = 1e5;
  };

  explicit EdgeYawRefiner(const ObjectModel& model);
  EdgeYawRefiner(const ObjectModel& model, const Options& options);

  /// m (4 or 8), or 0 when the model's outline is not m-fold regular.
  int order() const { return order_; }
  /// Order 0 with a polygonal outline of few directions (parallelogram): the distinct
  /// directions (modulo pi, object frame) of its side normals; the yaw is
  /// then the turn within maxCorrection_rad that best lines them up with the
  /// edge normals. Empty otherwise (curved outlines).
  const std::vector<double>& sideNormals_rad() const { return sideNormals_rad_; }

  /// X_camera_object turned about its z axis to the edges' yaw; nullopt when
  /// the model has no order, the image shows too few or too incoherent edges,
  /// or the correction exceeds maxCorrection_rad. `segmentPixels`: the
  /// object's depth segment (image coordinates).
  std::optional<core::Pose3> refine(const core::Pose3& X_camera_object, const std::vector<cv::Point>& segmentPixels,
                                    const cv::Mat& colour_bgr8, const CameraModel& camera, const Plane& plane) const;

 private:
  Options options_;
  int order_ = 0;
  double modelPhase_rad_ = 0.0;  ///< arg of sum exp(i m beta) over the side normals, object frame
  double top_m_ = 0.0;
  std::vector<double> sideNormals_rad_;  ///< order 0: the outline's distinct side normal directions, modulo pi
};

}  // namespace srp::perception
