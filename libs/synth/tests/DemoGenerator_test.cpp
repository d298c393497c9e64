#include "srp/kb/KnowledgeBase.h"
#include "srp/synth/DemoGenerator.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <iostream>
#include <map>

#include "srp/core/Error.h"
#include "srp/core/Json.h"
#include "srp/rawlog/RawlogReader.h"

#include <opencv2/imgproc.hpp>

namespace {

std::string tempPath(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("srp_synth_test_" + name)).string();
}

struct Fixture {
  srp::core::Scene scene = srp::core::Scene::load(std::string(SRP_SIM_DIR) + "/scenes/default.json");
  srp::core::ObjectCatalogue catalogue = srp::kb::loadCatalogue(scene.cataloguePath);
};

// A one-step plan, fast demonstrator, short idles and small images keep it quick.
nlohmann::json oneStepPlan() {
  auto plan = srp::synth::defaultPlanJson();
  plan["steps"] = nlohmann::json::array({plan["steps"][0]});
  return plan;
}

srp::synth::SynthDemoOptions quickOptions() {
  srp::synth::SynthDemoOptions o;
  o.demo.speedFactor = 2.0;
  o.demo.idleStart_s = 0.3;
  o.demo.idleEnd_s = 0.3;
  o.width_px = 320;
  o.height_px = 240;
  return o;
}

TEST(DemoGenerator, RawlogAndGroundTruthReadBack) {
  Fixture f;
  const std::string rawlog = tempPath("demo.rawlog");
  auto options = quickOptions();
  options.contactSheetPath = tempPath("sheet.png");
  const auto result = srp::synth::generateSyntheticDemo(f.scene, f.catalogue, oneStepPlan(), options, rawlog);
  ASSERT_GT(result.frameCount, 30);
  EXPECT_TRUE(std::filesystem::exists(options.contactSheetPath));

  const auto frames = srp::rawlog::RawlogReader::readAll(rawlog);
  const auto gt = srp::synth::DemoGroundTruth::load(result.groundTruthPath);
  ASSERT_EQ(static_cast<int>(frames.size()), result.frameCount);
  ASSERT_EQ(gt.frames.size(), frames.size());
  const auto K = srp::synth::scaleIntrinsics(f.scene.intrinsics, 320, 240);
  for (const auto& fr : frames) ASSERT_EQ(fr.intrinsics, K);
  EXPECT_EQ(gt.intrinsics, K);
  EXPECT_NEAR(frames[1].t_s - frames[0].t_s, 1.0 / f.scene.fps, 1e-6);
  ASSERT_EQ(gt.events.size(), 1u);
  EXPECT_EQ(gt.events[0].objectId, "cuboid");
  EXPECT_EQ(gt.frames[gt.events[0].graspFrame].carriedObject, "cuboid");
  EXPECT_TRUE(gt.frames[gt.events[0].releaseFrame + 1].carriedObject.empty());
  EXPECT_FALSE(gt.frames.front().handInView);
  EXPECT_FALSE(gt.frames.back().handInView);
  // Carried object: constant hand-relative pose in the file too.
  const auto& e = gt.events[0];
  for (int k = e.graspFrame; k <= e.releaseFrame; ++k) {
    const auto X_hand_object = gt.frames[k].X_world_hand.inverse() * gt.frames[k].X_world_objects.at("cuboid");
    ASSERT_LT((X_hand_object.translation() - e.X_hand_object.translation()).norm(), 1e-6) << "frame " << k;
  }
  // Ground truth round trip through JSON.
  const auto again = srp::synth::DemoGroundTruth::fromJson(gt.toJson(), "round trip");
  EXPECT_TRUE(again.frames[e.graspFrame].X_camera_tag.isApprox(gt.frames[e.graspFrame].X_camera_tag, 1e-12));
  EXPECT_TRUE(again.X_base_camera().isApprox(f.scene.X_base_camera(), 0.05));

  // Tag in view = readable: the whole plate is the visible surface; the glove
  // keeps it readable from the slow final approach through grasp and lift.
  for (const auto& g : gt.frames) {
    if (g.tagInView) EXPECT_DOUBLE_EQ(g.tagVisibleFraction, 1.0) << "frame " << g.index;
    if (!g.handInView) EXPECT_FALSE(g.tagInView) << "frame " << g.index;
  }
  for (int k = e.graspFrame - 10; k <= e.graspFrame + 10; ++k) EXPECT_TRUE(gt.frames[k].tagInView) << "frame " << k;
  EXPECT_EQ(again.frames[e.graspFrame].tagVisibleFraction, gt.frames[e.graspFrame].tagVisibleFraction);

  // Occlusion by the hand: none without a hand in view; the grasped part is
  // under the hand at the grasp; the gray box, far from the first pick, is not
  // hidden while the hand reaches into the blue box.
  for (const auto& g : gt.frames) {
    ASSERT_TRUE(g.handOccludedObjects.has_value()) << "frame " << g.index;
    if (!g.handInView) EXPECT_TRUE(g.handOccludedObjects->empty()) << "frame " << g.index;
  }
  EXPECT_EQ(gt.frames[e.graspFrame].handOccludedObjects->count("cuboid"), 1u);
  EXPECT_EQ(gt.frames[e.graspFrame].handOccludedObjects->count("gray box"), 0u);
  EXPECT_EQ(again.frames[e.graspFrame].handOccludedObjects, gt.frames[e.graspFrame].handOccludedObjects);

  // Sensor realism as in the thesis: < 50 % valid depth on the hand, > 70 % on objects.
  std::cout << "[measured] valid depth: hand " << 100 * result.meanHandValidDepth << " %, objects "
            << 100 * result.meanObjectValidDepth << " %\n";
  EXPECT_LT(result.meanHandValidDepth, 0.5);
  EXPECT_GT(result.meanHandValidDepth, 0.05);
  EXPECT_GT(result.meanObjectValidDepth, 0.7);
}

TEST(DemoGenerator, CleanDepthMatchesTheObjectPoses) {
  Fixture f;
  auto options = quickOptions();
  options.sensor.enabled = false;
  options.maxFrames = 1;
  const std::string rawlog = tempPath("clean.rawlog");
  srp::synth::generateSyntheticDemo(f.scene, f.catalogue, oneStepPlan(), options, rawlog);
  const auto frames = srp::rawlog::RawlogReader::readAll(rawlog);
  const auto gt = srp::synth::DemoGroundTruth::load(srp::synth::groundTruthPathFor(rawlog));
  ASSERT_EQ(frames.size(), 1u);
  // The pixel at the centre of the star's top face sees it at the true depth.
  const srp::core::Pose3 X_camera_star = gt.X_camera_object(0, "star");
  const Eigen::Vector3d p_top = X_camera_star * Eigen::Vector3d(0, 0, 0.025);
  const auto uv = gt.intrinsics.project(p_top);
  ASSERT_TRUE(uv);
  const float d = frames[0].depth_m.at<float>(std::lround(uv->y()), std::lround(uv->x()));
  EXPECT_NEAR(d, p_top.z(), 2e-3);
}

// A swaying head camera and a carry-only clip: every frame holds a part, every frame's camera is in
// the ground truth and the images are rendered from it (a resting part's top face seen at its true
// depth where the per-frame camera projects it), and the camera really moves.
TEST(DemoGenerator, HeadSwayCarryOnlyGroundTruthHasEachFramesCamera) {
  Fixture f;
  auto options = quickOptions();
  options.sensor.enabled = false;
  options.headSway.enabled = true;
  options.carryOnly = true;
  const std::string rawlog = tempPath("sway.rawlog");
  const auto result = srp::synth::generateSyntheticDemo(f.scene, f.catalogue, oneStepPlan(), options, rawlog);
  const auto frames = srp::rawlog::RawlogReader::readAll(rawlog);
  const auto gt = srp::synth::DemoGroundTruth::load(result.groundTruthPath);
  ASSERT_GT(frames.size(), 10u);
  ASSERT_EQ(gt.frames.size(), frames.size());
  EXPECT_TRUE(gt.cameraMoves());
  ASSERT_EQ(gt.events.size(), 1u);
  EXPECT_EQ(gt.events[0].graspFrame, 0);
  EXPECT_NEAR(frames[0].t_s - frames[1].t_s, -1.0 / f.scene.fps, 1e-6);
  constexpr double kDepthTol_m = 2e-3;
  constexpr double kMinSway_px = 5.0;  // the camera moves: the nominal camera's projection is off by more
  int seen = 0, seenNominal = 0;
  double largestShift_px = 0.0;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const auto& g = gt.frames[i];
    EXPECT_EQ(g.index, static_cast<int>(i));
    EXPECT_FALSE(g.carriedObject.empty()) << "frame " << i;
    ASSERT_TRUE(g.X_world_camera.has_value());
    const Eigen::Vector3d p_world_top = g.X_world_objects.at("star") * Eigen::Vector3d(0, 0, 0.025);
    const Eigen::Vector3d p_top = gt.X_camera_object(g.index, "star") * Eigen::Vector3d(0, 0, 0.025);
    EXPECT_TRUE(p_top.isApprox(g.X_world_camera->inverse() * p_world_top, 1e-9));
    const auto uv = gt.intrinsics.project(p_top);
    const auto uvNominal = gt.intrinsics.project(gt.X_world_camera.inverse() * p_world_top);
    ASSERT_TRUE(uv && uvNominal);
    largestShift_px = std::max(largestShift_px, (*uv - *uvNominal).norm());
    const float d = frames[i].depth_m.at<float>(std::lround(uv->y()), std::lround(uv->x()));
    seen += std::abs(d - p_top.z()) < kDepthTol_m;  // the hand may hide it in some frames
    const Eigen::Vector3d p_nominal = gt.X_world_camera.inverse() * p_world_top;
    const float dNominal = frames[i].depth_m.at<float>(std::lround(uvNominal->y()), std::lround(uvNominal->x()));
    seenNominal += std::abs(dNominal - p_nominal.z()) < kDepthTol_m;
  }
  std::cout << "[ figures  ] star's top at its true depth in " << seen << " of " << frames.size()
            << " frames through each frame's camera, " << seenNominal << " through the nominal camera\n";
  EXPECT_GE(seen, static_cast<int>(0.5 * frames.size()));
  EXPECT_GT(seen, 2 * seenNominal);
  EXPECT_GT(largestShift_px, kMinSway_px);
}

// Layered rendering (static background once, moving bodies per frame) gives
// the same images as rendering everything every frame.
TEST(DemoGenerator, LayeredRenderingMatchesFullRendering) {
  Fixture f;
  auto options = quickOptions();
  options.sensor.enabled = false;
  options.width_px = 160;
  options.height_px = 120;
  const std::string layeredPath = tempPath("layered.rawlog"), fullPath = tempPath("full.rawlog");
  options.layeredRendering = true;
  srp::synth::generateSyntheticDemo(f.scene, f.catalogue, oneStepPlan(), options, layeredPath);
  options.layeredRendering = false;
  srp::synth::generateSyntheticDemo(f.scene, f.catalogue, oneStepPlan(), options, fullPath);
  const auto layered = srp::rawlog::RawlogReader::readAll(layeredPath);
  const auto full = srp::rawlog::RawlogReader::readAll(fullPath);
  ASSERT_EQ(layered.size(), full.size());
  constexpr double kMaxDifferentPixels = 1e-3;  // fraction; coplanar faces may tie differently
  long long different = 0, total = 0;
  for (std::size_t k = 0; k < full.size(); ++k) {
    cv::Mat depthDiff = cv::abs(layered[k].depth_m - full[k].depth_m) > 1e-4f;
    cv::Mat colourDiff;
    cv::absdiff(layered[k].colour_bgr8, full[k].colour_bgr8, colourDiff);
    cv::Mat colourDiffGrey;
    cv::cvtColor(colourDiff, colourDiffGrey, cv::COLOR_BGR2GRAY);
    different += cv::countNonZero(depthDiff | (colourDiffGrey > 2));
    total += depthDiff.total();
  }
  EXPECT_LT(static_cast<double>(different) / total, kMaxDifferentPixels) << different << " of " << total;
}

TEST(DemoGroundTruth, LoadNamesTheFileAndMissingField) {
  Fixture f;
  auto options = quickOptions();
  options.maxFrames = 2;
  options.sensor.enabled = false;
  const std::string rawlog = tempPath("gtfields.rawlog");
  srp::synth::generateSyntheticDemo(f.scene, f.catalogue, oneStepPlan(), options, rawlog);
  auto j = srp::core::readJsonFile(srp::synth::groundTruthPathFor(rawlog));
  j.erase("camera");
  const std::string broken = tempPath("broken.gt.json");
  srp::core::writeJsonFile(broken, j);
  try {
    srp::synth::DemoGroundTruth::load(broken);
    FAIL();
  } catch (const srp::core::Error& e) {
    EXPECT_NE(std::string(e.what()).find("broken.gt.json"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("camera"), std::string::npos) << e.what();
  }
  j = srp::core::readJsonFile(srp::synth::groundTruthPathFor(rawlog));
  j["schema_version"] = srp::synth::DemoGroundTruth::kSchemaVersion + 1;
  srp::core::writeJsonFile(broken, j);
  EXPECT_THROW(srp::synth::DemoGroundTruth::load(broken), srp::core::Error);
}

TEST(DemoGenerator, BadSceneFailsNamingTheField) {
  Fixture f;
  const std::string rawlog = tempPath("bad.rawlog");
  auto expectMessage = [&](const srp::core::Scene& scene, const std::string& needle) {
    try {
      srp::synth::generateSyntheticDemo(scene, f.catalogue, oneStepPlan(), quickOptions(), rawlog);
      FAIL() << "accepted a bad scene; expected a message naming " << needle;
    } catch (const srp::core::Error& e) {
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    }
  };
  auto unknown = f.scene;
  unknown.objects[2].className = "teapot";
  expectMessage(unknown, "teapot");
  auto outside = f.scene;
  outside.objects[3].X_world_object.translation().x() = 2.0;
  expectMessage(outside, outside.objects[3].id);
  // Missing field: parsing the scene file names it.
  nlohmann::json j = srp::core::readJsonFile(std::string(SRP_SIM_DIR) + "/scenes/default.json");
  j["camera"].erase("intrinsics");
  try {
    srp::core::Scene::fromJson(j, "scene.json", std::string(SRP_SIM_DIR) + "/scenes");
    FAIL();
  } catch (const srp::core::InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("intrinsics"), std::string::npos) << e.what();
  }
}

}  // namespace

// Issue 19: several instances of one class, each rendered in its scene colour
// (sim/scenes/two_cuboids_two_stars.json: red and blue cuboid, yellow and green star).
TEST(DemoGenerator, InstancesOfOneClassRenderInTheirOwnColour) {
  const auto scene = srp::core::Scene::load(std::string(SRP_SIM_DIR) + "/scenes/two_cuboids_two_stars.json");
  const auto catalogue = srp::kb::loadCatalogue(scene.cataloguePath);
  nlohmann::json plan = {{"steps",
                          {{{"object", {{"name", "star"}, {"color", "green"}}},
                            {"target", {{{"relation", "in"}, {"landmark", {{"name", "box"}, {"color", "gray"}}}}}}}}}};
  auto options = quickOptions();
  options.sensor.enabled = false;
  options.demo.randomise = false;
  options.maxFrames = 1;
  const std::string rawlog = tempPath("instances.rawlog");
  srp::synth::generateSyntheticDemo(scene, catalogue, plan, options, rawlog);
  const auto frames = srp::rawlog::RawlogReader::readAll(rawlog);
  const auto gt = srp::synth::DemoGroundTruth::load(srp::synth::groundTruthPathFor(rawlog));
  ASSERT_EQ(frames.size(), 1u);
  const std::vector<std::string> ids{"cuboid_red", "cuboid_blue", "star_yellow", "star_green"};
  auto chroma = [](const Eigen::Vector3d& rgb) -> Eigen::Vector3d { return rgb / std::max(rgb.sum(), 1e-9); };
  std::map<std::string, Eigen::Vector3d> expected;
  for (const auto& id : ids) {
    const auto* o = scene.findObject(id);
    ASSERT_NE(o, nullptr) << id;
    expected[id] = chroma(srp::core::instanceRgb(*o, catalogue.at(o->className)));
  }
  for (const auto& id : ids) {
    // Mean colour of a 3x3 patch at the centre of the top face.
    const auto* o = scene.findObject(id);
    const double h = catalogue.at(o->className).dimensions_m.z();
    const auto uv = gt.intrinsics.project(gt.X_camera_object(0, id) * Eigen::Vector3d(0, 0, h));
    ASSERT_TRUE(uv) << id;
    const cv::Rect patch(static_cast<int>(std::lround(uv->x())) - 1, static_cast<int>(std::lround(uv->y())) - 1, 3, 3);
    const cv::Scalar bgr = cv::mean(frames[0].colour_bgr8(patch));
    const Eigen::Vector3d seen = chroma(Eigen::Vector3d(bgr[2], bgr[1], bgr[0]) / 255.0);
    // Nearest of the four instance colours (chromaticity: the lighting scales brightness).
    std::string nearest;
    double best = 1e9;
    for (const auto& [other, c] : expected)
      if ((c - seen).norm() < best) best = (c - seen).norm(), nearest = other;
    EXPECT_EQ(nearest, id) << id << " rendered with chromaticity " << seen.transpose();
  }
}
