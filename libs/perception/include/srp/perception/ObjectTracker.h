#pragma once
/// \file ObjectTracker.h
/// \brief Objects over a frame sequence from a fixed camera, at a fraction of
/// per-frame detection's cost: a segment that has not changed keeps its last
/// answer, static objects are fixed once seen, moving objects are refined from
/// their last pose, and only new or changed segments get the full class search.

#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "srp/perception/ObjectDetector.h"

namespace srp::perception {

/// Tracks the objects of an ObjectDetector's classes through the frames of one
/// demo (fixed camera, time order). Poses in the camera optical frame, metres.
///
/// Per frame, each depth segment above the support plane is, in order:
/// 0. the *hand* (near the given hand points): no object;
/// 1. *unchanged*: its pixel count, extent and centre along the plane and its
///    top height match (within Options tolerances) those of a segment
///    answered in an earlier frame, less
///    than `refreshFrames` ago -> the same answer (the same class and pose, or
///    "no object"), no fit;
/// 2. a *fixed static object* (after `staticFixDetections` detections a static
///    class is fixed at its most confident one): verified at the fixed pose
///    (no ICP), never searched again;
/// 3. else explained by ObjectDetector::explain (tracking from the last pose of
///    the moving classes, else the full search); the frame's segments are
///    searched on `Options::searchThreads` threads.
/// Each class is given to at most one segment per frame, the most confident
/// first (a part is never reported at another part's segment because it is
/// missing from its own, e.g. while it is carried).
///
/// "Class" here is the detector's model name (ObjectModel::name). For several
/// parts of one class (two cuboids, red and blue) DemoPerceiver gives each
/// instance a model of its own, named by its instance id, with the instance's
/// colour: the tracker then keys by (class, instance), detects every instance
/// in a frame, and tells them apart by colour (the fit's confidence carries
/// the colour agreement, ObjectDetector::colourScore) and by their last poses
/// (tracking, unchanged segments, the unheld-jump rule below).
class ObjectTracker {
 public:
  struct Options {
    std::set<std::string> staticClasses;  ///< containers, landmarks (from the task plan)
    int staticFixDetections = 10;         ///< detections before a static object is fixed
    double staticVerifyInliers = 0.5;     ///< segment points on the fixed model to count as seen
    int refreshFrames = 30;               ///< an unchanged segment is re-explained after this many frames
    double sameCentre_m = 0.003;          ///< unchanged: centres this close (along the plane) ...
    double sameExtent_m = 0.004;          ///< ... extents along the plane and tops this close ...
    double samePixels = 0.06;             ///< ... and pixel counts within this fraction
    double noObjectSlack = 3.0;           ///< tolerances x this for a segment that was no object
    double handRadius_px = 6.0;           ///< a segment this close to a hand point is the hand
    /// A part moves only in the hand: a moving class reported farther than
    /// this from its last pose is believed only when a hand point has come
    /// within handVisit_m of that pose since (a grasp), when its last place
    /// is vacated (the depth sees through at least vacatedSeenThrough of the
    /// model's surface samples there, of at least vacatedMinEvidence samples
    /// with evidence; a hand in front is no evidence), or when the new pose
    /// holds for jumpConfirmFrames frames (a hand the detector missed). Keeps
    /// a reaching hand's fingers from being taken for the part it reaches
    /// for (the part is still in its place), yet believes a placed part at
    /// once even when the palm stayed centimetres from it (a cuboid held at
    /// its end: 7 cm).
    double maxUnheldJump_m = 0.02;
    double handVisit_m = 0.03;
    double vacatedSeenThrough = 0.6;
    int vacatedMinEvidence = 30;
    int jumpConfirmFrames = 15;
    /// Threads that search a frame's segments (step 3; 1: one after the
    /// other). The answers do not depend on it.
    int searchThreads = 2;
  };

  /// `detector` must outlive the tracker.
  ObjectTracker(const ObjectDetector& detector, const Options& options);

  /// Detections in the next frame, most confident first, at most one per
  /// class. `support`: the support plane (e.g. fitted once for a fixed
  /// camera); fitted on this frame when null (no plane -> no detections).
  /// Throws InvalidInputError for a frame without depth.
  /// `hand_px`: the hand's image points in this frame (e.g. the palm pixel)
  /// when known: a segment within Options::handRadius_px of one of them is
  /// the hand, with whatever it holds, and explains no object (a part in the
  /// hand is "not detected", never fitted to the hand's depth).
  std::vector<ObjectDetection> update(const rawlog::RgbdFrame& frame, const Plane* support = nullptr,
                                      const std::vector<Eigen::Vector2d>& hand_px = {});

  /// What update() computes from the frame alone, before any tracking state:
  /// the point cloud, the support plane (`support` or fitted) and the
  /// segments above it. A caller may compute it while the hand is looked for
  /// in the same frame, then give it to update(); update(frame, support,
  /// hand_px) is update(frame, segment(frame, support), hand_px).
  struct FrameSegments {
    cv::Mat cloud;
    std::optional<Plane> plane;
    std::vector<ObjectSegment> segments;
  };
  /// Throws InvalidInputError for a frame without depth. Changes no tracking
  /// state (it reuses the last cloud's memory).
  FrameSegments segment(const rawlog::RgbdFrame& frame, const Plane* support = nullptr);
  std::vector<ObjectDetection> update(const rawlog::RgbdFrame& frame, FrameSegments segmented,
                                      const std::vector<Eigen::Vector2d>& hand_px = {});

  /// The support plane of the last update, if one was found.
  const std::optional<Plane>& lastPlane() const { return lastPlane_; }

  /// The fixed pose of a static class, once fixed.
  std::optional<ObjectDetection> fixedStatic(const std::string& className) const;

  /// Per-frame counters of the last update (how the segments were answered).
  struct Stats {
    int segments = 0, unchanged = 0, staticVerified = 0, explained = 0, hand = 0;
  };
  const Stats& lastStats() const { return stats_; }

 private:
  /// Whether the class's model at X_camera_object is seen through (see Options).
  bool placeVacated(const std::string& className, const core::Pose3& X_camera_object, const cv::Mat& cloud,
                    const CameraModel& camera) const;

  /// A segment answered in some frame, and the answer.
  struct Answer {
    Eigen::Vector3d lo_plane_m, hi_plane_m;
    int pixels = 0;
    int frame = 0;  ///< when it was explained
    std::optional<ObjectDetection> detection;
  };
  bool same(const Answer& a, const ObjectSegment& s) const;

  /// One update's answers so far: per segment (for the next frame), the
  /// classes given out, the detections.
  struct FrameAnswers {
    std::vector<Answer> next;
    std::set<std::string> assigned;
    std::vector<ObjectDetection> out;
  };
  /// Records a segment's answer (a static class fixed since reports its fixed pose).
  void answer(FrameAnswers& fa, const ObjectSegment& seg, int explainedAt,
              const std::optional<ObjectDetection>& d) const;
  /// Step 0: a segment within handRadius_px of a hand point is the hand.
  bool isHand(const ObjectSegment& seg, const std::vector<Eigen::Vector2d>& hand_px) const;
  /// Steps 0 and 1: hand segments skipped, unchanged ones keep their answer;
  /// returns the indices of the others.
  std::vector<std::size_t> keepUnchanged(const std::vector<ObjectSegment>& segs,
                                         const std::vector<Eigen::Vector2d>& hand_px, int now, FrameAnswers& fa);
  /// Step 2: pending segments verified at a fixed static object's pose leave `pending`.
  void verifyFixedStatics(const std::vector<ObjectSegment>& segs, std::vector<std::size_t>& pending,
                          const Plane& plane, const cv::Mat& cloud, const CameraModel& camera, int now,
                          FrameAnswers& fa);
  /// Step 3: the rest explained (tracking, else full search), each class to its most confident segment.
  void explainPending(const std::vector<ObjectSegment>& segs, const std::vector<std::size_t>& pending,
                      const Plane& plane, const cv::Mat& cloud, const CameraModel& camera, int now,
                      FrameAnswers& fa);
  /// Moving classes reported far from their last pose without a grasp since
  /// are dropped until believed (see Options::maxUnheldJump_m).
  void dropUnheldJumps(std::vector<ObjectDetection>& out, const std::vector<Eigen::Vector2d>& hand_px,
                       const cv::Mat& cloud, const CameraModel& camera);
  /// Last poses, hand visits and the fixing of static classes after a frame.
  void remember(const std::vector<ObjectDetection>& out);

  const ObjectDetector& detector_;
  Options options_;
  int frame_ = 0;
  std::vector<Answer> answers_;  ///< of the last frame
  std::map<std::string, core::Pose3> lastPose_;
  std::map<std::string, bool> handVisited_;  ///< a hand point came near lastPose_ since it was set
  struct PendingJump {
    core::Pose3 X_camera_object;
    int frames = 0;
  };
  std::map<std::string, PendingJump> pendingJumps_;
  std::map<std::string, std::vector<ObjectDetection>> staticDetections_;
  std::map<std::string, ObjectDetection> fixed_;
  Stats stats_;
  cv::Mat cloud_;  ///< the frame's point cloud, its memory reused frame to frame
  std::optional<Plane> lastPlane_;
};

}  // namespace srp::perception
