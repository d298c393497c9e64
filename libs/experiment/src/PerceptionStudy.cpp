#include "PerceptionStudy.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <unistd.h>

#include "srp/core/Error.h"
#include "srp/core/Json.h"
#include "srp/core/Scene.h"
#include "srp/experiment/DemoCache.h"
#include "srp/experiment/ExperimentSupport.h"
#include "srp/kb/KnowledgeBase.h"
#include "srp/perception/MarkerFreeHandDetector.h"
#include "srp/perception/RawlogPerception.h"

namespace srp::experiment::detail {

namespace fs = std::filesystem;

namespace {

constexpr int kCacheSchemaVersion = 1;

/// The demo of `seed` for this study: the default scene and instruction 1
/// (SPEC.md §4), seeded randomisation, default sensor noise, the scene
/// camera's 640×480 (the L515's depth size, not the standard demos' 320×240:
/// the glove's tag is 40 px wide there, half that at 320×240); only the
/// frames the study uses are rendered. Rendered once per run by the shared
/// demo cache.
DemoRequest studyDemoRequest(unsigned seed, const PerceptionStudySize& size)
{
  DemoRequest request;
  request.seed = seed;
  request.maxFrames = size.framesPerDemo;
  return request;
}

nlohmann::json handToJson(const std::vector<PerceivedHand>& hands)
{
  nlohmann::json j = nlohmann::json::array();
  for (const auto& h : hands)
    j.push_back({h.detected, h.hasPoint, h.p_camera_palm_m.x(), h.p_camera_palm_m.y(), h.p_camera_palm_m.z()});
  return j;
}

std::vector<PerceivedHand> handFromJson(const nlohmann::json& j)
{
  std::vector<PerceivedHand> hands;
  for (const auto& e : j)
    hands.push_back({e.at(0).get<bool>(), e.at(1).get<bool>(),
                     Eigen::Vector3d(e.at(2).get<double>(), e.at(3).get<double>(), e.at(4).get<double>())});
  return hands;
}

nlohmann::json objectsToJson(const std::vector<std::vector<PerceivedObject>>& perFrame)
{
  nlohmann::json j = nlohmann::json::array();
  for (const auto& frame : perFrame) {
    nlohmann::json f = nlohmann::json::array();
    for (const auto& o : frame)
      f.push_back({{"class", o.className}, {"confidence", o.confidence}, {"detected", o.detected},
                   {"X_camera_object", core::poseToJson(o.X_camera_object)}});
    j.push_back(f);
  }
  return j;
}

std::vector<std::vector<PerceivedObject>> objectsFromJson(const nlohmann::json& j, const std::string& context)
{
  std::vector<std::vector<PerceivedObject>> perFrame;
  for (const auto& f : j) {
    perFrame.emplace_back();
    for (const auto& o : f)
      perFrame.back().push_back({o.at("class").get<std::string>(), o.at("confidence").get<double>(),
                                 core::poseFromJson(o.at("X_camera_object"), context), o.at("detected").get<bool>()});
  }
  return perFrame;
}

/// One perception pass over the first frames of a demo: the module with the
/// AprilTag glove and instruction 1's objects of interest, plus the
/// marker-free detector on the same frames.
PerceivedDemo perceiveDemo(const ExperimentOptions& options, unsigned seed, const PerceptionStudySize& size,
                           const CachedDemo& files, const core::ObjectCatalogue& catalogue, int demoIndex,
                           const std::string& what)
{
  PerceivedDemo demo;
  demo.seed = seed;
  demo.groundTruth = synth::DemoGroundTruth::load(files.groundTruthPath.string());

  perception::PerceptionOptions o;
  o.marker.tagSize_m = demo.groundTruth.tagSize_m;
  o.marker.tagId = demo.groundTruth.tagId;
  o.marker.p_tag_palm_m = demo.groundTruth.X_hand_tag.inverse().translation();
  // Instruction 1 names the four parts (moved) and the two boxes (static):
  // the plan `srp perceive --objects <parts> --static <boxes>` makes, parts first.
  for (const bool containers : {false, true})
    for (const auto& object : demo.groundTruth.objects) {
      const bool isStatic = catalogue.at(object.className).kind == core::ObjectKind::Container;
      if (isStatic != containers) continue;
      o.plan.push_back({object.className, isStatic, "", std::nullopt});
      demo.isStatic[object.className] = isStatic;
    }
  o.onFrameDetections = [&demo](int, const std::vector<perception::ObjectDetection>& detections) {
    demo.raw.emplace_back();
    for (const auto& d : detections) demo.raw.back().push_back({d.key, d.confidence, d.X_camera_object, true});
  };
  perception::MarkerFreeHandDetector markerFree(o.markerFree);
  bool haveDepth = false;
  double lastZ_m = 0.0;
  // The marker-free hand alone on each frame the module perceives, its depth
  // holes filled as the module fills them: the last depth carried along the
  // palm pixel's ray.
  const auto detectMarkerFree = [&](const rawlog::RgbdFrame& frame, int) {
    PerceivedHand h;
    if (const auto obs = markerFree.detect(frame)) {
      h.detected = true;
      if (obs->hasDepth) {
        h.hasPoint = true;
        h.p_camera_palm_m = obs->p_camera_palm_m;
        lastZ_m = obs->p_camera_palm_m.z();
        haveDepth = true;
      } else if (haveDepth) {
        h.hasPoint = true;
        h.p_camera_palm_m = frame.intrinsics.backProject(obs->palm_px.x(), obs->palm_px.y(), lastZ_m);
      }
    }
    demo.markerFree.push_back(h);
  };
  const auto progress = [&](int frame, int) {
    if ((frame + 1) % 10 == 0)
      reportProgress(options, what + ": perceiving demo seed " + std::to_string(seed),
                     (demoIndex + 0.5 + 0.5 * (frame + 1) / size.framesPerDemo) / size.demoCount);
  };

  // The module as `srp perceive` runs it (perception::perceiveRawlog: the
  // preview pass, then perception), on the demo rendered with the study's frames.
  const auto start = std::chrono::steady_clock::now();
  const perception::PerceptionResult result =
      perception::perceiveRawlog(files.rawlogPath.string(), catalogue, o, progress, detectMarkerFree);
  if (result.frames != size.framesPerDemo)
    throw core::FileError(files.rawlogPath.string(),
                          "has " + std::to_string(result.frames) + " frames, the study needs " +
                              std::to_string(size.framesPerDemo) + "; delete it to render it again");
  demo.perceptionTime_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  demo.frames = result.frames;

  for (std::size_t i = 0; i < result.hand.size(); ++i) {
    const auto& s = result.hand[i];
    demo.marker.push_back({s.valid, s.valid, s.p_m});
  }
  demo.refined.assign(static_cast<std::size_t>(demo.frames), {});
  for (const auto& trajectory : result.objects)
    for (std::size_t i = 0; i < trajectory.samples.size() && i < demo.refined.size(); ++i) {
      const auto& s = trajectory.samples[i];
      demo.refined[i].push_back({trajectory.className, s.confidence, s.X_camera_object, s.detected});
    }
  demo.groundTruth.frames.resize(static_cast<std::size_t>(demo.frames));
  return demo;
}

}  // namespace

std::string PerceptionStudySize::describe() const
{
  return std::to_string(demoCount) + " seeded synthetic demo" + (demoCount == 1 ? "" : "s") + " × first " +
         std::to_string(framesPerDemo) + " frames (" + formatNumber(framesPerDemo / 30.0, 1) +
         " s of instruction 1, the cuboid's pick & place; 640×480, default sensor noise)";
}

PerceptionStudySize studySize(const ExperimentOptions& options)
{
  if (options.demoCount < 1)
    throw core::InvalidInputError("demo count " + std::to_string(options.demoCount) + " is not positive; use 1 or more");
  PerceptionStudySize size;
  size.demoCount = options.demoCount;
  if (options.quick) {
    // The hand-free start (the marker-free detector's background), then the
    // reach to the cuboid: a few dozen frames with the hand.
    size.demoCount = 1;
    size.framesPerDemo = 100;
  }
  return size;
}

core::ObjectCatalogue studyCatalogue(const ExperimentOptions& options)
{
  // Scene::load names the file when it is missing or broken.
  return kb::loadCatalogue(core::Scene::load(defaultScenePathIn(options.simDir).string()).cataloguePath);
}

std::vector<PerceivedDemo> perceivedDemos(const ExperimentOptions& options, const std::string& what)
{
  const PerceptionStudySize size = studySize(options);
  const DemoCache demoCache = demoCacheFor(options);
  std::vector<PerceivedDemo> demos;
  for (int k = 0; k < size.demoCount; ++k) {
    const unsigned seed = options.firstSeed + static_cast<unsigned>(k);
    const fs::path cachePath =
        options.outDir / "perception" / ((options.quick ? "quick-seed-" : "seed-") + std::to_string(seed) + ".json");
    const DemoRequest request = studyDemoRequest(seed, size);
    const CachedDemo files = demoCache.get(request, [&](int frame, int frames) {
      if (frame % 20 == 0) reportProgress(options, what + ": rendering demo seed " + std::to_string(seed),
                                          (k + 0.5 * frame / std::max(1, frames)) / size.demoCount);
    });
    const std::string& demoKey = files.key;
    if (fs::exists(cachePath)) {
      try {
        const nlohmann::json j = core::readJsonFile(cachePath.string());
        if (j.at("schema_version").get<int>() == kCacheSchemaVersion && j.at("frames").get<int>() == size.framesPerDemo &&
            j.at("seed").get<unsigned>() == seed && j.at("demo_key").get<std::string>() == demoKey &&
            j.value("program_build", std::string()) == programBuildIdentity()) {
          PerceivedDemo demo;
          demo.seed = seed;
          demo.frames = size.framesPerDemo;
          demo.groundTruth = synth::DemoGroundTruth::load(files.groundTruthPath.string());
          demo.groundTruth.frames.resize(static_cast<std::size_t>(demo.frames));
          demo.marker = handFromJson(j.at("marker"));
          demo.markerFree = handFromJson(j.at("marker_free"));
          demo.raw = objectsFromJson(j.at("raw"), cachePath.string());
          demo.refined = objectsFromJson(j.at("refined"), cachePath.string());
          demo.isStatic = j.at("static").get<std::map<std::string, bool>>();
          demo.perceptionTime_s = j.at("perception_time_s").get<double>();
          demos.push_back(std::move(demo));
          continue;
        }
      } catch (const std::exception&) {
        // Unreadable or from another version: perceive again.
      }
    }
    PerceivedDemo demo = perceiveDemo(options, seed, size, files, files.catalogue, k, what);
    fs::create_directories(cachePath.parent_path());
    const nlohmann::json cache{{"schema_version", kCacheSchemaVersion},
                                             {"seed", seed},
                                             {"frames", demo.frames},
                                             {"demo_key", demoKey},
                                             {"program_build", programBuildIdentity()},
                                             {"rawlog", files.rawlogPath.string()},
                                             {"perception_time_s", demo.perceptionTime_s},
                                             {"static", demo.isStatic},
                                             {"marker", handToJson(demo.marker)},
                                             {"marker_free", handToJson(demo.markerFree)},
                                             {"raw", objectsToJson(demo.raw)},
                                             {"refined", objectsToJson(demo.refined)}};
    // Own temporary name, then an atomic rename (concurrent runs write the same content).
    const fs::path tmpCache = cachePath.string() + "." + std::to_string(::getpid()) + ".tmp";
    core::writeJsonFile(tmpCache.string(), cache);
    fs::rename(tmpCache, cachePath);
    demos.push_back(std::move(demo));
  }
  return demos;
}

double percentile(std::vector<double> values, double fraction)
{
  if (values.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::sort(values.begin(), values.end());
  const double rank = std::ceil(fraction * static_cast<double>(values.size()));
  const std::size_t index = static_cast<std::size_t>(std::clamp(rank, 1.0, static_cast<double>(values.size()))) - 1;
  return values[index];
}

}  // namespace srp::experiment::detail
