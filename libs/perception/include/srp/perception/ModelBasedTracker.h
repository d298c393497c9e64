#pragma once
/// \file ModelBasedTracker.h
/// \brief One rigid part followed frame to frame by ViSP's model-based tracker
/// (vpMbGenericTracker) on an RGB-D camera: KLT points (and optionally moving
/// edges) on the colour image, dense depth on the registered depth image, the
/// model built from the part's CAD mesh.

#include <memory>

#include "srp/core/CameraIntrinsics.h"
#include "srp/core/Pose.h"
#include "srp/kb/TriangleMesh.h"
#include "srp/rawlog/RgbdFrame.h"

namespace srp::perception {

/// Follows one part given by its mesh (any CAD part: the mesh's triangles,
/// coplanar neighbours merged into one polygon face, become ViSP's CAO model)
/// through the frames of one RGB-D recording whose depth is registered to
/// colour. initialise() with a pose from detection (ObjectDetector /
/// ObjectPoseFitter), then track() each next frame. Poses are the mesh
/// frame's in the camera optical frame, metres.
///
/// The tracking-quality check is ViSP's own: a frame is *lost* when fewer
/// than Options::minKltPoints KLT points (when KLT is on) or
/// Options::minDepthFeatures dense-depth features remain, or when ViSP's
/// projection error (edges on: mean angle between the model's projected edges and the
/// image gradient) exceeds Options::maxProjectionError_deg. A lost tracker
/// must be initialised again (from detection) before it tracks.
class ModelBasedTracker {
 public:
  struct Options {
    bool useKlt = true;            ///< KLT points on the colour image (textured parts)
    bool useEdges = false;         ///< moving edges on the colour image (contrasted outlines)
    /// Dense depth (point-to-plane) on the depth image. Off by default: on
    /// the real cube's development frames (0-29) KLT alone agreed best with
    /// the reference (23/30 within 1 cm / 5 deg vs 21/30 with dense depth);
    /// DemoPerceiver checks the tracked pose against the depth instead
    /// (PerceptionOptions::mbtMinCoverage).
    bool useDepthDense = false;
    int depthSampling_px = 2;      ///< dense depth: one point every this many pixels in x and y
    int kltMaxPoints = 300;        ///< KLT: features detected on the part at initialisation
    double kltQuality = 0.01;      ///< KLT: Harris quality level (relative to the best corner)
    double kltMinDistance_px = 5;  ///< KLT: minimum distance between features
    int kltWindow_px = 5;          ///< KLT: window size
    int kltPyramidLevels = 3;      ///< KLT: pyramid levels (large frame-to-frame motion)
    int kltMaskBorder_px = 5;      ///< KLT: features kept this far inside the face outlines
    double edgeSampleStep_px = 4;  ///< moving edges: one site every this many pixels along an edge
    double edgeRange_px = 8;       ///< moving edges: search range along the normal
    int minKltPoints = 20;         ///< lost below this many KLT points (KLT on)
    int minDepthFeatures = 50;     ///< lost below this many dense-depth features (dense depth on)
    double maxProjectionError_deg = 35.0;  ///< lost above this projection error
    double maxDepth_m = 3.0;       ///< depth farther than this is ignored
    // edgeDistance_px (image support of a pose, e.g. to choose between a
    // tracked pose and a detection): Canny edges of the colour image.
    double supportBlurSigma_px = 1.2;      ///< Gaussian blur before Canny (5x5 kernel)
    double supportCannyLow = 40.0;         ///< Canny hysteresis thresholds (8-bit gradient)
    double supportCannyHigh = 100.0;
    double supportTruncation_px = 10.0;    ///< a model edge sample farther than this from an image edge counts this much
    double supportCreaseAngle_rad = 0.35;  ///< mesh edges whose faces turn by more than this (20 deg) are model edges
    double supportOcclusion_m = 0.02;      ///< an edge sample with depth this much nearer is hidden (not counted)
  };

  /// Per-frame answer of track().
  struct Result {
    bool tracked = false;  ///< false: lost (see the class comment), pose not to be used
    core::Pose3 X_camera_mesh = core::Pose3::Identity();
    double projectionError_deg = 0.0;
    int kltPoints = 0;
    int depthFeatures = 0;
    int edgeFeatures = 0;
  };

  /// `mesh_mesh`: the part's mesh in its own frame [m]; `intrinsics`: the
  /// colour camera's (depth registered to it, no distortion). Throws
  /// InvalidInputError for an empty mesh, invalid intrinsics or an Options
  /// combination without any feature.
  ModelBasedTracker(const kb::TriangleMesh& mesh_mesh, const core::CameraIntrinsics& intrinsics,
                    const Options& options);
  ModelBasedTracker(const ModelBasedTracker&) = delete;
  ModelBasedTracker& operator=(const ModelBasedTracker&) = delete;
  ~ModelBasedTracker();

  /// Starts (or restarts) tracking at X_camera_mesh in `frame` (colour and
  /// depth needed; throws InvalidInputError otherwise).
  void initialise(const rawlog::RgbdFrame& frame, const core::Pose3& X_camera_mesh);
  /// The pose in the next frame; Result::tracked false when lost (then
  /// initialised() is false until initialise() is called again).
  Result track(const rawlog::RgbdFrame& frame);
  bool initialised() const;

  /// What the colour image says about the part at X_camera_mesh in `frame`:
  /// the mean distance [px] from the model's visible crease edges (mesh edges
  /// between faces turning by more than Options::supportCreaseAngle_rad, one
  /// adjacent face towards the camera; corners left out), projected, to the
  /// nearest Canny edge of the image, each sample truncated at
  /// Options::supportTruncation_px. Samples behind something nearer in the
  /// depth image (Options::supportOcclusion_m) are left out. Lower is better;
  /// the truncation when no edge sample is left. Does not change the
  /// tracker's state.
  double edgeDistance_px(const rawlog::RgbdFrame& frame, const core::Pose3& X_camera_mesh) const;

  /// The mesh as ViSP's CAO text (vertices, polygon faces), as loaded.
  static std::string caoModel(const kb::TriangleMesh& mesh_mesh);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace srp::perception
