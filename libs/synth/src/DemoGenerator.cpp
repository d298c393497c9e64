#include "srp/synth/DemoGenerator.h"

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <chrono>
#include <ctime>
#include <optional>
#include <condition_variable>
#include <deque>
#include <exception>
#include <memory>
#include <mutex>
#include <thread>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <cstdio>

#include "srp/core/Error.h"
#include "srp/kb/KnowledgeBase.h"
#include "srp/kb/ShapeMeshes.h"
#include "srp/rawlog/RawlogWriter.h"
#include "srp/synth/HeadSway.h"
#include "srp/synth/SceneRenderer.h"

namespace srp::synth {
namespace {

using Clock = std::chrono::steady_clock;
double secondsSince(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

constexpr double kRawlogEpoch_s = 1.7e9;  // rawlog timestamps: a fixed epoch + t_s, reproducible
constexpr double kMaskDepthMargin_m = 0.004;
constexpr double kMaxTagViewAngle_rad = 60.0 * 3.14159265358979323846 / 180.0;

// A box (in its part frame, placed at X_camera_part) projected into the image:
// its convex hull as a filled mask over `bounds` (clipped to the image) and its
// depth range. nullopt when it is behind the camera or outside the image.
struct ProjectedBox {
  cv::Rect bounds;
  cv::Mat local;  // CV_8UC1 over `bounds`, 255 inside the hull
  double zMin = 1e9, zMax = -1e9;
};
std::optional<ProjectedBox> projectBox(const Eigen::AlignedBox3d& box, const srp::core::Pose3& X_camera_part,
                                       const srp::core::CameraIntrinsics& K) {
  ProjectedBox out;
  std::vector<cv::Point> pts;
  for (int c = 0; c < 8; ++c) {
    const Eigen::Vector3d p = X_camera_part * box.corner(static_cast<Eigen::AlignedBox3d::CornerType>(c));
    if (p.z() <= 0.05) return std::nullopt;  // behind or at the camera: not drawn
    out.zMin = std::min(out.zMin, p.z());
    out.zMax = std::max(out.zMax, p.z());
    const auto uv = K.project(p);
    pts.emplace_back(static_cast<int>(std::lround(uv->x())), static_cast<int>(std::lround(uv->y())));
  }
  std::vector<cv::Point> hull;
  cv::convexHull(pts, hull);
  out.bounds = cv::boundingRect(hull) & cv::Rect(0, 0, K.width_px, K.height_px);
  if (out.bounds.empty()) return std::nullopt;
  out.local = cv::Mat(out.bounds.size(), CV_8UC1, cv::Scalar(0));
  for (auto& p : hull) p -= out.bounds.tl();
  cv::fillConvexPoly(out.local, hull, cv::Scalar(255));
  return out;
}

// Whether some pixel of `mask` lies inside the box's projected hull.
bool boxCoversMaskPixels(const Eigen::AlignedBox3d& box, const srp::core::Pose3& X_camera_part,
                         const srp::core::CameraIntrinsics& K, const cv::Mat& mask) {
  const auto projected = projectBox(box, X_camera_part, K);
  if (!projected) return false;
  cv::Mat inside;
  cv::bitwise_and(mask(projected->bounds), projected->local, inside);
  return cv::countNonZero(inside) > 0;
}

// Marks the pixels where a box (in its part frame, placed at X_camera_part) is
// the visible surface: inside the projected hull and at a depth within the box's range.
void markBox(const Eigen::AlignedBox3d& box, const srp::core::Pose3& X_camera_part,
             const srp::core::CameraIntrinsics& K, const cv::Mat& depth, cv::Mat& mask) {
  const auto projected = projectBox(box, X_camera_part, K);
  if (!projected) return;
  const cv::Rect& bounds = projected->bounds;
  const cv::Mat& local = projected->local;
  const double zMin = projected->zMin, zMax = projected->zMax;
  for (int r = 0; r < bounds.height; ++r) {
    const unsigned char* l = local.ptr<unsigned char>(r);
    const float* d = depth.ptr<float>(bounds.y + r) + bounds.x;
    unsigned char* m = mask.ptr<unsigned char>(bounds.y + r) + bounds.x;
    for (int c = 0; c < bounds.width; ++c)
      if (l[c] && d[c] >= zMin - kMaskDepthMargin_m && d[c] <= zMax + kMaskDepthMargin_m) m[c] = 255;
  }
}

// Fraction of the tag plate's pixels (black square and white margin, one cell
// wide, less a rim of kTagRim_m for rasterisation at its edges) where the plate
// is the visible surface of the rendered (clean) depth: each pixel centre's ray
// is cut with the plate plane, and the pixel counts as visible when the
// rendered depth there is that point's within kTagSurfaceTol_m (the palm top
// lies 2 mm below the plate). Anything in front (a finger, a carried part) or showing
// through (depth fighting with the palm) hides it; so does the image border.
// 0 when the plate faces away from the camera.
constexpr double kTagSurfaceTol_m = 0.001, kTagRim_m = 0.001;
double tagVisibleFraction(const srp::core::Pose3& X_camera_tag, double plateHalf_m,
                          const srp::core::CameraIntrinsics& K, const cv::Mat& depth) {
  const Eigen::Vector3d n = X_camera_tag.linear().col(2), o = X_camera_tag.translation();
  if (n.dot(o) <= 0.0) return 0.0;  // tag z points into the tag: it must point away from the camera
  std::vector<cv::Point> pts;
  for (const auto& [x, y] : {std::pair{-1, -1}, {1, -1}, {1, 1}, {-1, 1}}) {
    const Eigen::Vector3d p = X_camera_tag * Eigen::Vector3d(x * plateHalf_m, y * plateHalf_m, 0.0);
    if (p.z() <= 0.05) return 0.0;
    const auto uv = K.project(p);
    pts.emplace_back(static_cast<int>(std::floor(uv->x())), static_cast<int>(std::floor(uv->y())));
  }
  const cv::Rect box = cv::boundingRect(pts) + cv::Size(2, 2);
  const srp::core::Pose3 X_tag_camera = X_camera_tag.inverse();
  int inside = 0, visible = 0;
  for (int v = box.y; v < box.y + box.height; ++v)
    for (int u = box.x; u < box.x + box.width; ++u) {
      const Eigen::Vector3d ray = K.backProject(u, v, 1.0);
      const double s = n.dot(o) / n.dot(ray);  // ray point on the plate plane
      if (s <= 0.0) continue;
      const Eigen::Vector3d p_tag = X_tag_camera * (s * ray);
      if (std::abs(p_tag.x()) > plateHalf_m || std::abs(p_tag.y()) > plateHalf_m) continue;
      ++inside;
      if (u < 0 || v < 0 || u >= depth.cols || v >= depth.rows) continue;
      const float d = depth.at<float>(v, u);
      if (std::abs(d - s * ray.z()) <= kTagSurfaceTol_m) ++visible;
    }
  return inside ? static_cast<double>(visible) / inside : 0.0;
}

double threadCpuTime_s() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}
double processCpuTime_s() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// Hands rendered frames from the render thread to the sensor thread. Bounded,
// so that a slow consumer holds the producer back instead of filling memory.
template <class T>
class FrameQueue {
 public:
  explicit FrameQueue(std::size_t capacity) : capacity_(capacity) {}
  /// Blocks while full; false when the consumer has stopped (it failed).
  bool push(T item) {
    std::unique_lock<std::mutex> lock(mutex_);
    notFull_.wait(lock, [this] { return items_.size() < capacity_ || stopped_; });
    if (stopped_) return false;
    items_.push_back(std::move(item));
    notEmpty_.notify_one();
    return true;
  }
  /// Blocks while empty; nullopt once the producer has finished and all is taken.
  std::optional<T> pop() {
    std::unique_lock<std::mutex> lock(mutex_);
    notEmpty_.wait(lock, [this] { return !items_.empty() || finished_; });
    if (items_.empty()) return std::nullopt;
    T item = std::move(items_.front());
    items_.pop_front();
    notFull_.notify_one();
    return item;
  }
  void finish() {
    std::lock_guard<std::mutex> lock(mutex_);
    finished_ = true;
    notEmpty_.notify_all();
  }
  void stop() {
    std::lock_guard<std::mutex> lock(mutex_);
    stopped_ = true;
    notFull_.notify_all();
  }

 private:
  std::size_t capacity_;
  std::mutex mutex_;
  std::condition_variable notEmpty_, notFull_;
  std::deque<T> items_;
  bool finished_ = false, stopped_ = false;
};

cv::Mat colourMapDepth(const cv::Mat& depth_m, double near_m, double far_m) {
  cv::Mat scaled;
  depth_m.convertTo(scaled, CV_8UC1, -255.0 / (far_m - near_m), 255.0 * far_m / (far_m - near_m));
  cv::Mat coloured;
  cv::applyColorMap(scaled, coloured, cv::COLORMAP_JET);
  coloured.setTo(cv::Scalar(0, 0, 0), depth_m <= 0.f);
  return coloured;
}

// `srp import`'s unregistered layout (RgbdImporter.h): colour camera, depth camera, extrinsic.
void writeTwoCameraFolderHeader(const std::string& folder, const srp::core::CameraIntrinsics& K,
                                const SynthDepthCamera& depthCamera, double depthUnit_m) {
  namespace fs = std::filesystem;
  fs::create_directories(folder);
  const auto write = [&](const std::string& name, const std::string& text) {
    std::ofstream out(fs::path(folder) / name);
    out << text;
    if (!out) throw srp::core::FileError((fs::path(folder) / name).string(), "cannot write the two-camera demo");
  };
  write("cam.json", nlohmann::json{{"px", K.fx_px}, {"py", K.fy_px}, {"u0", K.cx_px}, {"v0", K.cy_px}, {"w", K.width_px},
                                   {"h", K.height_px}, {"depthScale", depthUnit_m},
                                   {"model", "perspectiveProjWithoutDistortion"}}
                        .dump(2));
  write("depth_cam.json", nlohmann::json(depthCamera.intrinsics).dump(2));
  const Eigen::Matrix4d depth_M_color = depthCamera.X_colour_depth.inverse().matrix();
  std::ostringstream m;
  m.precision(17);
  for (int r = 0; r < 4; ++r) m << depth_M_color(r, 0) << " " << depth_M_color(r, 1) << " " << depth_M_color(r, 2) << " "
                                << depth_M_color(r, 3) << "\n";
  write("depth_M_color.txt", m.str());
}

void writeTwoCameraFolderFrame(const std::string& folder, int k, const cv::Mat& colour, const cv::Mat& depth_m,
                               double depthUnit_m) {
  char name[32];
  std::snprintf(name, sizeof name, "%04d.png", k);
  const std::filesystem::path dir(folder);
  cv::Mat depth16(depth_m.size(), CV_16UC1);
  for (int r = 0; r < depth_m.rows; ++r) {
    const float* d = depth_m.ptr<float>(r);
    std::uint16_t* o = depth16.ptr<std::uint16_t>(r);
    for (int c = 0; c < depth_m.cols; ++c) {
      const double steps = d[c] / depthUnit_m;
      o[c] = steps > 0.0 && steps <= 65535.0 ? static_cast<std::uint16_t>(std::lround(steps)) : 0;
    }
  }
  const std::vector<int> fast{cv::IMWRITE_PNG_COMPRESSION, 1};
  if (!cv::imwrite((dir / (std::string("color_") + name)).string(), colour, fast) ||
      !cv::imwrite((dir / (std::string("depth_") + name)).string(), depth16, fast))
    throw srp::core::FileError(folder, "cannot write frame " + std::to_string(k) + " of the two-camera demo");
}

// One renderer with the scene's bodies: optionally the table and floor, every
// scene object (its mesh, the timeline's colour), optionally the hand's parts.
struct Layer {
  std::unique_ptr<SceneRenderer> renderer;
  std::vector<int> objectBodies, handBodies;
};

Layer makeLayer(const core::CameraIntrinsics& intrinsics, const DemoTimeline& timeline,
                const std::vector<srp::kb::TriangleMesh>& objectMeshes, const HandModel& hand, bool withTable,
                bool withHand, const Eigen::Vector3d& lightRgb) {
  const srp::core::Scene& world = timeline.scene;
  Layer layer;
  layer.renderer = std::make_unique<SceneRenderer>(intrinsics);
  SceneRenderer& r = *layer.renderer;
  r.setLighting(world.lighting, lightRgb);
  r.setBackground({0.3, 0.3, 0.32});
  if (withTable) {
    const int table = r.addBody(
        "table",
        srp::kb::makeBoxMesh({-0.5 * world.tableSize_m.x(), -0.5 * world.tableSize_m.y(), -0.03},
                             {0.5 * world.tableSize_m.x(), 0.5 * world.tableSize_m.y(), 0.0}),
        world.tableRgb);
    r.setBodyPose(table, srp::core::Pose3::Identity());
    const int floor = r.addBody("floor", srp::kb::makeBoxMesh({-3, -3, -0.78}, {3, 3, -0.75}), {0.42, 0.4, 0.38});
    r.setBodyPose(floor, srp::core::Pose3::Identity());
  }
  for (std::size_t i = 0; i < world.objects.size(); ++i)
    layer.objectBodies.push_back(r.addBody(world.objects[i].id, objectMeshes[i], timeline.objectRgb.at(world.objects[i].id)));
  if (withHand)
    for (const auto& part : hand.parts()) layer.handBodies.push_back(r.addBody("hand:" + part.name, part.mesh_part, part.triangleRgb));
  return layer;
}

// The ground truth's header: scene, camera, hand tag, objects (initial and
// final poses) and the plan's events; the frames are appended as they are made.
DemoGroundTruth groundTruthHeader(const DemoTimeline& timeline, const srp::core::ObjectCatalogue& catalogue,
                                  const HandModel& hand, const nlohmann::json& plan, const SynthDemoOptions& options,
                                  const std::string& rawlogFile) {
  const srp::core::Scene& world = timeline.scene;
  DemoGroundTruth gt;
  gt.sceneName = world.name;
  gt.rawlogFile = rawlogFile;
  gt.seed = options.demo.seed;
  gt.fps = world.fps;
  gt.speedFactor = timeline.speedFactor;
  gt.instruction = plan.value("instruction", std::string());
  gt.intrinsics = world.intrinsics;
  gt.X_world_camera = world.X_world_camera;
  gt.X_world_base = world.X_world_base;
  gt.tagId = options.hand.tagId;
  gt.tagSize_m = options.hand.tagSize_m;
  gt.X_hand_tag = hand.X_hand_tag();
  gt.sensorRealism = options.sensor.enabled;
  for (std::size_t i = 0; i < world.objects.size(); ++i) {
    const auto& o = world.objects[i];
    GroundTruthObject g{o.id, o.className, catalogue.at(o.className).classId, o.X_world_object,
                        timeline.frames.back().X_world_objects[i]};
    gt.objects.push_back(g);
  }
  for (const auto& e : timeline.events)
    gt.events.push_back({e.objectId, e.step, e.graspFrame, e.releaseFrame, e.sourceId, e.targetId, e.referenceId,
                         e.X_hand_object});
  return gt;
}

// The contact sheet PNG: colour | depth of each chosen frame, two frames per row, labelled.
void writeContactSheet(const std::string& path, const std::vector<std::pair<int, srp::rawlog::RgbdFrame>>& sheet,
                       const DemoGroundTruth& gt) {
  const cv::Size tile(256, 192);
  const int perRow = 2, rows = (static_cast<int>(sheet.size()) + perRow - 1) / perRow;
  cv::Mat canvas(rows * tile.height, perRow * 2 * tile.width, CV_8UC3, cv::Scalar(255, 255, 255));
  for (std::size_t i = 0; i < sheet.size(); ++i) {
    const auto& [index, fr] = sheet[i];
    const int r = static_cast<int>(i) / perRow, c = static_cast<int>(i) % perRow;
    cv::Mat colour, depth;
    cv::resize(fr.colour_bgr8, colour, tile, 0, 0, cv::INTER_AREA);
    cv::resize(colourMapDepth(fr.depth_m, 0.55, 0.95), depth, tile, 0, 0, cv::INTER_NEAREST);
    colour.copyTo(canvas(cv::Rect(2 * c * tile.width, r * tile.height, tile.width, tile.height)));
    depth.copyTo(canvas(cv::Rect((2 * c + 1) * tile.width, r * tile.height, tile.width, tile.height)));
    const std::string label = "frame " + std::to_string(index) + "  t=" +
                              cv::format("%.1f", gt.frames[index].t_s) + " s  " + gt.frames[index].phase;
    cv::putText(canvas, label, {2 * c * tile.width + 6, r * tile.height + 18}, cv::FONT_HERSHEY_SIMPLEX, 0.5,
                cv::Scalar(255, 255, 255), 2);
    cv::putText(canvas, label, {2 * c * tile.width + 6, r * tile.height + 18}, cv::FONT_HERSHEY_SIMPLEX, 0.5,
                cv::Scalar(0, 0, 0), 1);
  }
  if (!cv::imwrite(path, canvas))
    throw srp::core::FileError(path, "cannot write the contact sheet PNG");
}

// The scene's object meshes (for the renderers), their bounds and which
// are parts (for the masks and the ground truth), in scene order.
struct SceneBodies {
  std::vector<srp::kb::TriangleMesh> meshes;
  std::vector<Eigen::AlignedBox3d> bounds;
  std::vector<bool> isPart;
};

SceneBodies loadSceneBodies(const srp::core::Scene& world, const srp::core::ObjectCatalogue& catalogue) {
  SceneBodies b;
  for (const auto& o : world.objects) {
    const auto& cls = catalogue.at(o.className);
    b.meshes.push_back(srp::kb::loadClassMesh(cls));
    b.bounds.push_back(b.meshes.back().bounds());
    b.isPart.push_back(cls.kind == srp::core::ObjectKind::Part);
  }
  return b;
}

// The renderers of one demo. Two with the same bodies: `background` holds the
// table, floor and resting objects and is re-rendered only when that set
// changes; `moving` draws the hand and the carried object on an empty
// background every frame; a per-pixel depth test composes them. Software
// rendering costs per covered pixel, so this skips re-shading the table.
// Without layering, `background` draws everything every frame. A two-camera
// sensor's depth camera (`depthLayer`) renders the whole scene itself.
struct Renderers {
  bool layered = true;
  Layer background, moving, depthLayer;
  srp::core::Pose3 X_colour_depth = srp::core::Pose3::Identity();  ///< the depth camera in the colour camera
  /// The colour camera in every timeline frame (its nominal pose, or swayed about it: HeadSway).
  std::vector<srp::core::Pose3> X_world_camera;
  srp::core::Pose3 X_world_depth(int k) const { return X_world_camera[static_cast<std::size_t>(k)] * X_colour_depth; }
  std::vector<int> backgroundState;  // per object: 0 hidden, 1 shown; with the poses below
  std::vector<srp::core::Pose3> backgroundPoses;
  srp::rawlog::RgbdFrame backgroundFrame;
};

Renderers setUpRenderers(const DemoTimeline& timeline, const SceneBodies& bodies, const HandModel& hand,
                         const SynthDemoOptions& options) {
  const srp::core::Scene& world = timeline.scene;
  Renderers r;
  // A swaying camera sees the resting bodies move every frame: nothing to cache.
  r.layered = options.layeredRendering && !options.headSway.enabled;
  r.background = makeLayer(world.intrinsics, timeline, bodies.meshes, hand, true, !r.layered, options.lightRgb);
  if (r.layered) r.moving = makeLayer(world.intrinsics, timeline, bodies.meshes, hand, false, true, options.lightRgb);
  if (options.depthCamera) {
    options.depthCamera->intrinsics.validate("synth-demo depth camera");
    r.depthLayer = makeLayer(options.depthCamera->intrinsics, timeline, bodies.meshes, hand, true, true, options.lightRgb);
  }
  if (options.depthCamera) r.X_colour_depth = options.depthCamera->X_colour_depth;
  const HeadSway sway(options.headSway, options.demo.seed);
  for (const auto& f : timeline.frames) r.X_world_camera.push_back(world.X_world_camera * sway.X_nominal_camera(f.t_s));
  return r;
}

// Contact-sheet frames: evenly spread, first and last included; none without a sheet.
std::vector<int> contactSheetFrames(const SynthDemoOptions& options, int frameCount) {
  std::vector<int> frames;
  if (options.contactSheetPath.empty()) return frames;
  const int n = std::max(2, options.contactSheetFrames);
  for (int i = 0; i < n; ++i) frames.push_back(static_cast<int>(std::lround(i * (frameCount - 1.0) / (n - 1))));
  return frames;
}

// Frame k of the colour camera: everything in one pass, or (layered) the
// cached background composed by depth with the moving bodies.
srp::rawlog::RgbdFrame renderColourFrame(Renderers& r, const DemoTimeline& timeline, int k,
                                         const std::vector<srp::core::Pose3>& partPoses) {
  const srp::core::Scene& world = timeline.scene;
  const auto& K = world.intrinsics;
  const FrameState& f = timeline.frames[k];
  const FrameState& prev = timeline.frames[std::max(k - 1, 0)];
  const srp::core::Pose3& X_world_camera = r.X_world_camera[static_cast<std::size_t>(k)];
  srp::rawlog::RgbdFrame frame;
  if (!r.layered) {
    for (std::size_t i = 0; i < world.objects.size(); ++i)
      r.background.renderer->setBodyPose(r.background.objectBodies[i], f.X_world_objects[i]);
    for (std::size_t i = 0; i < r.background.handBodies.size(); ++i)
      r.background.renderer->setBodyPose(r.background.handBodies[i], f.X_world_hand * partPoses[i]);
    return r.background.renderer->render(X_world_camera);
  }
  // Objects in motion (carried, or moved since the last frame) go to the moving layer.
  std::vector<int> state(world.objects.size());
  bool anyMoving = false;
  for (std::size_t i = 0; i < world.objects.size(); ++i) {
    const bool isMoving = static_cast<int>(i) == f.carriedObject ||
                          !f.X_world_objects[i].matrix().isApprox(prev.X_world_objects[i].matrix(), 0.0);
    state[i] = isMoving ? 0 : 1;
    anyMoving = anyMoving || isMoving;
  }
  bool backgroundChanged = state != r.backgroundState;
  for (std::size_t i = 0; i < world.objects.size() && !backgroundChanged; ++i)
    backgroundChanged = state[i] && !f.X_world_objects[i].matrix().isApprox(r.backgroundPoses[i].matrix(), 0.0);
  if (backgroundChanged) {
    for (std::size_t i = 0; i < world.objects.size(); ++i) {
      r.background.renderer->setBodyVisible(r.background.objectBodies[i], state[i] == 1);
      r.background.renderer->setBodyPose(r.background.objectBodies[i], f.X_world_objects[i]);
    }
    r.backgroundFrame = r.background.renderer->render(X_world_camera);
    r.backgroundState = state;
    r.backgroundPoses = f.X_world_objects;
  }
  frame.intrinsics = K;
  frame.colour_bgr8 = r.backgroundFrame.colour_bgr8.clone();
  frame.depth_m = r.backgroundFrame.depth_m.clone();
  // The hand is out of view while idle (the timeline guarantees it): nothing moves then.
  if (f.phase == "idle" && !anyMoving) return frame;
  for (std::size_t i = 0; i < world.objects.size(); ++i) {
    r.moving.renderer->setBodyVisible(r.moving.objectBodies[i], state[i] == 0);
    r.moving.renderer->setBodyPose(r.moving.objectBodies[i], f.X_world_objects[i]);
  }
  for (std::size_t i = 0; i < r.moving.handBodies.size(); ++i)
    r.moving.renderer->setBodyPose(r.moving.handBodies[i], f.X_world_hand * partPoses[i]);
  const auto front = r.moving.renderer->render(X_world_camera);
  for (int row = 0; row < K.height_px; ++row) {
    const float* dFront = front.depth_m.ptr<float>(row);
    const cv::Vec3b* cFront = front.colour_bgr8.ptr<cv::Vec3b>(row);
    float* d = frame.depth_m.ptr<float>(row);
    cv::Vec3b* c = frame.colour_bgr8.ptr<cv::Vec3b>(row);
    for (int col = 0; col < K.width_px; ++col)
      if (dFront[col] > 0.f && (d[col] <= 0.f || dFront[col] < d[col])) {
        d[col] = dFront[col];
        c[col] = cFront[col];
      }
  }
  return frame;
}

// Frame k of the two-camera sensor's depth camera (the whole scene).
srp::rawlog::RgbdFrame renderDepthCameraFrame(Renderers& r, const DemoTimeline& timeline, int k,
                                              const std::vector<srp::core::Pose3>& partPoses) {
  const FrameState& f = timeline.frames[k];
  for (std::size_t i = 0; i < timeline.scene.objects.size(); ++i)
    r.depthLayer.renderer->setBodyPose(r.depthLayer.objectBodies[i], f.X_world_objects[i]);
  for (std::size_t i = 0; i < r.depthLayer.handBodies.size(); ++i)
    r.depthLayer.renderer->setBodyPose(r.depthLayer.handBodies[i], f.X_world_hand * partPoses[i]);
  return r.depthLayer.renderer->render(r.X_world_depth(k));
}

// Hand, resting-part and moving-part masks of one camera's rendered depth in
// frame k, and the fastest part's speed [m/s].
struct FrameMasks {
  cv::Mat hand, part, moving;
  double movingSpeed = 0.0;
};

FrameMasks frameMasks(const DemoTimeline& timeline, const SceneBodies& bodies, const HandModel& hand, int k,
                      const std::vector<srp::core::Pose3>& partPoses, const srp::core::CameraIntrinsics& Kcam,
                      const srp::core::Pose3& X_cam_world, const cv::Mat& depth) {
  const srp::core::Scene& world = timeline.scene;
  const FrameState& f = timeline.frames[k];
  const FrameState& prev = timeline.frames[std::max(k - 1, 0)];
  const double dt = 1.0 / world.fps;
  FrameMasks m;
  m.hand = cv::Mat(Kcam.height_px, Kcam.width_px, CV_8UC1, cv::Scalar(0));
  m.part = m.hand.clone();
  m.moving = m.hand.clone();
  for (std::size_t i = 0; i < hand.parts().size(); ++i)
    markBox(hand.parts()[i].bounds_part, X_cam_world * f.X_world_hand * partPoses[i], Kcam, depth, m.hand);
  for (std::size_t i = 0; i < world.objects.size(); ++i) {
    if (!bodies.isPart[i]) continue;
    const double speed = (f.X_world_objects[i].translation() - prev.X_world_objects[i].translation()).norm() / dt;
    markBox(bodies.bounds[i], X_cam_world * f.X_world_objects[i], Kcam, depth, speed > 0.0 ? m.moving : m.part);
    m.movingSpeed = std::max(m.movingSpeed, speed);
  }
  m.part.setTo(0, m.hand);
  m.moving.setTo(0, m.hand);
  return m;
}

// The ground truth of frame k: phase, hand and tag (corners, visibility:
// `tagVisible` from the clean depth), objects, hand occlusions, and the
// share of valid depth on the hand and the parts in the degraded `frame`.
// `index`, `t0_s`: the frame's index in the recording and the time of the recording's first frame
// (a recording of some of the timeline's frames); `X_world_camera`: the camera in frame k, recorded in
// the ground truth when `cameraMoves`.
GroundTruthFrame groundTruthFrame(const DemoTimeline& timeline, const SceneBodies& bodies, const HandModel& hand,
                                  int k, int index, double t0_s, const srp::core::Pose3& X_world_camera,
                                  bool cameraMoves, const srp::core::Pose3& X_camera_tag, double tagVisible,
                                  const FrameMasks& masks, const srp::rawlog::RgbdFrame& frame) {
  const srp::core::Scene& world = timeline.scene;
  const auto& K = world.intrinsics;
  const FrameState& f = timeline.frames[k];
  const srp::core::Pose3 X_camera_world = X_world_camera.inverse();
  GroundTruthFrame g;
  g.index = index;
  g.t_s = f.t_s - t0_s;
  if (cameraMoves) g.X_world_camera = X_world_camera;
  g.phase = f.phase;
  g.step = f.step;
  g.grip = f.grip;
  g.handPixels = cv::countNonZero(masks.hand);
  g.handInView = g.handPixels > 0;
  g.X_world_hand = f.X_world_hand;
  g.p_camera_palm_m = X_camera_world * f.X_world_hand.translation();
  g.X_camera_tag = X_camera_tag;
  const auto corners = hand.tagCorners_tag();
  for (int c = 0; c < 4; ++c) {
    const auto uv = K.project(g.X_camera_tag * corners[c]);
    g.tagCorners_px[c] = uv ? *uv : Eigen::Vector2d(-1, -1);
  }
  // "In view" = a detector could read it: the whole plate (black square and
  // white margin) is in the image, seen at most kMaxTagViewAngle_rad off its
  // normal, and nothing hides any of its pixels.
  const double cosView = X_camera_tag.linear().col(2).dot(X_camera_tag.translation().normalized());
  g.tagVisibleFraction = tagVisible;
  g.tagInView = tagVisible >= 1.0 && cosView >= std::cos(kMaxTagViewAngle_rad);
  if (f.carriedObject >= 0) g.carriedObject = world.objects[f.carriedObject].id;
  for (std::size_t i = 0; i < world.objects.size(); ++i) g.X_world_objects[world.objects[i].id] = f.X_world_objects[i];
  g.handOccludedObjects.emplace();
  if (g.handInView)
    for (std::size_t i = 0; i < world.objects.size(); ++i)
      if (boxCoversMaskPixels(bodies.bounds[i], X_camera_world * f.X_world_objects[i], K, masks.hand))
        g.handOccludedObjects->insert(world.objects[i].id);
  auto validFraction = [&](const cv::Mat& mask) -> std::optional<double> {
    const int n = cv::countNonZero(mask);
    if (n == 0) return std::nullopt;
    cv::Mat valid = (frame.depth_m > 0.f) & mask;
    return static_cast<double>(cv::countNonZero(valid)) / n;
  };
  g.handValidDepthFraction = validFraction(masks.hand);
  g.objectsValidDepthFraction = validFraction(masks.part | masks.moving);
  return g;
}

/// What the render thread hands the sensor thread.
struct Rendered {
  int k;      ///< timeline frame
  int index;  ///< frame of the recording
  srp::rawlog::RgbdFrame frame;
  std::vector<srp::core::Pose3> partPoses;
  srp::rawlog::RgbdFrame depthCameraFrame;  // two-camera sensor only
};

/// The sensor stage of the frame pipeline (its own thread): per rendered frame the masks, ground truth
/// and sensor realism, then the frame to the rawlog writer (or the two-camera folder).
struct SensorStage {
  const DemoTimeline& timeline;
  const SceneBodies& bodies;
  const HandModel& hand;
  const SynthDemoOptions& options;
  const Renderers& renderers;
  const std::vector<int>& sheetFrames;
  srp::rawlog::RawlogWriter* writer;  ///< null: the two-camera folder
  const std::string& folder;
  double depthUnit_m;
  double t0_s;  ///< the timeline time of the recording's first frame
  DemoGroundTruth& gt;
  std::vector<std::pair<int, srp::rawlog::RgbdFrame>>& sheet;
  SynthDemoResult& result;
  SensorModel sensor;
  SensorModel depthSensor;
  double handValidSum = 0.0, objectValidSum = 0.0;
  int handValidFrames = 0, objectValidFrames = 0;
  cv::Mat previousColour{};  // the clean colour of the frame before (motion blur)

  void process(Rendered& item) {
    const auto& K = timeline.scene.intrinsics;
    const int k = item.k;
    const srp::core::Pose3& X_world_camera = renderers.X_world_camera[static_cast<std::size_t>(k)];
    const srp::core::Pose3 X_camera_world = X_world_camera.inverse();
    const double dt = 1.0 / timeline.scene.fps;
    const FrameState& f = timeline.frames[k];
    const FrameState& prev = timeline.frames[std::max(k - 1, 0)];
    srp::rawlog::RgbdFrame& frame = item.frame;
    const double cpu0 = threadCpuTime_s();
    auto t0 = Clock::now();
    frame.index = item.index;
    frame.t_s = kRawlogEpoch_s + (f.t_s - t0_s);
    const FrameMasks masks = frameMasks(timeline, bodies, hand, k, item.partPoses, K, X_camera_world, frame.depth_m);
    // Tag visibility from the clean rendered depth (before the sensor model punches holes).
    const srp::core::Pose3 X_camera_tag = X_camera_world * f.X_world_hand * hand.X_hand_tag();
    const double tagVisible = tagVisibleFraction(X_camera_tag, hand.tagPlateHalfSize_m() - kTagRim_m, K, frame.depth_m);
    const double handSpeed = (f.X_world_hand.translation() - prev.X_world_hand.translation()).norm() / dt;
    const cv::Mat cleanColour = options.sensor.motionBlur ? frame.colour_bgr8.clone() : cv::Mat();
    sensor.apply(frame, masks.hand, handSpeed, masks.part, masks.moving, masks.movingSpeed, previousColour);
    previousColour = cleanColour;
    if (options.depthCamera) {  // the depth camera's own image, degraded the same way
      srp::rawlog::RgbdFrame& d = item.depthCameraFrame;
      const FrameMasks dm = frameMasks(timeline, bodies, hand, k, item.partPoses, options.depthCamera->intrinsics,
                                       renderers.X_world_depth(k).inverse(), d.depth_m);
      depthSensor.apply(d, dm.hand, handSpeed, dm.part, dm.moving, dm.movingSpeed, cv::Mat());
    }

    GroundTruthFrame g = groundTruthFrame(timeline, bodies, hand, k, item.index, t0_s, X_world_camera,
                                          options.headSway.enabled, X_camera_tag, tagVisible, masks, frame);
    if (g.handValidDepthFraction && g.handPixels > 200) {
      handValidSum += *g.handValidDepthFraction;
      ++handValidFrames;
    }
    if (g.objectsValidDepthFraction) {
      objectValidSum += *g.objectsValidDepthFraction;
      ++objectValidFrames;
    }
    gt.frames.push_back(std::move(g));
    result.sensorTime_s += secondsSince(t0);
    result.sensorCpuTime_s += threadCpuTime_s() - cpu0;

    if (std::find(sheetFrames.begin(), sheetFrames.end(), item.index) != sheetFrames.end())
      sheet.emplace_back(item.index, frame);
    t0 = Clock::now();
    if (writer) writer->write(std::move(frame));
    else writeTwoCameraFolderFrame(folder, item.index, frame.colour_bgr8, item.depthCameraFrame.depth_m, depthUnit_m);
    result.writeTime_s += secondsSince(t0);
  }
};

/// The render stage (this thread: the EGL context lives here): the timeline frames `recorded` rendered
/// and handed to the sensor stage, until it stops taking them (it failed).
void renderFrames(Renderers& renderers, const DemoTimeline& timeline, const HandModel& hand, bool depthCamera,
                  const std::vector<int>& recorded, FrameQueue<Rendered>& rendered, SynthDemoResult& result,
                  const std::function<void(int, int)>& progress) {
  const int frameCount = static_cast<int>(recorded.size());
  for (int n = 0; n < frameCount; ++n) {
    const int k = recorded[static_cast<std::size_t>(n)];
    auto t0 = Clock::now();
    auto partPoses = hand.partPoses(timeline.frames[k].grip);
    srp::rawlog::RgbdFrame frame = renderColourFrame(renderers, timeline, k, partPoses);
    srp::rawlog::RgbdFrame depthCameraFrame;
    if (depthCamera) depthCameraFrame = renderDepthCameraFrame(renderers, timeline, k, partPoses);
    result.renderTime_s += secondsSince(t0);
    if (!rendered.push({k, n, std::move(frame), std::move(partPoses), std::move(depthCameraFrame)}))
      break;  // the sensor thread failed
    if (progress) progress(n, frameCount);
  }
}

/// The rawlog writer at `rawlogPath`, or (two-camera sensor) no writer and the folder's header written.
std::unique_ptr<srp::rawlog::RawlogWriter> openOutput(const SynthDemoOptions& options, const std::string& rawlogPath,
                                                      const std::string& folder, const srp::core::CameraIntrinsics& K,
                                                      double depthUnit_m) {
  if (options.depthCamera) {
    writeTwoCameraFolderHeader(folder, K, *options.depthCamera, depthUnit_m);
    return nullptr;
  }
  const int encoderThreads = options.rawlogEncoderThreads >= 0
                                 ? options.rawlogEncoderThreads
                                 : std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  return std::make_unique<srp::rawlog::RawlogWriter>(rawlogPath, depthUnit_m, options.rawlogCompressionLevel,
                                                     encoderThreads);
}

/// The events' grasp and release frames as frames of a recording of the timeline frames `recorded`
/// (increasing): the first recorded frame at or after the grasp, the last at or before the release.
void remapEvents(DemoGroundTruth& gt, const std::vector<int>& recorded) {
  const int last = static_cast<int>(recorded.size()) - 1;
  for (auto& e : gt.events) {
    e.graspFrame = std::min(last, static_cast<int>(std::lower_bound(recorded.begin(), recorded.end(), e.graspFrame) -
                                                   recorded.begin()));
    e.releaseFrame = std::max(0, static_cast<int>(std::upper_bound(recorded.begin(), recorded.end(), e.releaseFrame) -
                                                  recorded.begin()) - 1);
  }
}

}  // namespace

std::string groundTruthPathFor(const std::string& rawlogPath) {
  std::filesystem::path p(rawlogPath);
  p.replace_extension(".gt.json");
  return p.string();
}

srp::core::CameraIntrinsics scaleIntrinsics(const srp::core::CameraIntrinsics& K, int width_px, int height_px) {
  if (width_px <= 0 || height_px <= 0 || (width_px == K.width_px && height_px == K.height_px)) return K;
  const double sx = static_cast<double>(width_px) / K.width_px, sy = static_cast<double>(height_px) / K.height_px;
  srp::core::CameraIntrinsics out = K;
  out.fx_px = K.fx_px * sx;
  out.fy_px = K.fy_px * sy;
  out.cx_px = (K.cx_px + 0.5) * sx - 0.5;  // pixel centres at integers
  out.cy_px = (K.cy_px + 0.5) * sy - 0.5;
  out.width_px = width_px;
  out.height_px = height_px;
  return out;
}

SynthDemoResult generateSyntheticDemo(const srp::core::Scene& sceneIn, const srp::core::ObjectCatalogue& catalogue,
                                      const nlohmann::json& plan, const SynthDemoOptions& options,
                                      const std::string& rawlogPath, const std::function<void(int, int)>& progress) {
  const auto tStart = Clock::now();
  sceneIn.validate(catalogue);
  srp::core::Scene scene = sceneIn;
  scene.intrinsics = scaleIntrinsics(sceneIn.intrinsics, options.width_px, options.height_px);
  const HandModel hand(options.hand);
  const auto steps = groundPlan(plan, scene, catalogue);
  const DemoTimeline timeline = planDemonstration(scene, catalogue, steps, hand, options.demo);
  const srp::core::Scene& world = timeline.scene;
  const auto& K = world.intrinsics;

  // ---- Renderer set-up ----------------------------------------------------------
  const SceneBodies bodies = loadSceneBodies(world, catalogue);
  Renderers renderers = setUpRenderers(timeline, bodies, hand, options);
  const std::optional<SynthDepthCamera>& depthCamera = options.depthCamera;
  std::filesystem::path folderPath = std::filesystem::path(rawlogPath).lexically_normal();
  if (!folderPath.has_filename()) folderPath = folderPath.parent_path();  // "demo/" -> "demo"
  const std::string folder = depthCamera ? folderPath.string() : std::string();

  // ---- Ground truth header -----------------------------------------------------
  DemoGroundTruth gt = groundTruthHeader(timeline, catalogue, hand, plan, options,
                                         (options.depthCamera ? folderPath : std::filesystem::path(rawlogPath)).filename().string());

  // The timeline frames recorded: all, or (carryOnly) those with a part in the hand; at most maxFrames.
  std::vector<int> recorded;
  for (int k = 0; k < static_cast<int>(timeline.frames.size()); ++k)
    if (!options.carryOnly || timeline.frames[static_cast<std::size_t>(k)].carriedObject >= 0) recorded.push_back(k);
  if (recorded.empty())
    throw srp::core::InvalidInputError("synth-demo: the plan's demonstration carries no part, so keeping only the "
                                       "frames with a part in the hand (carryOnly) leaves none; give a plan that "
                                       "moves a part");
  if (options.maxFrames >= 0 && options.maxFrames < static_cast<int>(recorded.size())) recorded.resize(options.maxFrames);
  const int frameCount = static_cast<int>(recorded.size());
  const double t0_s = options.carryOnly ? timeline.frames[static_cast<std::size_t>(recorded.front())].t_s : 0.0;
  if (options.carryOnly) remapEvents(gt, recorded);
  const std::vector<int> sheetFrames = contactSheetFrames(options, frameCount);
  std::vector<std::pair<int, srp::rawlog::RgbdFrame>> sheet;

  // ---- Frames -------------------------------------------------------------------
  // Two stages on two threads: this thread renders (the EGL context lives here),
  // the sensor thread computes masks, ground truth and sensor realism and hands
  // the frame to the rawlog writer, whose own threads compress and append.
  SynthDemoResult result;
  result.rawlogPath = rawlogPath;
  // With realism on, depth is already quantised to depthStep_m: storing it finer adds only size.
  const double depthUnit_m = options.sensor.enabled ? std::max(options.rawlogDepthUnit_m, options.sensor.depthStep_m)
                                                    : options.rawlogDepthUnit_m;
  const std::unique_ptr<srp::rawlog::RawlogWriter> writer = openOutput(options, rawlogPath, folder, K, depthUnit_m);
  const double cpuLoopStart_s = processCpuTime_s();
  SensorStage stage{timeline, bodies, hand, options, renderers, sheetFrames, writer.get(), folder, depthUnit_m, t0_s, gt, sheet,
                    result, SensorModel(options.sensor, options.demo.seed), SensorModel(options.sensor, options.demo.seed + 1)};
  FrameQueue<Rendered> rendered(3);
  std::exception_ptr sensorError;
  std::thread sensorThread([&] {
    try {
      while (auto item = rendered.pop()) stage.process(*item);
    } catch (...) {
      sensorError = std::current_exception();
      rendered.stop();
    }
  });

  try {
    renderFrames(renderers, timeline, hand, depthCamera.has_value(), recorded, rendered, result, progress);
  } catch (...) {
    rendered.finish();
    sensorThread.join();
    throw;
  }
  rendered.finish();
  sensorThread.join();
  if (sensorError) std::rethrow_exception(sensorError);
  const auto tClose = Clock::now();
  if (writer) {
    writer->close();
    result.writeCpuTime_s = writer->encodeCpuTime_s();
    result.rawlogBytes = writer->bytesWritten();
  }
  result.writeTime_s += secondsSince(tClose);
  result.processCpuTime_s = processCpuTime_s() - cpuLoopStart_s;
  // The rest of the loop's CPU: the render thread and llvmpipe's rasteriser threads.
  result.renderCpuTime_s = std::max(0.0, result.processCpuTime_s - result.sensorCpuTime_s - result.writeCpuTime_s);
  result.groundTruthPath = groundTruthPathFor(depthCamera ? folder : rawlogPath);
  gt.save(result.groundTruthPath);
  result.frameCount = frameCount;
  result.duration_s = frameCount / world.fps;
  result.meanHandValidDepth = stage.handValidFrames ? stage.handValidSum / stage.handValidFrames : -1.0;
  result.meanObjectValidDepth = stage.objectValidFrames ? stage.objectValidSum / stage.objectValidFrames : -1.0;

  // ---- Contact sheet: colour | depth per frame, two frames per row ----------------
  if (!options.contactSheetPath.empty() && !sheet.empty()) {
    writeContactSheet(options.contactSheetPath, sheet, gt);
    result.contactSheetPath = options.contactSheetPath;
  }
  result.totalTime_s = secondsSince(tStart);
  return result;
}

}  // namespace srp::synth
