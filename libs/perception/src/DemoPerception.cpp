#include "srp/perception/DemoPerception.h"
#include "srp/core/Log.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <future>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <sstream>

#include "srp/core/Error.h"
#include "srp/core/OutputFile.h"
#include "srp/perception/DepthCloud.h"
#include "srp/rawlog/RawlogReader.h"

namespace srp::perception {

int ObjectTrajectory::detectedFrames() const {
  return static_cast<int>(std::count_if(samples.begin(), samples.end(), [](const auto& s) { return s.detected; }));
}

double cameraYaw(const core::Pose3& X_camera_object) {
  const Eigen::Vector3d x = X_camera_object.linear().col(0);
  return std::atan2(x.y(), x.x());
}

namespace {


void checkFrame(const rawlog::RgbdFrame& f, const rawlog::RgbdFrame& first, int i) {
  const std::string what = "frame " + std::to_string(i);
  if (f.depth_m.empty())
    throw core::InvalidInputError(what + " has no depth image: record the demo with an RGB-D camera (depth registered to colour)");
  if (f.colour_bgr8.empty()) throw core::InvalidInputError(what + " has no colour image: the hand and tag detectors need colour");
  f.validate(what);
  if (f.depth_m.size() != first.depth_m.size() || f.intrinsics != first.intrinsics)
    throw core::InvalidInputError(what + ": image size or intrinsics differ from frame 0 (" +
                                  std::to_string(f.depth_m.cols) + "x" + std::to_string(f.depth_m.rows) + " vs " +
                                  std::to_string(first.depth_m.cols) + "x" + std::to_string(first.depth_m.rows) +
                                  "); a demo must come from one camera setting");
}

// One detector model per plan object, named by its key: the class's shape,
// the instance's colour when it has one (its colour is then evidence, also
// for a class whose catalogue colour is not discriminative). Throws
// InvalidInputError for a repeated key or an unknown class.
std::vector<ObjectModel> instanceModels(const core::ObjectCatalogue& catalogue, const std::vector<PlanObject>& plan) {
  std::set<std::string> keys, classes;
  for (const auto& p : plan) classes.insert(p.className);
  std::map<std::string, ObjectModel> byClass;  // a class's model is built once
  std::vector<ObjectModel> models;
  for (const auto& p : plan) {
    if (!keys.insert(p.key()).second || (!p.instanceId.empty() && p.instanceId != p.className && classes.count(p.instanceId)))
      throw core::InvalidInputError("perception plan: object '" + p.key() + "' (class '" + p.className +
                                    "') is named twice or after another class; give each instance a unique id");
    auto it = byClass.find(p.className);
    if (it == byClass.end()) it = byClass.emplace(p.className, ObjectModel::fromCatalogue(catalogue.at(p.className))).first;
    ObjectModel model = it->second;
    model.name = p.key();
    if (p.rgb) {
      model.rgb = *p.rgb;
      model.useColour = true;
    }
    models.push_back(std::move(model));
  }
  return models;
}

bool useModelBasedTracking(const PerceptionOptions& o, bool movingCamera) {
  return o.objectTracking == PerceptionOptions::ObjectTracking::Mbt ||
         (o.objectTracking == PerceptionOptions::ObjectTracking::Auto && movingCamera);
}

}  // namespace

struct DemoPerceiver::Impl {
  const core::ObjectCatalogue& catalogue;
  PerceptionOptions options;
  std::vector<PlanObject> plan;
  std::unique_ptr<ObjectDetector> detector;
  std::unique_ptr<ObjectTracker> tracker;
  std::unique_ptr<HandDetector> hand;
  PerceptionOptions::HandMethod handUsed = PerceptionOptions::HandMethod::Marker;  // Auto until the preview decided
  std::unique_ptr<HandDetector> tagProbe;  // Auto: the glove's tag looked for in the preview
  int previewed = 0, tagFrames = 0;
  std::unique_ptr<ObjectDiscovery> discovery;
  std::map<std::string, std::unique_ptr<ModelBasedTracker>> mbt;  // per moving class, when tracking with ViSP
  // Per moving class, this frame: the pose ViSP tracked but the depth did not confirm (mbtCompareBeforeReinit).
  std::map<std::string, core::Pose3> unconfirmed;
  // Per moving class: the last pose the depth confirmed (tracked, or the one the tracker started from).
  std::map<std::string, core::Pose3> lastConfirmed;
  std::optional<rawlog::RgbdFrame> first;  // images released: only size and intrinsics are kept
  std::optional<Plane> support;
  std::optional<Plane> firstSupport;  // the support plane in the first frame's camera
  std::unique_ptr<CameraMotionEstimator> cameraMotion;  // when watched or declared moving
  bool moving = false;  // perceived as with a moving camera (declared, or from the frame it was noticed)
  std::vector<int> frameIndex;
  std::vector<double> frameTime_s;
  // Per class: per frame, the best detection (if any).
  std::map<std::string, std::vector<std::optional<ObjectDetection>>> perClass;
  PerceptionResult result;
  bool haveDepth = false;
  double lastZ_m = 0.0;
  double lastZ_t_s = 0.0;  // when lastZ_m was measured
  const bool debug = core::Log::enabled("perception", core::Log::Level::Debug);

  Impl(const core::ObjectCatalogue& c, const PerceptionOptions& o) : catalogue(c), options(o) {}
  std::map<std::string, ObjectDetection> trackParts(const rawlog::RgbdFrame& f);
  void mergeTracked(const rawlog::RgbdFrame& f, const std::map<std::string, ObjectDetection>& tracked,
                    std::vector<ObjectDetection>& detections);
  bool visibleEnough(const rawlog::RgbdFrame& f, const ObjectPoseFitter& fitter, const core::Pose3& X_camera_object,
                     const std::string& key) const;
  // The steps of DemoPerceiver::add, in order.
  void startFrame(const rawlog::RgbdFrame& f, int i);
  std::optional<ObjectTracker::FrameSegments> cameraAndHand(const rawlog::RgbdFrame& f, std::optional<HandObservation>& h);
  void noteCameraMotion(const rawlog::RgbdFrame& f);
  core::PositionSample handSample(const rawlog::RgbdFrame& f, const std::optional<HandObservation>& h);
  void detectObjects(const rawlog::RgbdFrame& f, const std::optional<HandObservation>& h,
                     std::optional<ObjectTracker::FrameSegments> segmented);
  void addToDiscovery(const rawlog::RgbdFrame& f, const std::optional<HandObservation>& h, const core::PositionSample& s);
  // The steps of DemoPerceiver::finish.
  void throwIfNothingToPerceive() const;
  std::vector<std::optional<ObjectDetection>> consolidatedRests(const PlanObject& p,
                                                                const std::vector<std::optional<ObjectDetection>>& dets) const;
  using CarryPose = std::function<core::Pose3(const core::Pose3&, std::size_t, std::size_t)>;
  ObjectTrajectory trajectoryOf(const PlanObject& p, const CarryPose& carry) const;
};

/// The re-initialisation gate (PerceptionOptions::mbtMinDetectionVisibleFraction,
/// mbtMinDetectionSupport): is the model at X_camera_object mostly in view
/// and in the depth image?
bool DemoPerceiver::Impl::visibleEnough(const rawlog::RgbdFrame& f, const ObjectPoseFitter& fitter,
                                        const core::Pose3& X_camera_object, const std::string& key) const {
  const auto& o = options;
  if (o.mbtMinDetectionVisibleFraction <= 0.0 && o.mbtMinDetectionSupport <= 0.0 && !debug) return true;
  const ObjectPoseFitter::SurfaceEvidence e =
      fitter.surfaceEvidenceInDepth(X_camera_object, f.depth_m, f.intrinsics, o.mbtOccluderMargin_m);
  const double visible = e.inView > 0 ? 1.0 - static_cast<double>(e.occluded) / e.inView : 0.0;
  const double support = e.inView > 0 ? static_cast<double>(e.supported) / e.inView : 0.0;
  const bool ok = visible >= o.mbtMinDetectionVisibleFraction && support >= o.mbtMinDetectionSupport;
  if (debug)
    core::Log::writef("perception", core::Log::Level::Debug,
                      "frame %d: %s (re)initialisation gate: %d samples, visible %.2f, supported %.2f: %s\n", f.index,
                      key.c_str(), e.inView, visible, support, ok ? "used" : "rejected");
  return ok;
}

/// Moving classes followed by ViSP's model-based tracker, before detection:
/// the pose of each class whose tracker is running and not lost this frame.
std::map<std::string, ObjectDetection> DemoPerceiver::Impl::trackParts(const rawlog::RgbdFrame& f) {
  Impl& m = *this;
  std::map<std::string, ObjectDetection> out;
  const CameraModel camera(f.intrinsics);
  cv::Mat cloud;
  m.unconfirmed.clear();
  for (const auto& p : m.plan) {
    if (p.isStatic) continue;
    const ObjectPoseFitter* fitter = m.detector->fitterFor(p.key());
    auto it = m.mbt.find(p.key());
    if (!fitter || it == m.mbt.end() || !it->second || !it->second->initialised()) continue;
    const auto t0 = std::chrono::steady_clock::now();
    const ModelBasedTracker::Result r = it->second->track(f);
    const double track_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    double coverage = 0.0;
    if (r.tracked) {
      if (cloud.empty()) depthToCloud(f.depth_m, camera, cloud);
      coverage = fitter->coverage(r.X_camera_mesh, cloud, camera);
      // A depth offset from the colour along the ray must not lose a pose that follows the colour.
      constexpr double kShiftStep_m = 0.001;
      const Eigen::Vector3d ray = r.X_camera_mesh.translation().normalized();
      const int steps = static_cast<int>(std::lround(m.options.mbtDepthShiftTolerance_m / kShiftStep_m));
      for (int s = -steps; s <= steps; ++s) {
        if (s == 0) continue;
        core::Pose3 shifted = r.X_camera_mesh;
        shifted.translation() += ray * (kShiftStep_m * s);
        coverage = std::max(coverage, fitter->coverage(shifted, cloud, camera));
      }
    }
    const bool tracked = r.tracked && coverage >= m.options.mbtMinCoverage;
    if (m.debug)
      core::Log::writef(
          "perception", core::Log::Level::Debug,
          "frame %d: %s mbt %s in %.1f ms: %d klt, %d depth, %d edge features, projection error %.1f deg, "
          "coverage %.2f\n",
          f.index, p.key().c_str(), tracked ? "tracked" : "lost", track_ms, r.kltPoints, r.depthFeatures,
          r.edgeFeatures, r.projectionError_deg, coverage);
    if (!tracked) {
      if (r.tracked && m.options.mbtCompareBeforeReinit && coverage >= m.options.mbtKeepMinCoverage) {
        m.unconfirmed[p.key()] = r.X_camera_mesh;  // weighed against the detection in mergeTracked
        continue;
      }
      it->second.reset();  // lost: a new tracker from the next detection
      continue;
    }
    ObjectDetection d;
    d.key = p.key();  // the detector's model name
    d.classId = fitter->model().classId;
    d.size_m = fitter->model().dimensions_m;
    d.X_camera_object = r.X_camera_mesh;  // the tracker's model is the fitter's (model frame)
    d.confidence = coverage;
    d.p_camera_median_m = r.X_camera_mesh.translation();
    out[p.key()] = d;
    m.lastConfirmed[p.key()] = r.X_camera_mesh;
  }
  return out;
}

/// After detection: tracked classes report the tracked pose; the others
/// (lost, or not started) keep their detection, which starts their tracker.
void DemoPerceiver::Impl::mergeTracked(const rawlog::RgbdFrame& f, const std::map<std::string, ObjectDetection>& tracked,
                                       std::vector<ObjectDetection>& detections) {
  Impl& m = *this;
  for (const auto& p : m.plan) {
    if (p.isStatic) continue;
    const ObjectPoseFitter* fitter = m.detector->fitterFor(p.key());
    if (!fitter) continue;
    auto detected = std::find_if(detections.begin(), detections.end(),
                                 [&](const ObjectDetection& d) { return d.key == p.key(); });
    if (const auto t = tracked.find(p.key()); t != tracked.end()) {
      if (detected != detections.end()) *detected = t->second;
      else detections.push_back(t->second);
      continue;
    }
    auto& tracker = m.mbt[p.key()];
    const auto unconfirmed = m.unconfirmed.find(p.key());
    if (unconfirmed != m.unconfirmed.end() && tracker) {
      // The depth did not confirm the tracked pose: the colour image decides
      // between it and the detection (a blurred frame's detection can be
      // worse than the pose it would replace).
      const double trackedEdge_px = tracker->edgeDistance_px(f, unconfirmed->second);
      const double detectedEdge_px =
          detected != detections.end() ? tracker->edgeDistance_px(f, detected->X_camera_object) : 1e9;
      if (m.debug)
        core::Log::writef("perception", core::Log::Level::Debug,
                          "frame %d: %s unconfirmed: edges %.2f px tracked, %.2f px detected\n", f.index,
                          p.key().c_str(), trackedEdge_px, detected != detections.end() ? detectedEdge_px : -1.0);
      if (detected != detections.end() && trackedEdge_px <= detectedEdge_px + m.options.mbtReinitEdgeMargin_px) {
        detected->X_camera_object = unconfirmed->second;
        detected->p_camera_median_m = unconfirmed->second.translation();
      }
    }
    // The gate: neither the pose that would start the tracker nor the part's
    // last confirmed place may be mostly hidden behind nearer depth (a part
    // behind a passing hand: the detector then takes another object, or the
    // few pixels of the part still in view).
    const auto last = m.lastConfirmed.find(p.key());
    if (detected != detections.end() &&
        ((last != m.lastConfirmed.end() && !visibleEnough(f, *fitter, last->second, p.key() + " last place")) ||
         !visibleEnough(f, *fitter, detected->X_camera_object, p.key()))) {
      // Reported not detected (every detection of the class: the detector may report it on several segments).
      detections.erase(std::remove_if(detections.begin(), detections.end(),
                                      [&](const ObjectDetection& d) { return d.key == p.key(); }),
                       detections.end());
      detected = detections.end();
    }
    if (detected == detections.end()) {
      tracker.reset();  // lost, nothing detected: a new tracker from the next detection
      continue;
    }
    if (!tracker) tracker = std::make_unique<ModelBasedTracker>(fitter->model().mesh, f.intrinsics, m.options.mbt);
    tracker->initialise(f, detected->X_camera_object);
    m.lastConfirmed[p.key()] = detected->X_camera_object;
  }
}

DemoPerceiver::DemoPerceiver(const core::ObjectCatalogue& catalogue, const PerceptionOptions& options)
    : impl_(std::make_unique<Impl>(catalogue, options)) {
  for (const auto& [name, share] : {std::make_pair("mbtMinDetectionVisibleFraction", options.mbtMinDetectionVisibleFraction),
                                    std::make_pair("mbtMinDetectionSupport", options.mbtMinDetectionSupport)})
    if (!(share >= 0.0 && share <= 1.0))
      throw core::InvalidInputError("perception options: " + std::string(name) + " = " + std::to_string(share) +
                                    " is a share of the model's samples; give a value in [0, 1] (0 = no gate)");
  if (!(options.mbtOccluderMargin_m >= 0.0))
    throw core::InvalidInputError("perception options: mbtOccluderMargin_m = " +
                                  std::to_string(options.mbtOccluderMargin_m) +
                                  " must be a distance >= 0 [m] (depth this much nearer than the model hides it)");
  // Objects of interest: the plan's, else every class (moving).
  // Objects of interest: the plan's, else every class (moving) unless only unknown objects are looked for.
  impl_->plan = options.plan;
  if (impl_->plan.empty() && options.unknownObjects.empty())
    for (const auto& c : catalogue.classes()) impl_->plan.push_back({c.name, false, "", std::nullopt});
  if (!impl_->plan.empty()) {
    impl_->detector = std::make_unique<ObjectDetector>(instanceModels(catalogue, impl_->plan), options.objects);
    ObjectTracker::Options tracking = options.tracking;
    for (const auto& p : impl_->plan)
      if (p.isStatic) tracking.staticClasses.insert(p.key());
    impl_->tracker = std::make_unique<ObjectTracker>(*impl_->detector, tracking);
  }
  if (!options.unknownObjects.empty())
    impl_->discovery = std::make_unique<ObjectDiscovery>(options.unknownObjects, options.discovery);
  impl_->handUsed = options.hand;
  if (options.hand == PerceptionOptions::HandMethod::Marker) impl_->hand = std::make_unique<MarkerHandDetector>(options.marker);
  else if (options.hand == PerceptionOptions::HandMethod::MarkerFree || options.hand == PerceptionOptions::HandMethod::Auto)
    impl_->hand = std::make_unique<MarkerFreeHandDetector>(options.markerFree);
  if (options.hand == PerceptionOptions::HandMethod::Auto) impl_->tagProbe = std::make_unique<MarkerHandDetector>(options.marker);
  for (const auto& p : impl_->plan) impl_->perClass[p.key()];
}

DemoPerceiver::~DemoPerceiver() = default;

int DemoPerceiver::framesAdded() const { return static_cast<int>(impl_->frameIndex.size()); }

bool DemoPerceiver::wantsPreview() const {
  return impl_->options.hand == PerceptionOptions::HandMethod::MarkerFree ||
         impl_->options.hand == PerceptionOptions::HandMethod::Auto;
}

bool DemoPerceiver::previewComplete() const {
  return impl_->options.hand == PerceptionOptions::HandMethod::Auto &&
         impl_->handUsed == PerceptionOptions::HandMethod::Marker;
}

void DemoPerceiver::preview(const rawlog::RgbdFrame& f) {
  Impl& m = *impl_;
  if (m.handUsed == PerceptionOptions::HandMethod::Auto) {
    if (!m.tagProbe) return;  // decided: the glove's tag is seen
    // The glove's tag, looked for in every probeStride-th frame: seen in enough, the marker hand.
    if (m.previewed++ % m.options.autoHandProbeStride == 0 && m.tagProbe->detect(f) &&
        ++m.tagFrames >= m.options.autoHandMinTagFrames) {
      m.hand = std::move(m.tagProbe);
      m.handUsed = PerceptionOptions::HandMethod::Marker;
      return;
    }
  }
  if (m.hand) m.hand->preview(f);
}

/// The first frame's header, the hand chosen after the preview, the camera-motion watch.
void DemoPerceiver::Impl::startFrame(const rawlog::RgbdFrame& f, int i) {
  Impl& m = *this;
  if (!m.first) {
    checkFrame(f, f, i);
    rawlog::RgbdFrame header;
    header.intrinsics = f.intrinsics;
    header.depth_m = cv::Mat(f.depth_m.size(), CV_32FC1);
    m.first = header;
    m.result.intrinsics = f.intrinsics;
  }
  checkFrame(f, *m.first, i);
  if (i == 0 && m.handUsed == PerceptionOptions::HandMethod::Auto) {
    // No tag in the preview (or no preview): the marker-free hand, which learnt from it.
    m.tagProbe.reset();
    m.handUsed = m.previewed > 0 ? PerceptionOptions::HandMethod::MarkerFree : PerceptionOptions::HandMethod::Marker;
    if (m.handUsed == PerceptionOptions::HandMethod::Marker) m.hand = std::make_unique<MarkerHandDetector>(m.options.marker);
    if (m.debug)
      core::Log::writef(
          "perception", core::Log::Level::Debug, "hand: %s (glove tag in %d of the %d previewed frames probed)\n",
          m.handUsed == PerceptionOptions::HandMethod::Marker ? "marker" : "marker-free", m.tagFrames, m.previewed);
  }
  if (i == 0) {
    m.moving = m.options.movingCamera;
    if (m.moving) m.result.cameraMovedAtFrame = f.index;
    if (m.options.movingCamera || m.options.detectCameraMotion)
      m.cameraMotion = std::make_unique<CameraMotionEstimator>(f.intrinsics, m.options.cameraMotion);
  }
}

/// The camera's motion and the hand in frame f, with the tracker's segmentation of it when the camera is still.
std::optional<ObjectTracker::FrameSegments> DemoPerceiver::Impl::cameraAndHand(const rawlog::RgbdFrame& f,
                                                                              std::optional<HandObservation>& h) {
  Impl& m = *this;
  // The camera's motion and the hand in this frame depend on the frame and
  // their own past only: with a still camera they are found on a second
  // thread while the tracker segments the frame (the same results, in about
  // the time of the slower of the two).
  const auto watch = [&] {
    if (m.cameraMotion) m.cameraMotion->add(f);
    if (m.hand) h = m.hand->detect(f);
  };
  std::optional<ObjectTracker::FrameSegments> segmented;
  if (m.tracker && !m.moving && m.support) {
    auto side = std::async(std::launch::async, watch);
    try {
      segmented = m.tracker->segment(f, m.options.fixedSupportPlane ? &*m.support : nullptr);
    } catch (...) {
      side.get();  // its error first, as a sequential run would throw it
      throw;
    }
    side.get();
  } else {
    watch();
  }
  return segmented;
}

/// From the frame the camera is noticed moving on, perceived as with a moving camera.
void DemoPerceiver::Impl::noteCameraMotion(const rawlog::RgbdFrame& f) {
  Impl& m = *this;
  if (m.cameraMotion) {
    if (!m.moving && m.cameraMotion->moved()) {
      m.moving = true;  // from here on as with a moving camera
      m.result.cameraMovedAtFrame = f.index;
      if (m.debug)
        core::Log::writef("perception", core::Log::Level::Debug,
                          "frame %d: the camera moved, perceived as moving from here on\n", f.index);
    }
  }
}

/// The palm's sample of frame f (a depth hole or jump: the depth carried forward).
core::PositionSample DemoPerceiver::Impl::handSample(const rawlog::RgbdFrame& f, const std::optional<HandObservation>& h) {
  Impl& m = *this;
  core::PositionSample s;
  s.frame = f.index;
  s.t_s = f.t_s;
  s.valid = false;
  if (h) {
    // A palm depth farther from the last one than the hand can move since
    // (a hole in a blurred hand filled by the wall behind it) is a hole too.
    const bool depthJump = h->hasDepth && m.haveDepth && m.options.maxPalmDepthSpeed_mps > 0.0 &&
                           std::abs(h->p_camera_palm_m.z() - m.lastZ_m) >
                               m.options.maxPalmDepthSpeed_mps * std::max(f.t_s - m.lastZ_t_s, 1.0 / 30.0);
    if (h->hasDepth && !depthJump) {
      s.p_m = h->p_camera_palm_m;
      m.lastZ_m = h->p_camera_palm_m.z();
      m.lastZ_t_s = f.t_s;
      m.haveDepth = true;
      s.valid = true;
    } else if (m.haveDepth) {
      // Depth hole: the palm's pixel is known, its depth is carried forward.
      const auto& k = f.intrinsics;
      s.p_m = {(h->palm_px.x() - k.cx_px) * m.lastZ_m / k.fx_px, (h->palm_px.y() - k.cy_px) * m.lastZ_m / k.fy_px,
               m.lastZ_m};
      s.valid = true;
      ++m.result.handDepthCarried;
    }
    if (s.valid) ++m.result.handDetected;
  }
  return s;
}

/// The support plane and the objects of frame f, after the hand.
void DemoPerceiver::Impl::detectObjects(const rawlog::RgbdFrame& f, const std::optional<HandObservation>& h,
                                        std::optional<ObjectTracker::FrameSegments> segmented) {
  Impl& m = *this;
  // Objects after the hand: the hand's segment (and a part it holds) explains no object.
  const auto detectStart = std::chrono::steady_clock::now();  // plane fit and detection: the fitter's cost
  std::optional<Plane> movingPlane;
  if (!m.support) {
    // The first frame's support plane: the table, not a larger wall behind it.
    m.support = fitSupportPlane(depthToCloud(f.depth_m, CameraModel(f.intrinsics)), m.options.objects.plane);
    m.firstSupport = m.support;
    movingPlane = m.support;
  } else if (m.moving) {
    // The table turns little between frames: the plane is looked for near
    // the last one, so that a wall or board filling more of the image does
    // not take its place (frame 41 of the real RealSense recording).
    PlaneFitOptions po = m.options.objects.plane;
    po.expectedNormal = m.support->n;
    po.maxTilt_rad = m.options.maxPlaneTurnPerFrame_rad;
    movingPlane = fitDominantPlane(depthToCloud(f.depth_m, CameraModel(f.intrinsics)), po);
    if (!movingPlane) movingPlane = m.support;
    m.support = movingPlane;
  }
  if (m.detector) {
    const std::vector<Eigen::Vector2d> palm_px =
        h ? std::vector<Eigen::Vector2d>{h->palm_px} : std::vector<Eigen::Vector2d>{};
    // Model-based tracking first: when every moving class is tracked, no detection is needed.
    const bool useMbt = useModelBasedTracking(m.options, m.moving);
    const std::map<std::string, ObjectDetection> tracked = useMbt ? m.trackParts(f) : std::map<std::string, ObjectDetection>{};
    const bool allTracked =
        useMbt && m.moving && std::all_of(m.plan.begin(), m.plan.end(), [&](const PlanObject& p) {
          return p.isStatic || tracked.count(p.key()) > 0;
        });
    auto detections =
        m.moving
            ? (movingPlane && !allTracked ? m.detector->detect(f, &*movingPlane) : std::vector<ObjectDetection>{})
            : segmented ? m.tracker->update(f, std::move(*segmented), palm_px)
                        : m.tracker->update(f, m.options.fixedSupportPlane && m.support ? &*m.support : nullptr, palm_px);
    if (m.debug)
      core::Log::writef(
          "perception", core::Log::Level::Debug, "frame %d: %s in %.1f ms\n", f.index,
          allTracked ? "plane fit (all tracked)" : "detection",
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - detectStart).count());
    if (m.options.onFrameDetections) m.options.onFrameDetections(f.index, detections);
    if (useMbt) m.mergeTracked(f, tracked, detections);
    if (!m.support) m.support = m.tracker->lastPlane();
    if (m.debug && !m.moving) {
      const auto& st = m.tracker->lastStats();
      core::Log::writef("perception", core::Log::Level::Debug,
                        "frame %d: %d segments: %d hand, %d unchanged, %d static verified, %d explained\n", f.index,
                        st.segments, st.hand, st.unchanged, st.staticVerified, st.explained);
    }
    for (auto& [name, perFrame] : m.perClass) perFrame.emplace_back();
    for (const auto& d : detections) {
      auto& slot = m.perClass[d.key].back();
      if (!slot || d.confidence > slot->confidence) slot = d;
    }
  }
}

/// Frame f for the parts found without a CAD file.
void DemoPerceiver::Impl::addToDiscovery(const rawlog::RgbdFrame& f, const std::optional<HandObservation>& h,
                                         const core::PositionSample& s) {
  Impl& m = *this;
  if (m.discovery && m.firstSupport) {
    // The table frame in this frame's camera: the first frame's plane, carried by the camera's motion.
    core::Pose3 X_camera_table = m.firstSupport->X_camera_plane();
    if (m.moving && m.cameraMotion) X_camera_table = m.cameraMotion->poses().back().inverse() * X_camera_table;
    const auto* markerFree = dynamic_cast<const MarkerFreeHandDetector*>(m.hand.get());
    m.discovery->add(f, X_camera_table, s.valid ? std::optional<Eigen::Vector3d>(s.p_m) : std::nullopt,
                     h && markerFree ? markerFree->lastMask() : cv::Mat());
  }

}

void DemoPerceiver::add(const rawlog::RgbdFrame& f) {
  Impl& m = *impl_;
  m.startFrame(f, framesAdded());
  std::optional<HandObservation> h;
  std::optional<ObjectTracker::FrameSegments> segmented = m.cameraAndHand(f, h);
  m.noteCameraMotion(f);
  m.frameIndex.push_back(f.index);
  m.frameTime_s.push_back(f.t_s);
  core::PositionSample s = m.handSample(f, h);
  m.detectObjects(f, h, std::move(segmented));
  m.addToDiscovery(f, h, s);

  // Timestamps must increase; folders without timestamps may repeat them.
  if (!m.result.hand.empty() && s.t_s <= m.result.hand.samples().back().t_s)
    s.t_s = m.result.hand.samples().back().t_s + 1e-6;
  m.result.hand.append(s);
}

/// Refuses a demo without frames, or one in which the hand was never seen, naming what to check.
void DemoPerceiver::Impl::throwIfNothingToPerceive() const {
  const Impl& m = *this;
  if (m.frameIndex.empty()) throw core::InvalidInputError("the demo has zero frames: nothing to perceive");
  if (m.result.handDetected == 0 && m.hand)
    throw core::InvalidInputError("the hand was never detected in the " + std::to_string(m.frameIndex.size()) +
                                  " frames of the demo (" +
                                  (m.handUsed == PerceptionOptions::HandMethod::Marker
                                       ? std::string("no tag36h11 tag of the glove seen: check the tag size/id, use the marker-free detector, or "
                                                     "perceive objects only (HandMethod::None, srp perceive --hand none)")
                                       : std::string(m.options.hand == PerceptionOptions::HandMethod::Auto
                                                         ? "no glove tag and no bare hand (skin-coloured foreground at the end of an arm): "
                                                         : "no skin-coloured foreground at the end of an arm: ") +
                                             "is the demonstrator's hand in view and does the camera stay still?") +
                                  "); nothing written");
}

/// Rests of a moving part: runs of detections near their running median, given their median yaw.
std::vector<std::optional<ObjectDetection>> DemoPerceiver::Impl::consolidatedRests(
    const PlanObject& p, const std::vector<std::optional<ObjectDetection>>& dets) const {
  const Impl& m = *this;
  std::vector<std::optional<ObjectDetection>> rested = dets;
  if (!p.isStatic && m.options.consolidateRests && !m.moving) {
    const ObjectPoseFitter* fitter = m.detector->fitterFor(p.key());
    const double symmetry_rad = fitter ? fitter->model().yawSymmetry_rad : 2 * M_PI;
    const core::Pose3 X_plane_camera = m.support ? m.support->X_camera_plane().inverse() : core::Pose3::Identity();
    auto yawInPlane = [&](const core::Pose3& X) { return core::yawOf((X_plane_camera * X).linear()); };
    std::vector<std::size_t> rest;
    auto close = [&]() {
      if (rest.size() >= 3) {
        std::vector<double> dyaw;
        const double yaw0 = yawInPlane(dets[rest.front()]->X_camera_object);
        for (std::size_t i : rest)
          dyaw.push_back(std::remainder(yawInPlane(dets[i]->X_camera_object) - yaw0, symmetry_rad));
        // The detection whose yaw is the median lends its orientation (tilt included).
        std::vector<std::size_t> order(rest.size());
        for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
        std::nth_element(order.begin(), order.begin() + static_cast<long>(order.size() / 2), order.end(),
                         [&](std::size_t a, std::size_t b) { return dyaw[a] < dyaw[b]; });
        const Eigen::Matrix3d R = dets[rest[order[order.size() / 2]]]->X_camera_object.linear();
        // The orientation only: each detection keeps its position, which
        // the motion module reads for the small moves of a grasp and a
        // release (snapping them to the rest's median hid a whole pick
        // from its segmentation on a 320x240 demo).
        for (std::size_t i : rest) rested[i]->X_camera_object.linear() = R;
      }
      rest.clear();
    };
    Eigen::Vector3d anchor = Eigen::Vector3d::Zero();
    std::vector<Eigen::Vector3d> members;
    for (std::size_t i = 0; i < dets.size(); ++i) {
      if (!dets[i]) continue;
      const Eigen::Vector3d t = dets[i]->X_camera_object.translation();
      if (!rest.empty() && (t - anchor).norm() > m.options.restRadius_m) {
        close();
        members.clear();
      }
      rest.push_back(i);
      members.push_back(t);
      // The anchor: the members' per-axis median (a stray detection does not drag it).
      for (int a = 0; a < 3; ++a) {
        std::vector<double> v;
        for (const auto& x : members) v.push_back(x[a]);
        std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
        anchor[a] = v[v.size() / 2];
      }
    }
    close();
  }
  return rested;
}

/// Language-guided refinement: static objects fixed at their most confident
/// detection; moving objects follow their detections, gaps carried from the
/// nearest earlier detection (before the first: the first).
ObjectTrajectory DemoPerceiver::Impl::trajectoryOf(const PlanObject& p, const CarryPose& carry) const {
  const Impl& m = *this;
  const auto& dets = m.perClass.at(p.key());  // (an empty plan: no detector, no catalogue objects)
  const core::ObjectClass& cls = m.catalogue.at(p.className);
  ObjectTrajectory traj;
  traj.className = p.className;
  traj.instanceId = p.instanceId;
  traj.classId = cls.classId;
  traj.isStatic = p.isStatic;
  int bestFrame = -1, firstFrame = -1;
  for (std::size_t i = 0; i < dets.size(); ++i)
    if (dets[i]) {
      if (firstFrame < 0) firstFrame = static_cast<int>(i);
      if (bestFrame < 0 || dets[i]->confidence > dets[static_cast<std::size_t>(bestFrame)]->confidence)
        bestFrame = static_cast<int>(i);
    }
  if (bestFrame < 0) return traj;  // never seen: empty trajectory
  const std::vector<std::optional<ObjectDetection>> rested = consolidatedRests(p, dets);
  // Reported in the class's object frame (its mesh's), not the model frame the detector fits in.
  const ObjectPoseFitter* classFitter = m.detector->fitterFor(p.key());
  const core::Pose3 X_model_mesh = classFitter ? classFitter->model().X_model_mesh : core::Pose3::Identity();
  const ObjectDetection* carried = &*rested[static_cast<std::size_t>(firstFrame)];
  std::size_t carriedFrom = static_cast<std::size_t>(firstFrame);
  for (std::size_t i = 0; i < dets.size(); ++i) {
    ObjectPoseSample s;
    s.frame = m.frameIndex[i];
    s.t_s = m.frameTime_s[i];
    if (p.isStatic) {
      const auto& best = *dets[static_cast<std::size_t>(bestFrame)];
      s.X_camera_object = carry(best.X_camera_object, static_cast<std::size_t>(bestFrame), i);
      s.detected = dets[i].has_value();
      s.confidence = best.confidence;
    } else {
      if (rested[i]) {
        carried = &*rested[i];
        carriedFrom = i;
      }
      s.X_camera_object = carry(carried->X_camera_object, carriedFrom, i);
      s.detected = dets[i].has_value();
      s.confidence = dets[i] ? dets[i]->confidence : 0.0;
    }
    s.X_camera_object = s.X_camera_object * X_model_mesh;
    traj.samples.push_back(s);
  }
  return traj;
}

PerceptionResult DemoPerceiver::finish() const {
  const Impl& m = *impl_;
  m.throwIfNothingToPerceive();
  PerceptionResult result = m.result;
  result.frames = static_cast<int>(m.frameIndex.size());
  result.handMethod = m.handUsed;
  if (m.firstSupport) result.X_camera_table = m.firstSupport->X_camera_plane();
  if (m.cameraMotion) {
    result.X_camera0_camera = m.cameraMotion->poses();
    result.cameraTravel_m = m.cameraMotion->maxTranslation_m();
    result.cameraTurn_rad = m.cameraMotion->maxRotation_rad();
  }
  result.cameraMoved = m.moving;
  // With a moving camera a pose is carried from one frame to another through the camera's motion.
  const bool carryThroughCamera = m.moving && result.X_camera0_camera.size() == m.frameIndex.size();
  const auto carry = [&](const core::Pose3& X_cameraFrom_object, std::size_t from, std::size_t to) {
    if (!carryThroughCamera || from == to) return X_cameraFrom_object;
    return core::Pose3(result.X_camera0_camera[to].inverse() * result.X_camera0_camera[from] * X_cameraFrom_object);
  };

  for (const auto& p : m.plan) result.objects.push_back(m.trajectoryOf(p, carry));
  if (m.discovery) {
    int freeId = 0;
    for (const auto& c : m.catalogue.classes()) freeId = std::max(freeId, c.classId + 1);
    ObjectDiscovery::Result found = m.discovery->finish(result.objects, freeId);
    result.observedClasses = found.classes;
    result.discoveryNotes = found.notes;
    for (auto& t : found.trajectories) result.objects.push_back(std::move(t));
  }
  return result;
}

core::ObjectCatalogue withObservedClasses(const core::ObjectCatalogue& catalogue,
                                          const std::vector<core::ObjectClass>& observed) {
  std::vector<core::ObjectClass> classes = catalogue.classes();
  for (const auto& c : observed) {
    if (catalogue.find(c.name) || catalogue.findById(c.classId))
      throw core::InvalidInputError("observed class '" + c.name + "' (id " + std::to_string(c.classId) +
                                    "): the knowledge base has a class of that name or id; give the observed object "
                                    "another name");
    classes.push_back(c);
  }
  return core::ObjectCatalogue(std::move(classes));
}

PerceptionResult inFirstCameraFrame(const PerceptionResult& result) {
  if (!result.cameraMoved) return result;
  if (result.X_camera0_camera.size() != result.hand.size())
    throw core::InvalidInputError("perception result: " + std::to_string(result.X_camera0_camera.size()) +
                                  " camera poses for " + std::to_string(result.hand.size()) +
                                  " frames; a moving camera needs one pose per frame");
  PerceptionResult out = result;
  core::PositionTrajectory hand(result.hand.frame());
  for (std::size_t i = 0; i < result.hand.size(); ++i) {
    core::PositionSample s = result.hand[i];
    if (s.valid) s.p_m = result.X_camera0_camera[i] * s.p_m;
    hand.append(s);
  }
  out.hand = hand;
  for (auto& o : out.objects)
    for (std::size_t i = 0; i < o.samples.size() && i < result.X_camera0_camera.size(); ++i)
      o.samples[i].X_camera_object = result.X_camera0_camera[i] * o.samples[i].X_camera_object;
  return out;
}

std::vector<PlanObject> withSceneInstances(const std::vector<PlanObject>& plan, const core::Scene& scene,
                                           const core::ObjectCatalogue& catalogue) {
  std::vector<PlanObject> out;
  for (const PlanObject& p : plan) {
    std::vector<const core::SceneObject*> instances;
    for (const auto& o : scene.objects)
      if (o.className == p.className) instances.push_back(&o);
    if (instances.size() < 2 || !p.instanceId.empty()) {
      out.push_back(p);
      continue;
    }
    const core::ObjectClass& cls = catalogue.at(p.className);
    for (const core::SceneObject* o : instances) out.push_back({p.className, p.isStatic, o->id, core::instanceRgb(*o, cls)});
  }
  return out;
}

PerceptionResult perceiveFrames(const std::vector<rawlog::RgbdFrame>& frames, const core::ObjectCatalogue& catalogue,
                                const PerceptionOptions& options, const std::function<void(int, int)>& progress) {
  if (frames.empty()) throw core::InvalidInputError("the demo has zero frames: nothing to perceive");
  DemoPerceiver perceiver(catalogue, options);
  // The preview pass only where a detector learns from it (the marker-free hand) or is chosen in it.
  if (perceiver.wantsPreview())
    for (const auto& f : frames) {
      if (perceiver.previewComplete()) break;
      perceiver.preview(f);
    }
  for (std::size_t i = 0; i < frames.size(); ++i) {
    perceiver.add(frames[i]);
    if (progress) progress(static_cast<int>(i), static_cast<int>(frames.size()));
  }
  return perceiver.finish();
}

void writeSegmentCsv(const PerceptionResult& result, const std::string& path) {
  {
    std::ostringstream out;
    out << "frame,hand_x,hand_y,hand_z";
    for (const auto& o : result.objects) {
      std::string n = o.key();
      std::replace(n.begin(), n.end(), ' ', '_');
      out << ',' << n << "_x," << n << "_y," << n << "_z," << n << "_rz";
    }
    out << '\n';
    char buf[64];
    for (std::size_t i = 0; i < result.hand.size(); ++i) {
      const auto& h = result.hand[i];
      out << h.frame;
      const Eigen::Vector3d p = h.valid ? h.p_m : Eigen::Vector3d::Zero();
      for (int k = 0; k < 3; ++k) {
        std::snprintf(buf, sizeof(buf), ",%.6f", p[k]);
        out << buf;
      }
      for (const auto& o : result.objects) {
        // Not detected in this frame (carried forward, in the hand, hidden,
        // never seen): exact zeros, as `srp segment` (motion::TrajectoryTable)
        // and the ProductPose rows' `detected` flag have it.
        const ObjectPoseSample* s = i < o.samples.size() ? &o.samples[i] : nullptr;
        if (!s || !s->detected) {
          out << ",0,0,0,0";
          continue;
        }
        const Eigen::Vector3d t = s->X_camera_object.translation();
        std::snprintf(buf, sizeof(buf), ",%.6f,%.6f,%.6f,%.6f", t.x(), t.y(), t.z(), cameraYaw(s->X_camera_object));
        out << buf;
      }
      out << '\n';
    }
    core::writeFileAtomically(path, out.str());
  }
}

}  // namespace srp::perception
