#pragma once
/// \file ObjectDiscovery.h
/// \brief Parts and containers without a CAD model, found in the
/// demonstration itself: what stands on the table, which of it the hand moves,
/// and where it is let go.

#include <Eigen/Core>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "srp/core/ObjectCatalogue.h"
#include "srp/core/Pose.h"
#include "srp/perception/ObjectTrajectory.h"
#include "srp/perception/SegmentColour.h"
#include "srp/rawlog/RgbdFrame.h"

namespace srp::perception {

/// An object of the instruction that the knowledge base does not know (or
/// knows without a mesh or a shape): found in the demonstration by
/// ObjectDiscovery.
struct UnknownObject {
  std::string name;  ///< the class name it gets (the instruction's noun, or the catalogue entry's name)
  std::string noun;  ///< its head noun in instructions ("toy")
  std::optional<std::string> colour;  ///< the instruction's colour word ("blue"): selects among candidates
  int classId = -1;  ///< -1: the next id after the catalogue's
  /// Moved: a part the hand moves. ReleasePlace / PickPlace: the place where
  /// the moved object `of` is let go / picked up (a container or a part it
  /// stands on).
  enum class Role { Moved, ReleasePlace, PickPlace };
  Role role = Role::Moved;
  std::string of;  ///< ReleasePlace / PickPlace: the perception key of the moved object
};

/// Finds UnknownObjects in a demonstration, frame by frame (add) and then as a
/// whole (finish). All geometry is in the table frame (the support plane's
/// frame of the first frame, PlaneFit.h: z up, metres).
///
/// Per frame, at a reduced resolution (Options::stride): the points between
/// minHeight_m and maxHeight_m above the table whose foot lies on the table
/// top (the convex hull of the first frame's largest connected region of
/// table points, tableMargin_m wider), without the hand (its mask when the
/// detector gives one, and every point within handRadius_m of the palm), cut
/// at depth steps, are *segments*: each summarised by its footprint (the
/// convex hull of its points' feet), heights, colour words (SegmentColour.h)
/// and whether the hand is near. A segment like an earlier one (its centre
/// within restRadius_m of the rest's, top within restTopTol_m, colours at
/// least minColourSimilarity alike) is one more sighting of that *rest*, a
/// place where something stands (or, by its footprint, something standing
/// there with an arm reaching for it); a rest keeps the points of its
/// keptSightings largest sightings, those as high as its anchor (within
/// restTopTol_m: not the part joined by the arm) and without the hand near
/// first (the fused point cloud its model is built from).
///
/// At the end (finish):
/// - static rests: seen both in the first and in the last
///   `windowShare` of the frames;
/// - a *moved part*: a rest A seen at the start and not at the end, and a
///   later rest B seen at the end and not at the start, at least minMove_m
///   from A, alike in colour (minColourSimilarity) and size (footprint areas
///   within a factor maxAreaRatio), the hand within handNear_m of A when A is
///   last seen and of B when B is first seen. The instruction's colour word
///   keeps the candidates whose share of that colour is at least
///   minColourShare; two or more left are refused, naming them;
/// - the part's trajectory: A's place until it leaves, the sightings near
///   the palm that belong to no static rest while it is carried (alike in
///   colour), B's place from its first sighting;
/// - a *release place*: the static rest whose footprint holds B's centre
///   (or the nearest within placeRadius_m); a *pick place* the same for A;
///   it is a container when it is concave: fewer than
///   maxInnerHighShare of its points over the inner half of its footprint
///   rise above innerHighFraction of its height (a bin's floor is low, a
///   box's lid high);
/// - models from the fused points: a part is shape "hull" (the convex hull
///   of the feet, up to the 95th percentile height), a container "open_box"
///   (its oriented box, rim at the 95th percentile height,
///   containerWall_m thick); x along the footprint's longer side, origin at
///   the bottom centre (ObjectCatalogue.h), observed = true.
///
/// Every failure throws InvalidInputError naming the object and what was (not)
/// seen, e.g. the rests at the start when no segment was moved by the hand.
class ObjectDiscovery {
 public:
  struct Options {
    int stride = 2;                   ///< every stride-th pixel in both directions
    double minHeight_m = 0.015;       ///< above the table top (noise, a bin's floor)
    double maxHeight_m = 0.6;         ///< a segment reaching this high is part of something taller (a person, a wall)
    double depthEdge_m = 0.02;        ///< neighbours farther apart (x their depth [m]) split segments
    int minPixels = 60;               ///< at the reduced resolution
    double tableInlierTol_m = 0.01;   ///< table points: this close to the plane
    double tableMargin_m = 0.02;
    double minInsideShare = 0.8;      ///< of a segment's feet on the table top
    double handRadius_m = 0.12;       ///< points this close to the palm are the hand
    int handMaskGrow_px = 2;          ///< the hand mask grown by this (reduced resolution)
    double armAbovePalm_m = 0.02;     ///< a held part's segment is cut this far above the palm (the arm)
    double minRestOverlap = 0.5;      ///< footprints overlapping this much (IoU) are one place
    double restRadius_m = 0.05;
    double restTopTol_m = 0.05;
    double minColourSimilarity = 0.5;
    int keptSightings = 8;
    int pointsPerSighting = 600;
    double windowShare = 0.2;         ///< start / end window, share of the frames (at least 2 frames)
    double maxStandingBottom_m = 0.05;  ///< a rest's median bottom at most this above what it stands on
    double minHolderAreaRatio = 1.5;    ///< what holds a part off the table (a container) has this x its footprint
    double minMove_m = 0.05;
    double maxAreaRatio = 3.0;
    double handNear_m = 0.25;
    int handNearFrames = 3;           ///< the hand's nearness is looked for this many frames either side
    double minColourShare = 0.25;
    double placeRadius_m = 0.05;
    double innerHighFraction = 0.6;
    double maxInnerHighShare = 0.3;
    double containerWall_m = 0.006;
    double partDensity_kg_m3 = 150.0;  ///< an observed part's mass from its hull's volume (unknown material)
    double containerMass_kg = 0.3;
  };

  /// What was found: one class per UnknownObject (in their order) and its
  /// trajectory (one sample per frame, each frame's camera, the class's
  /// object frame), and one line per decision for reports.
  struct Result {
    std::vector<core::ObjectClass> classes;
    std::vector<ObjectTrajectory> trajectories;
    std::vector<std::string> notes;
  };

  /// What stands on the table at one pixel of one frame, measured (`srp kb
  /// add --from-demo`): the segment (as add() cuts them, without a hand) that
  /// holds pixel `at_px` or lies within 3 sample steps of it; in the table
  /// frame its footprint frame (x along the longer side, origin at the bottom
  /// centre), size (long, short, 95th percentile height), footprint hull, and
  /// its pixels' mean colour (linear RGB) and dominant colour word.
  struct Measured {
    core::Pose3 X_table_object = core::Pose3::Identity();
    Eigen::Vector3d size_m = Eigen::Vector3d::Zero();
    std::vector<Eigen::Vector2d> footprint_object;
    Eigen::Vector3d rgb = Eigen::Vector3d::Zero();
    std::string colourWord;
    int points = 0;
  };
  /// nullopt when no segment is at or near `at_px` (the table, the background, a hole).
  static std::optional<Measured> measureAt(const rawlog::RgbdFrame& frame, const core::Pose3& X_camera_table,
                                           const Eigen::Vector2d& at_px, const Options& options);

  /// measureAt() in frame `frame` (counted from 0) of a rawlog, in the table
  /// frame of that frame's support plane (fitSupportPlane). Throws
  /// InvalidInputError naming the recording, the frame and the pixel when the
  /// recording is shorter, the pixel outside the image, no table plane is
  /// seen, or nothing stands on the table there.
  static Measured measureInRecording(const std::string& rawlogPath, int frame, const Eigen::Vector2d& at_px,
                                     const Options& options);

  ObjectDiscovery(std::vector<UnknownObject> objects, const Options& options);
  explicit ObjectDiscovery(std::vector<UnknownObject> objects);
  ~ObjectDiscovery();
  ObjectDiscovery(const ObjectDiscovery&) = delete;
  ObjectDiscovery& operator=(const ObjectDiscovery&) = delete;

  const std::vector<UnknownObject>& objects() const;

  /// One frame, in time order. `X_camera_table`: the table frame in this
  /// frame's camera; `p_camera_palm`: the palm when the hand was seen;
  /// `handMask`: the hand's pixels (CV_8UC1, the frame's size) or empty.
  void add(const rawlog::RgbdFrame& frame, const core::Pose3& X_camera_table,
           const std::optional<Eigen::Vector3d>& p_camera_palm, const cv::Mat& handMask);

  /// The objects, found. `known`: the catalogue objects' trajectories (a
  /// release place of a catalogue part is where that part came to rest);
  /// `firstFreeClassId`: the first id to give. Throws InvalidInputError
  /// naming the object and what was seen when one is not found or is ambiguous.
  Result finish(const std::vector<ObjectTrajectory>& known, int firstFreeClassId) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace srp::perception
