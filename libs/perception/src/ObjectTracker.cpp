#include "srp/perception/ObjectTracker.h"
#include "srp/core/Log.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <future>

#include "srp/core/Error.h"
#include "srp/perception/DepthCloud.h"

namespace srp::perception {

ObjectTracker::ObjectTracker(const ObjectDetector& detector, const Options& options)
    : detector_(detector), options_(options) {}

bool ObjectTracker::same(const Answer& a, const ObjectSegment& s) const {
  // "No object here" may be kept on a looser match: being wrong costs a few
  // frames of a missed detection (refreshFrames), not a wrong pose.
  const double slack = a.detection ? 1.0 : options_.noObjectSlack;
  const int pixels = static_cast<int>(s.points_camera_m.size());
  if (std::abs(pixels - a.pixels) > slack * options_.samePixels * std::max(pixels, a.pixels)) return false;
  // Along the plane only, and the top: a part's low edge (the bottom of its
  // visible sides) comes and goes with the depth noise.
  if ((0.5 * (a.lo_plane_m + a.hi_plane_m) - s.centre_plane_m()).head<2>().norm() > slack * options_.sameCentre_m)
    return false;
  if (std::abs(a.hi_plane_m.z() - s.hi_plane_m.z()) > slack * options_.sameExtent_m) return false;
  const Eigen::Vector2d dExtent = (a.hi_plane_m - a.lo_plane_m).head<2>() - (s.hi_plane_m - s.lo_plane_m).head<2>();
  return dExtent.cwiseAbs().maxCoeff() <= slack * options_.sameExtent_m;
}

std::optional<ObjectDetection> ObjectTracker::fixedStatic(const std::string& className) const {
  const auto it = fixed_.find(className);
  if (it == fixed_.end()) return std::nullopt;
  return it->second;
}

bool ObjectTracker::placeVacated(const std::string& className, const core::Pose3& X_camera_object,
                                 const cv::Mat& cloud, const CameraModel& camera) const {
  const ObjectPoseFitter* fitter = detector_.fitterFor(className);
  if (!fitter) return false;
  const ObjectPoseFitter::SurfaceEvidence e = fitter->surfaceEvidence(X_camera_object, cloud, camera);
  if (core::Log::enabled("perception", core::Log::Level::Debug))
    core::Log::writef("perception", core::Log::Level::Debug,
                      "frame %d: %s's last place (%.3f %.3f %.3f): %d samples supported, %d seen through\n", frame_ - 1,
                      className.c_str(), X_camera_object.translation().x(), X_camera_object.translation().y(),
                      X_camera_object.translation().z(), e.supported, e.seenThrough);
  return e.total() >= options_.vacatedMinEvidence && e.seenThrough >= options_.vacatedSeenThrough * e.total();
}

void ObjectTracker::answer(FrameAnswers& fa, const ObjectSegment& seg, int explainedAt,
                           const std::optional<ObjectDetection>& d) const {
  fa.next.push_back({seg.lo_plane_m, seg.hi_plane_m, static_cast<int>(seg.points_camera_m.size()), explainedAt, d});
  if (!d) return;
  ObjectDetection det = *d;
  // A static object fixed since this answer was given reports its fixed pose.
  if (const auto f = fixed_.find(det.key); f != fixed_.end()) det.X_camera_object = f->second.X_camera_object;
  fa.assigned.insert(det.key);
  fa.out.push_back(det);
}

bool ObjectTracker::isHand(const ObjectSegment& seg, const std::vector<Eigen::Vector2d>& hand_px) const {
  const double r2 = options_.handRadius_px * options_.handRadius_px;
  for (const Eigen::Vector2d& h : hand_px)
    for (const cv::Point& p : seg.pixels)
      if ((Eigen::Vector2d(p.x, p.y) - h).squaredNorm() <= r2) return true;
  return false;
}

std::vector<std::size_t> ObjectTracker::keepUnchanged(const std::vector<ObjectSegment>& segs,
                                                      const std::vector<Eigen::Vector2d>& hand_px, int now,
                                                      FrameAnswers& fa) {
  std::vector<std::size_t> pending;
  for (std::size_t i = 0; i < segs.size(); ++i) {
    if (isHand(segs[i], hand_px)) {
      ++stats_.hand;
      continue;
    }
    const auto a = std::find_if(answers_.begin(), answers_.end(), [&](const Answer& x) {
      return now - x.frame < options_.refreshFrames && same(x, segs[i]) &&
             !(x.detection && fa.assigned.count(x.detection->key));
    });
    if (a == answers_.end()) {
      pending.push_back(i);
      continue;
    }
    ++stats_.unchanged;
    const Answer kept = *a;
    answer(fa, segs[i], kept.frame, kept.detection);
    fa.next.back().lo_plane_m = kept.lo_plane_m;  // the anchor stays: no drift by small steps
    fa.next.back().hi_plane_m = kept.hi_plane_m;
    fa.next.back().pixels = kept.pixels;
  }
  return pending;
}

void ObjectTracker::verifyFixedStatics(const std::vector<ObjectSegment>& segs, std::vector<std::size_t>& pending,
                                       const Plane& plane, const cv::Mat& cloud, const CameraModel& camera, int now,
                                       FrameAnswers& fa) {
  const core::Pose3 X_plane_camera = plane.X_camera_plane().inverse();
  for (auto it = pending.begin(); it != pending.end();) {
    const ObjectSegment& seg = segs[*it];
    bool taken = false;
    for (const auto& [name, det] : fixed_) {
      if (fa.assigned.count(name)) continue;
      const ObjectPoseFitter* fitter = detector_.fitterFor(name);
      const Eigen::Vector3d p = X_plane_camera * det.X_camera_object.translation();
      if ((p - seg.centre_plane_m()).head<2>().norm() > fitter->model().dimensions_m.head<2>().norm()) continue;
      const ObjectPoseFit fit = fitter->evaluate(seg.points_camera_m, det.X_camera_object, cloud, camera);
      const double confidence = fit.score * detector_.colourScore(seg, fitter->model());
      if (fit.inlierRatio < options_.staticVerifyInliers || confidence < detector_.options().minConfidence) continue;
      answer(fa, seg, now, detector_.makeDetection(*fitter, det.X_camera_object, confidence, seg, plane));
      ++stats_.staticVerified;
      taken = true;
      break;
    }
    it = taken ? pending.erase(it) : it + 1;
  }
}

void ObjectTracker::explainPending(const std::vector<ObjectSegment>& segs, const std::vector<std::size_t>& pending,
                                   const Plane& plane, const cv::Mat& cloud, const CameraModel& camera, int now,
                                   FrameAnswers& fa) {
  std::map<std::string, core::Pose3> previous;
  for (const auto& [name, X] : lastPose_)
    if (!options_.staticClasses.count(name)) previous[name] = X;
  std::set<std::string> excluded = fa.assigned;
  for (const auto& [name, det] : fixed_) excluded.insert(name);
  // Each segment's search depends on this frame and the last poses only: the
  // searches run on searchThreads threads, each answer kept in its segment's
  // slot (the same answers as one after the other).
  std::vector<std::optional<ObjectDetection>> answers(pending.size());
  std::atomic<std::size_t> nextSearch{0};
  const auto search = [&] {
    for (std::size_t k; (k = nextSearch++) < pending.size();)
      answers[k] = detector_.explain(segs[pending[k]], plane, cloud, camera, previous, excluded);
  };
  std::vector<std::future<void>> others;
  const std::size_t threads = std::min<std::size_t>(std::max(options_.searchThreads, 1), pending.size());
  for (std::size_t t = 1; t < threads; ++t) others.push_back(std::async(std::launch::async, search));
  try {
    search();
  } catch (...) {
    for (auto& o : others) o.wait();
    throw;
  }
  for (auto& o : others) o.get();
  std::vector<std::pair<std::size_t, std::optional<ObjectDetection>>> found;
  for (std::size_t k = 0; k < pending.size(); ++k) found.emplace_back(pending[k], std::move(answers[k]));
  stats_.explained += static_cast<int>(pending.size());
  std::stable_sort(found.begin(), found.end(), [](const auto& a, const auto& b) {
    return (a.second ? a.second->confidence : 0.0) > (b.second ? b.second->confidence : 0.0);
  });
  for (auto& [i, d] : found) {
    if (d && fa.assigned.count(d->key)) {
      // Its class went to a better segment: the next best class, if any.
      for (const auto& n : fa.assigned) excluded.insert(n);
      d = detector_.explain(segs[i], plane, cloud, camera, previous, excluded);
      ++stats_.explained;
      if (d && fa.assigned.count(d->key)) d.reset();
    }
    answer(fa, segs[i], now, d);
  }
}

void ObjectTracker::dropUnheldJumps(std::vector<ObjectDetection>& out, const std::vector<Eigen::Vector2d>& hand_px,
                                    const cv::Mat& cloud, const CameraModel& camera) {
  for (const auto& [name, X] : lastPose_) {
    if (options_.staticClasses.count(name)) continue;
    const Eigen::Vector2d at_px = camera.cameraToPixel(X.translation());
    const double visit_px = camera.intrinsics().fx_px * options_.handVisit_m / std::max(X.translation().z(), 0.1);
    for (const Eigen::Vector2d& h : hand_px)
      if ((h - at_px).norm() <= visit_px) handVisited_[name] = true;
  }
  out.erase(std::remove_if(out.begin(), out.end(),
                           [&](const ObjectDetection& d) {
                             if (options_.staticClasses.count(d.key)) return false;
                             const auto last = lastPose_.find(d.key);
                             if (last == lastPose_.end() || handVisited_[d.key]) return false;
                             if (core::translationDistance(d.X_camera_object, last->second) <= options_.maxUnheldJump_m) {
                               pendingJumps_.erase(d.key);
                               return false;
                             }
                             if (placeVacated(d.key, last->second, cloud, camera)) return false;
                             auto& jump = pendingJumps_[d.key];
                             const bool same = jump.frames > 0 && core::translationDistance(d.X_camera_object, jump.X_camera_object) <= options_.maxUnheldJump_m;
                             jump.frames = same ? jump.frames + 1 : 1;
                             jump.X_camera_object = d.X_camera_object;
                             return jump.frames < options_.jumpConfirmFrames;
                           }),
            out.end());
}

void ObjectTracker::remember(const std::vector<ObjectDetection>& out) {
  for (const ObjectDetection& d : out) {
    handVisited_[d.key] = false;
    pendingJumps_.erase(d.key);
    lastPose_[d.key] = d.X_camera_object;
    if (!options_.staticClasses.count(d.key) || fixed_.count(d.key)) continue;
    auto& seen = staticDetections_[d.key];
    seen.push_back(d);
    if (static_cast<int>(seen.size()) >= options_.staticFixDetections)
      fixed_[d.key] = *std::max_element(seen.begin(), seen.end(), [](const auto& a, const auto& b) {
        return a.confidence < b.confidence;
      });
  }
}

ObjectTracker::FrameSegments ObjectTracker::segment(const rawlog::RgbdFrame& frame, const Plane* support) {
  if (frame.depth_m.empty())
    throw core::InvalidInputError("frame " + std::to_string(frame.index) + " has no depth image: objects need depth");
  FrameSegments out;
  std::swap(out.cloud, cloud_);  // the last frame's memory
  depthToCloud(frame.depth_m, CameraModel(frame.intrinsics), out.cloud);
  out.plane = support ? std::optional<Plane>(*support) : fitDominantPlane(out.cloud, detector_.options().plane);
  if (out.plane) out.segments = detector_.segments(frame, out.cloud, *out.plane);
  return out;
}

std::vector<ObjectDetection> ObjectTracker::update(const rawlog::RgbdFrame& frame, const Plane* support,
                                                  const std::vector<Eigen::Vector2d>& hand_px) {
  return update(frame, segment(frame, support), hand_px);
}

std::vector<ObjectDetection> ObjectTracker::update(const rawlog::RgbdFrame& frame, FrameSegments segmented,
                                                  const std::vector<Eigen::Vector2d>& hand_px) {
  const int now = frame_++;
  stats_ = Stats{};
  const CameraModel camera(frame.intrinsics);
  cloud_ = std::move(segmented.cloud);
  const cv::Mat& cloud = cloud_;
  lastPlane_ = std::move(segmented.plane);
  if (!lastPlane_) {
    answers_.clear();
    return {};
  }
  const Plane& plane = *lastPlane_;
  const std::vector<ObjectSegment> segs = std::move(segmented.segments);
  stats_.segments = static_cast<int>(segs.size());

  FrameAnswers fa;
  // 0. The hand's segment (with what it holds) explains no object;
  // 1. unchanged segments keep their answer.
  std::vector<std::size_t> pending = keepUnchanged(segs, hand_px, now, fa);
  // 2. Fixed static objects: verified at their pose, no fit.
  verifyFixedStatics(segs, pending, plane, cloud, camera, now, fa);
  // 3. The rest: tracking from the last poses, else the full search; each
  // class to its most confident segment.
  explainPending(segs, pending, plane, cloud, camera, now, fa);
  std::vector<ObjectDetection>& out = fa.out;
  // Two parts cannot fill the same space (ObjectDetector::overlappingParts):
  // the less confident goes, and its segment's answer with it.
  const std::set<std::string> dropped = detector_.overlappingParts(out, plane);
  if (!dropped.empty()) {
    out.erase(std::remove_if(out.begin(), out.end(), [&](const auto& d) { return dropped.count(d.key) > 0; }),
              out.end());
    for (Answer& x : fa.next)
      if (x.detection && dropped.count(x.detection->key)) x.detection.reset();
  }
  answers_ = std::move(fa.next);

  // A moving part far from where it was, with no grasp since: not believed yet.
  dropUnheldJumps(out, hand_px, cloud, camera);
  remember(out);
  std::sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.confidence > b.confidence; });
  return out;
}

}  // namespace srp::perception
