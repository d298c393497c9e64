#include "srp/experiment/DemoCache.h"

#include "srp/experiment/ExperimentResult.h"

#include <sys/file.h>
#include <fcntl.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "srp/core/DataPaths.h"
#include "srp/core/DefaultScene.h"
#include "srp/core/Error.h"
#include "srp/core/Json.h"
#include "srp/core/ObjectCatalogue.h"
#include "srp/core/Scene.h"
#include "srp/experiment/ExperimentSupport.h"
#include "srp/kb/KnowledgeBase.h"
#include "srp/programming/ProgrammingPipeline.h"
#include "srp/synth/DemoGenerator.h"
#include "srp/synth/PickPlacePlan.h"

namespace srp::experiment {
namespace {

// FNV-1a, 64 bit: a stable key across runs and machines (std::hash is neither).
std::uint64_t fnv1a(const std::string& text)
{
  std::uint64_t h = 1469598103934665603ULL;
  for (unsigned char c : text) {
    h ^= c;
    h *= 1099511628211ULL;
  }
  return h;
}

std::string readWholeFile(const std::filesystem::path& path)
{
  std::ifstream in(path, std::ios::binary);
  if (!in)
    throw core::FileError(path.string(), "cannot read the scene; give an existing scene JSON (e.g. sim/scenes/default.json)");
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// An exclusive lock on a file for the scope: processes sharing a cache (the
// tests under `ctest -j`, two experiments at once) render each demo once.
class FileLock
{
public:
  explicit FileLock(const std::filesystem::path& path) : fd_(::open(path.c_str(), O_CREAT | O_RDWR, 0644))
  {
    if (fd_ < 0) throw core::FileError(path.string(), "cannot create the demo cache's lock file; check permissions");
    ::flock(fd_, LOCK_EX);
  }
  ~FileLock()
  {
    ::flock(fd_, LOCK_UN);
    ::close(fd_);
  }
  FileLock(const FileLock&) = delete;
  FileLock& operator=(const FileLock&) = delete;

private:
  int fd_;
};

nlohmann::json planOf(const DemoRequest& request)
{
  return request.plan.is_null() ? synth::defaultPlanJson() : request.plan;
}

std::string keyFor(const std::string& sceneText, const DemoRequest& request) {
  const nlohmann::json key{{"scene", sceneText},
                           {"plan", planOf(request)},
                           {"seed", request.seed},
                           {"max_frames", request.maxFrames},
                           {"width_px", request.width_px},
                           {"height_px", request.height_px},
                           {"sensor_realism", request.sensorRealism}};
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(fnv1a(key.dump())));
  return hex;
}

/// The scene file's text (the cache key hashes it) and the scene parsed from that same text.
core::Scene sceneFromText(const std::string& text, const std::filesystem::path& path) {
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {
    throw core::FileError(path.string(), std::string("malformed scene JSON: ") + e.what() + "; fix the file");
  }
  return core::Scene::fromJson(j, path.string(), path.parent_path().string());
}

}  // namespace

DemoCache::DemoCache(std::filesystem::path rootDir, std::filesystem::path simDir)
    : rootDir_(std::move(rootDir)), simDir_(simDir.empty() ? core::DataPaths::file("sim") : std::move(simDir))
{
}

std::filesystem::path DemoCache::scenePathOf(const DemoRequest& request) const
{
  return request.scenePath.empty() ? defaultScenePathIn(simDir_) : request.scenePath;
}

std::string DemoCache::keyOf(const DemoRequest& request) const
{
  return keyFor(readWholeFile(scenePathOf(request)), request);
}

CachedDemo DemoCache::get(const DemoRequest& request, const std::function<void(int, int)>& progress) const
{
  const auto scenePath = scenePathOf(request);
  const std::string sceneText = readWholeFile(scenePath);  // the one read: key, scene and catalogue
  const std::string key = keyFor(sceneText, request);
  const auto dir = rootDir_ / std::to_string(request.seed);
  const auto donePath = dir / (key + ".done.json");
  const nlohmann::json plan = planOf(request);

  CachedDemo demo;
  demo.rawlogPath = dir / (key + ".rawlog");
  demo.groundTruthPath = synth::groundTruthPathFor(demo.rawlogPath.string());
  demo.instruction = plan.value("instruction", std::string());
  demo.key = key;
  demo.scene = sceneFromText(sceneText, scenePath);
  demo.catalogue = kb::loadCatalogue(demo.scene.cataloguePath);
  std::filesystem::create_directories(dir);
  const FileLock lock(dir / (key + ".lock"));
  if (std::filesystem::exists(donePath) && std::filesystem::exists(demo.rawlogPath) &&
      std::filesystem::exists(demo.groundTruthPath)) {
    demo.frameCount = core::readJsonFile(donePath.string()).value("frames", 0);
    return demo;
  }

  const auto t0 = std::chrono::steady_clock::now();
  synth::SynthDemoOptions options;
  options.demo.seed = request.seed;
  options.sensor.enabled = request.sensorRealism;
  options.width_px = request.width_px;
  options.height_px = request.height_px;
  options.maxFrames = request.maxFrames;
  const auto result =
      synth::generateSyntheticDemo(demo.scene, demo.catalogue, plan, options, demo.rawlogPath.string(), progress);
  demo.frameCount = result.frameCount;
  demo.renderedNow = true;
  demo.renderTime_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  // Written last: its presence says the rawlog and ground truth are complete.
  core::writeJsonFile(donePath.string(), {{"frames", result.frameCount},
                                          {"scene", scenePath.string()},
                                          {"seed", request.seed},
                                          {"max_frames", request.maxFrames},
                                          {"width_px", request.width_px},
                                          {"height_px", request.height_px},
                                          {"sensor_realism", request.sensorRealism},
                                          {"render_time_s", demo.renderTime_s}});
  return demo;
}

ProgrammedDemo DemoCache::programmed(
    const DemoRequest& request, const std::function<void(const std::string&, std::size_t, std::size_t)>& progress) const
{
  ProgrammedDemo out;
  out.demo = get(request, [&](int k, int n) {
    if (progress) progress("render", static_cast<std::size_t>(k + 1), static_cast<std::size_t>(n));
  });
  if (out.demo.instruction.empty())
    throw core::InvalidInputError("the demo's plan has no \"instruction\" text to program it with; add one to the plan JSON");
  const std::string key = out.demo.rawlogPath.stem().string();
  const auto dir = out.demo.rawlogPath.parent_path();
  out.databasePath = dir / (key + ".task.db");
  const auto donePath = dir / (key + ".program.json");
  const FileLock lock(dir / (key + ".program.lock"));
  if (std::filesystem::exists(donePath) && std::filesystem::exists(out.databasePath)) {
    out.program = core::readJsonFile(donePath.string());
    // Programmed by this build: reuse; by another build: program again.
    if (out.program.value("program_build", std::string()) == programBuildIdentity()) {
      out.taskModelId = out.program.at("task_model_id").get<int>();
      return out;
    }
  }
  const auto t0 = std::chrono::steady_clock::now();
  std::filesystem::remove(out.databasePath);  // a half-written one from an interrupted run
  programming::ProgrammingOptions options;
  options.instruction = out.demo.instruction;
  options.demoPath = out.demo.rawlogPath.string();
  options.dbPath = out.databasePath.string();
  options.name = "demo-seed-" + std::to_string(request.seed);
  // The experiments score what programming found, including steps it could not learn.
  options.allowPartial = true;
  if (progress) options.progress = progress;
  const auto result = programming::programTask(options);
  out.taskModelId = result.taskModelId;
  out.program = nlohmann::json::parse(programming::toJsonText(result));
  out.programmedNow = true;
  out.programTime_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  out.program["program_time_s"] = out.programTime_s;
  out.program["program_build"] = programBuildIdentity();
  core::writeJsonFile(donePath.string(), out.program);
  return out;
}

DemoRequest standardDemoRequest(const ExperimentOptions& options, int index)
{
  DemoRequest request;
  request.seed = options.firstSeed + static_cast<std::uint32_t>(index);
  // Half the L515's 640x480 depth resolution: perception costs ~4x less per
  // frame, which keeps `srp experiment all` within its budget on 2 cores.
  request.width_px = kStandardWidth_px;
  request.height_px = kStandardHeight_px;
  if (options.quick) {
    // The first step of instruction 1 alone, as its own instruction: a complete
    // pick & place in about 250 frames.
    nlohmann::json plan = synth::defaultPlanJson();
    plan["steps"] = nlohmann::json::array({plan.at("steps").at(0)});
    plan["instruction"] = "Pick up the cuboid from the blue box and place it in the gray box.";
    request.plan = plan;
  }
  return request;
}

std::filesystem::path defaultScenePathIn(const std::filesystem::path& simDir) {
  return simDir.empty() ? std::filesystem::path(core::defaultScenePath()) : simDir / "scenes" / "default.json";
}

DemoCache demoCacheFor(const ExperimentOptions& options)
{
  return DemoCache(options.outDir / "demos", options.simDir);  // empty simDir: the build's sim/
}

}  // namespace srp::experiment
