#include "srp/synth/DemoGenerator.h"

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <chrono>
#include <filesystem>

#include "srp/core/Error.h"
#include "srp/kb/KnowledgeBase.h"
#include "srp/kb/ShapeMeshes.h"
#include "srp/rawlog/RawlogWriter.h"
#include "srp/synth/SceneRenderer.h"

namespace srp::synth {
namespace {

using Clock = std::chrono::steady_clock;
double secondsSince(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

constexpr double kRawlogEpoch_s = 1.7e9;  // rawlog timestamps: a fixed epoch + t_s, reproducible
constexpr double kMaskDepthMargin_m = 0.004;

// Marks the pixels where a box (in its part frame, placed at X_camera_part) is
// the visible surface: inside the projected hull and at a depth within the box's range.
void markBox(const Eigen::AlignedBox3d& box, const srp::core::Pose3& X_camera_part,
             const srp::core::CameraIntrinsics& K, const cv::Mat& depth, cv::Mat& mask) {
  std::vector<cv::Point> pts;
  double zMin = 1e9, zMax = -1e9;
  for (int c = 0; c < 8; ++c) {
    const Eigen::Vector3d p = X_camera_part * box.corner(static_cast<Eigen::AlignedBox3d::CornerType>(c));
    if (p.z() <= 0.05) return;  // behind or at the camera: not drawn
    zMin = std::min(zMin, p.z());
    zMax = std::max(zMax, p.z());
    const auto uv = K.project(p);
    pts.emplace_back(static_cast<int>(std::lround(uv->x())), static_cast<int>(std::lround(uv->y())));
  }
  std::vector<cv::Point> hull;
  cv::convexHull(pts, hull);
  const cv::Rect bounds = cv::boundingRect(hull) & cv::Rect(0, 0, depth.cols, depth.rows);
  if (bounds.empty()) return;
  cv::Mat local(bounds.size(), CV_8UC1, cv::Scalar(0));
  for (auto& p : hull) p -= bounds.tl();
  cv::fillConvexPoly(local, hull, cv::Scalar(255));
  for (int r = 0; r < bounds.height; ++r) {
    const unsigned char* l = local.ptr<unsigned char>(r);
    const float* d = depth.ptr<float>(bounds.y + r) + bounds.x;
    unsigned char* m = mask.ptr<unsigned char>(bounds.y + r) + bounds.x;
    for (int c = 0; c < bounds.width; ++c)
      if (l[c] && d[c] >= zMin - kMaskDepthMargin_m && d[c] <= zMax + kMaskDepthMargin_m) m[c] = 255;
  }
}

cv::Mat colourMapDepth(const cv::Mat& depth_m, double near_m, double far_m) {
  cv::Mat scaled;
  depth_m.convertTo(scaled, CV_8UC1, -255.0 / (far_m - near_m), 255.0 * far_m / (far_m - near_m));
  cv::Mat coloured;
  cv::applyColorMap(scaled, coloured, cv::COLORMAP_JET);
  coloured.setTo(cv::Scalar(0, 0, 0), depth_m <= 0.f);
  return coloured;
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
  SceneRenderer renderer(K);
  renderer.setLighting(world.lighting);
  renderer.setBackground({0.3, 0.3, 0.32});
  const int table = renderer.addBody(
      "table",
      srp::kb::makeBoxMesh({-0.5 * world.tableSize_m.x(), -0.5 * world.tableSize_m.y(), -0.03},
                           {0.5 * world.tableSize_m.x(), 0.5 * world.tableSize_m.y(), 0.0}),
      world.tableRgb);
  renderer.setBodyPose(table, srp::core::Pose3::Identity());
  const int floor = renderer.addBody("floor", srp::kb::makeBoxMesh({-3, -3, -0.78}, {3, 3, -0.75}), {0.42, 0.4, 0.38});
  renderer.setBodyPose(floor, srp::core::Pose3::Identity());
  std::vector<int> objectBodies;
  std::vector<Eigen::AlignedBox3d> objectBounds;
  std::vector<bool> isPart;
  for (const auto& o : world.objects) {
    const auto& cls = catalogue.at(o.className);
    const auto mesh = srp::kb::loadClassMesh(cls);
    objectBodies.push_back(renderer.addBody(o.id, mesh, timeline.objectRgb.at(o.id)));
    objectBounds.push_back(mesh.bounds());
    isPart.push_back(cls.kind == srp::core::ObjectKind::Part);
  }
  std::vector<int> handBodies;
  for (const auto& part : hand.parts()) handBodies.push_back(renderer.addBody("hand:" + part.name, part.mesh_part, part.triangleRgb));

  // ---- Ground truth header -----------------------------------------------------
  DemoGroundTruth gt;
  gt.sceneName = world.name;
  gt.rawlogFile = std::filesystem::path(rawlogPath).filename().string();
  gt.seed = options.demo.seed;
  gt.fps = world.fps;
  gt.speedFactor = timeline.speedFactor;
  gt.instruction = plan.value("instruction", std::string());
  gt.intrinsics = K;
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

  // Contact-sheet frames: evenly spread, first and last included.
  const int frameCount = options.maxFrames >= 0 ? std::min<int>(options.maxFrames, static_cast<int>(timeline.frames.size()))
                                                : static_cast<int>(timeline.frames.size());
  std::vector<int> sheetFrames;
  if (!options.contactSheetPath.empty()) {
    const int n = std::max(2, options.contactSheetFrames);
    for (int i = 0; i < n; ++i) sheetFrames.push_back(static_cast<int>(std::lround(i * (frameCount - 1.0) / (n - 1))));
  }
  std::vector<std::pair<int, srp::rawlog::RgbdFrame>> sheet;

  // ---- Frames -------------------------------------------------------------------
  SynthDemoResult result;
  result.rawlogPath = rawlogPath;
  // With realism on, depth is already quantised to depthStep_m: storing it finer adds only size.
  const double depthUnit_m = options.sensor.enabled ? std::max(options.rawlogDepthUnit_m, options.sensor.depthStep_m)
                                                    : options.rawlogDepthUnit_m;
  srp::rawlog::RawlogWriter writer(rawlogPath, depthUnit_m);
  SensorModel sensor(options.sensor, options.demo.seed);
  const srp::core::Pose3 X_camera_world = world.X_world_camera.inverse();
  cv::Mat previousColour;
  double handValidSum = 0.0, objectValidSum = 0.0;
  int handValidFrames = 0, objectValidFrames = 0;
  const double dt = 1.0 / world.fps;
  for (int k = 0; k < frameCount; ++k) {
    const FrameState& f = timeline.frames[k];
    const FrameState& prev = timeline.frames[std::max(k - 1, 0)];
    auto t0 = Clock::now();
    for (std::size_t i = 0; i < objectBodies.size(); ++i) renderer.setBodyPose(objectBodies[i], f.X_world_objects[i]);
    const auto partPoses = hand.partPoses(f.grip);
    for (std::size_t i = 0; i < handBodies.size(); ++i) renderer.setBodyPose(handBodies[i], f.X_world_hand * partPoses[i]);
    srp::rawlog::RgbdFrame frame = renderer.render(world.X_world_camera);
    result.renderTime_s += secondsSince(t0);

    t0 = Clock::now();
    frame.index = k;
    frame.t_s = kRawlogEpoch_s + f.t_s;
    cv::Mat handMask(K.height_px, K.width_px, CV_8UC1, cv::Scalar(0));
    cv::Mat partMask(K.height_px, K.width_px, CV_8UC1, cv::Scalar(0));
    cv::Mat movingMask(K.height_px, K.width_px, CV_8UC1, cv::Scalar(0));
    for (std::size_t i = 0; i < handBodies.size(); ++i)
      markBox(hand.parts()[i].bounds_part, X_camera_world * f.X_world_hand * partPoses[i], K, frame.depth_m, handMask);
    double movingSpeed = 0.0;
    for (std::size_t i = 0; i < objectBodies.size(); ++i) {
      if (!isPart[i]) continue;
      const double speed = (f.X_world_objects[i].translation() - prev.X_world_objects[i].translation()).norm() / dt;
      markBox(objectBounds[i], X_camera_world * f.X_world_objects[i], K, frame.depth_m, speed > 0.0 ? movingMask : partMask);
      movingSpeed = std::max(movingSpeed, speed);
    }
    partMask.setTo(0, handMask);
    movingMask.setTo(0, handMask);
    const double handSpeed = (f.X_world_hand.translation() - prev.X_world_hand.translation()).norm() / dt;
    const cv::Mat cleanColour = options.sensor.motionBlur ? frame.colour_bgr8.clone() : cv::Mat();
    sensor.apply(frame, handMask, handSpeed, partMask, movingMask, movingSpeed, previousColour);
    previousColour = cleanColour;

    GroundTruthFrame g;
    g.index = k;
    g.t_s = f.t_s;
    g.phase = f.phase;
    g.step = f.step;
    g.grip = f.grip;
    g.handPixels = cv::countNonZero(handMask);
    g.handInView = g.handPixels > 0;
    g.X_world_hand = f.X_world_hand;
    g.p_camera_palm_m = X_camera_world * f.X_world_hand.translation();
    g.X_camera_tag = X_camera_world * f.X_world_hand * hand.X_hand_tag();
    const auto corners = hand.tagCorners_tag();
    bool allIn = g.X_camera_tag.linear().col(2).dot(g.X_camera_tag.translation()) > 0.0;
    for (int c = 0; c < 4; ++c) {
      const auto uv = K.project(g.X_camera_tag * corners[c]);
      g.tagCorners_px[c] = uv ? *uv : Eigen::Vector2d(-1, -1);
      allIn = allIn && uv && K.contains(uv->x(), uv->y());
    }
    g.tagInView = allIn;
    if (f.carriedObject >= 0) g.carriedObject = world.objects[f.carriedObject].id;
    for (std::size_t i = 0; i < world.objects.size(); ++i) g.X_world_objects[world.objects[i].id] = f.X_world_objects[i];
    auto validFraction = [&](const cv::Mat& mask) -> std::optional<double> {
      const int n = cv::countNonZero(mask);
      if (n == 0) return std::nullopt;
      cv::Mat valid = (frame.depth_m > 0.f) & mask;
      return static_cast<double>(cv::countNonZero(valid)) / n;
    };
    g.handValidDepthFraction = validFraction(handMask);
    g.objectsValidDepthFraction = validFraction(partMask | movingMask);
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

    t0 = Clock::now();
    writer.write(frame);
    result.writeTime_s += secondsSince(t0);
    if (std::find(sheetFrames.begin(), sheetFrames.end(), k) != sheetFrames.end()) sheet.emplace_back(k, frame);
    if (progress) progress(k, frameCount);
  }
  writer.close();
  result.groundTruthPath = groundTruthPathFor(rawlogPath);
  gt.save(result.groundTruthPath);
  result.frameCount = frameCount;
  result.duration_s = frameCount / world.fps;
  result.meanHandValidDepth = handValidFrames ? handValidSum / handValidFrames : -1.0;
  result.meanObjectValidDepth = objectValidFrames ? objectValidSum / objectValidFrames : -1.0;

  // ---- Contact sheet: colour | depth per frame, two frames per row ----------------
  if (!options.contactSheetPath.empty() && !sheet.empty()) {
    const cv::Size tile(320, 240);
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
    if (!cv::imwrite(options.contactSheetPath, canvas))
      throw srp::core::FileError(options.contactSheetPath, "cannot write the contact sheet PNG");
    result.contactSheetPath = options.contactSheetPath;
  }
  result.totalTime_s = secondsSince(tStart);
  return result;
}

}  // namespace srp::synth
