// Robustness of the real cube's tracking (issue 17, session 8): the frames of
// datasets/real/visp-rbt-cube played back the ways a real recording differs
// from the one the tracker was developed on -- faster apparent motion (every
// 2nd/3rd/4th frame), dropped frames, a hand passing in front of the cube, a
// start in a fast-moving frame, the camera moving the other way (reversed).
// Measured against both references: the board-derived one (RealData.h
// trueCubePose) and the scene-derived one (storedScenePoses: RGB-D odometry of
// the scene, no tags, cube masked).
//
// Development: every choice was made on variants of frames 0-29; the
// variants of frames 30-49 are this module's own check, measured once.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <cstdio>
#include <functional>
#include <opencv2/imgproc.hpp>
#include <string>
#include <time.h>

#include "RealData.h"
#include "srp/kb/KnowledgeBase.h"
#include "srp/perception/DemoPerception.h"
#include "srp/perception/ModelBasedTracker.h"
#include "srp/perception/RgbdFolder.h"

namespace srp::perception {
namespace {

constexpr double kPositionTol_m = 0.01;               // issue 17: 1 cm ...
constexpr double kAngleTol_rad = 5.0 * M_PI / 180.0;  // ... and 5 deg, modulo the cube's 24 rotations
constexpr double kCubeHalf_m = 0.0425;                // cube.obj: 8.5 cm, centred

/// One way of playing the recording back: which frames, in which order, and
/// which of them a synthetic hand hides the cube in.
struct Variant {
  std::string name;
  std::vector<int> frames;
  std::vector<int> occluded;
  std::vector<int> depthOutOfStep;  ///< frames whose depth image is shifted by kDepthOutOfStep_px
};

/// Depth and colour out of step (the depth of a moment earlier during a fast
/// move): the depth image shifted sideways by this much, about 3 cm at the cube.
constexpr int kDepthOutOfStep_px = 40;

std::vector<int> range(int first, int last, int step = 1) {
  std::vector<int> out;
  if (step > 0)
    for (int i = first; i <= last; i += step) out.push_back(i);
  else
    for (int i = first; i >= last; i += step) out.push_back(i);
  return out;
}

/// The stress variants of frames [first, last] (dev: 0-29, own check: 30-49).
std::vector<Variant> variants(int first, int last) {
  const int n = last - first + 1;
  std::vector<Variant> out;
  out.push_back({"every frame", range(first, last), {}});
  const char* steps = std::getenv("SRP_CUBE_STRESS_MORE_STEPS");  // exploration: where does tracking break?
  if (steps)
    for (int step : {5, 6, 8}) out.push_back({"every " + std::to_string(step) + ". frame", range(first, last, step), {}});
  for (int step : {2, 3, 4}) out.push_back({"every " + std::to_string(step) + ". frame", range(first, last, step), {}});
  // Five frames dropped in the middle (a stall of the recorder).
  std::vector<int> dropped;
  for (int i = first; i <= last; ++i)
    if (i < first + n / 3 || i >= first + n / 3 + 5) dropped.push_back(i);
  out.push_back({"5 frames dropped", dropped, {}});
  // A hand passes in front of the cube for 4 frames.
  out.push_back({"hand passes (4 frames)", range(first, last), range(first + n / 3, first + n / 3 + 3)});
  // The first frame in the middle of the fastest stretch, then on.
  out.push_back({"starts mid-sequence", range(first + n / 2, last), {}});
  out.push_back({"reversed", range(last, first, -1), {}});
  // Depth out of step with colour in two frames in the middle.
  out.push_back({"depth out of step (2 frames)", range(first, last), {}, range(first + n / 2, first + n / 2 + 1)});
  return out;
}

/// A hand-sized skin-coloured, textured blob 25 cm in front of the camera,
/// sweeping across the cube's image from left to right over the occluded
/// frames (`phase` in [0, 1]), hiding it whole in the middle ones.
void paintHand(rawlog::RgbdFrame& f, const core::Pose3& X_camera_cube, double phase) {
  const auto& k = f.intrinsics;
  const Eigen::Vector3d c = X_camera_cube.translation();
  const double radius_px = 1.6 * kCubeHalf_m * k.fx_px / c.z();
  const double u = k.fx_px * c.x() / c.z() + k.cx_px + (phase - 0.5) * 2.0 * radius_px;
  const double v = k.fy_px * c.y() / c.z() + k.cy_px;
  f.colour_bgr8 = f.colour_bgr8.clone();
  f.depth_m = f.depth_m.clone();
  cv::Mat mask = cv::Mat::zeros(f.colour_bgr8.size(), CV_8U);
  cv::ellipse(mask, cv::Point(static_cast<int>(u), static_cast<int>(v)),
              cv::Size(static_cast<int>(radius_px), static_cast<int>(1.4 * radius_px)), 20.0, 0, 360, 255, -1);
  cv::Mat skin(f.colour_bgr8.size(), CV_8UC3, cv::Scalar(120, 150, 200));
  cv::Mat noise(f.colour_bgr8.size(), CV_8UC3);
  cv::RNG rng(static_cast<std::uint64_t>(1000 + f.index));  // the same hand in every run
  rng.fill(noise, cv::RNG::UNIFORM, cv::Scalar(0, 0, 0), cv::Scalar(40, 40, 40));
  skin += noise;
  skin.copyTo(f.colour_bgr8, mask);
  f.depth_m.setTo(0.25, mask);
}

struct Figures {
  int frames = 0, detected = 0, withinBoard = 0, withinScene = 0, wrongWhileHidden = 0;
  std::vector<double> board_m, scene_m;
  static double median(std::vector<double> v) {
    if (v.empty()) return 1e9;
    std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
    return v[v.size() / 2];  // the upper median of an even count
  }
  double worstScene_m() const { return scene_m.empty() ? 1e9 : *std::max_element(scene_m.begin(), scene_m.end()); }
};

class RealCubeStress : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    frames_ = new std::vector<rawlog::RgbdFrame>(readRgbdFolder(testing::rbtFolder()));
    catalogue_ = new core::ObjectCatalogue(kb::loadCatalogue(testing::rbtFolder() + "/catalogue.json"));
  }
  static void TearDownTestSuite() {
    delete frames_;
    delete catalogue_;
  }

  static PerceptionOptions shippedOptions() {
    PerceptionOptions o;  // as `srp perceive --hand none --moving-camera --objects cube` sets them
    o.hand = PerceptionOptions::HandMethod::None;
    o.movingCamera = true;
    o.plan = {{"cube", false}};
    return o;
  }

  /// Runs one variant and scores every frame of it (a frame where the cube
  /// is not detected is scored with the pose carried to it; hidden frames
  /// only count a detection more than 1 cm from the scene-derived pose).
  static Figures run(const Variant& v, const PerceptionOptions& options, bool print = false) {
    const auto& all = *frames_;
    const auto boards = testing::storedBoardPoses();
    const auto scenes = testing::storedScenePoses();
    const core::Pose3 X_c0_cube = testing::storedCubePoseFrame0();
    std::vector<rawlog::RgbdFrame> frames;
    for (std::size_t j = 0; j < v.frames.size(); ++j) {
      const int i = v.frames[j];
      rawlog::RgbdFrame f = all.at(static_cast<std::size_t>(i));
      f.t_s = 0.1 * static_cast<double>(j);  // played back in this order
      const auto hidden = std::find(v.occluded.begin(), v.occluded.end(), i);
      if (hidden != v.occluded.end())
        paintHand(f, scenes[static_cast<std::size_t>(i)],
                  v.occluded.size() > 1 ? double(hidden - v.occluded.begin()) / double(v.occluded.size() - 1) : 0.5);
      if (std::count(v.depthOutOfStep.begin(), v.depthOutOfStep.end(), i)) {
        cv::Mat shifted(f.depth_m.size(), f.depth_m.type(), cv::Scalar(0.0f));
        f.depth_m.colRange(0, f.depth_m.cols - kDepthOutOfStep_px)
            .copyTo(shifted.colRange(kDepthOutOfStep_px, f.depth_m.cols));
        f.depth_m = shifted;
      }
      frames.push_back(f);
    }
    const PerceptionResult r = perceiveFrames(frames, *catalogue_, options);
    Figures fig;
    const auto& samples = r.objects.front().samples;
    for (std::size_t j = 0; j < samples.size(); ++j) {
      const auto& s = samples[j];
      const auto i = static_cast<std::size_t>(s.frame);
      const bool hidden = std::count(v.occluded.begin(), v.occluded.end(), s.frame) > 0;
      const double dScene = core::translationDistance(s.X_camera_object, scenes[i]);
      const core::Pose3 board = testing::trueCubePose(boards, X_c0_cube, i);
      const double dBoard = core::translationDistance(s.X_camera_object, board);
      const double aBoard = testing::cubeAngleError(s.X_camera_object.linear(), board.linear());
      const double aScene = testing::cubeAngleError(s.X_camera_object.linear(), scenes[i].linear());
      if (print)
        std::printf("[ frame    ] %-24s %2d %s%s board %6.2f mm %4.2f deg, scene %6.2f mm %4.2f deg\n", v.name.c_str(),
                    s.frame, s.detected ? "detected" : "carried ", hidden ? " hidden" : "       ", dBoard * 1e3,
                    aBoard * 180 / M_PI, dScene * 1e3, aScene * 180 / M_PI);
      if (hidden) {
        fig.wrongWhileHidden += s.detected && dScene >= kPositionTol_m;
        continue;
      }
      ++fig.frames;
      fig.detected += s.detected;
      fig.board_m.push_back(dBoard);
      fig.scene_m.push_back(dScene);
      fig.withinBoard += dBoard < kPositionTol_m && aBoard < kAngleTol_rad;
      fig.withinScene += dScene < kPositionTol_m && aScene < kAngleTol_rad;
    }
    return fig;
  }

  static void report(const std::string& config, const std::string& variant, const Figures& f) {
    std::printf("[ figures  ] %-28s %-24s board %2d/%2d %6.2f mm | scene %2d/%2d %6.2f mm, worst %6.2f mm | detected "
                "%2d/%2d, wrong while hidden %d\n",
                config.c_str(), variant.c_str(), f.withinBoard, f.frames, Figures::median(f.board_m) * 1e3,
                f.withinScene, f.frames, Figures::median(f.scene_m) * 1e3, f.worstScene_m() * 1e3, f.detected,
                f.frames, f.wrongWhileHidden);
  }

  static std::vector<rawlog::RgbdFrame>* frames_;
  static core::ObjectCatalogue* catalogue_;
};
std::vector<rawlog::RgbdFrame>* RealCubeStress::frames_ = nullptr;
core::ObjectCatalogue* RealCubeStress::catalogue_ = nullptr;

/// The session-7 loss handling: coverage at the tracked pose as tracked, the
/// detection always re-initialises.
PerceptionOptions session7(PerceptionOptions o) {
  o.mbtDepthShiftTolerance_m = 0.0;
  o.mbtCompareBeforeReinit = false;
  o.mbtMinDetectionVisibleFraction = 0.0;
  o.mbtMinDetectionSupport = 0.0;
  return o;
}

/// Session 8 before the re-initialisation gate: any detection (or kept
/// tracked pose) re-initialises the tracker, however hidden.
PerceptionOptions noGate(PerceptionOptions o) {
  o.mbtMinDetectionVisibleFraction = 0.0;
  o.mbtMinDetectionSupport = 0.0;
  return o;
}

// Every stress variant of the development frames 0-29 with the defaults
// (`srp perceive --hand none --moving-camera`): within 1 cm / 5 deg of the
// scene-derived pose in every frame where the cube is in view; the board
// figures are printed (that reference is 8-21 mm off in frames 10-12, 16-21).
// Reached (README "session 8"): worst 7.1 mm (reversed), every other variant
// <= 5.9 mm; hand passing: no hidden frame reports a wrong pose (before the
// re-initialisation gate, mbtMinDetectionVisibleFraction, frame 11 did: the
// detector took another object 21 cm away while the cube was hidden). "Depth out of step" is the test that a re-initialisation does not
// take a worse detection: in frames 15-16 the depth is shifted 40 px (3 cm),
// the depth check fails on the (right) tracked pose and the frame's detection,
// made on that depth, is 3 cm off; re-initialising from it (session 7's
// handling) puts frames 15-16 29.6 mm off, the colour comparison keeps the
// tracked pose (worst 5.6 mm).
constexpr double kMaxWorstToScene_m = 0.008;
constexpr int kMaxWrongWhileHidden = 0;  // with the gate; 1 without (RealCubeStress.GateStopsAHiddenCubeBeingDetected)
// Every third frame (3x the apparent motion): worst to the scene-derived pose 5.2 mm.
constexpr double kMaxWorstToSceneEveryThird_m = 0.006;

TEST_F(RealCubeStress, DevelopmentVariantsStayOnTheSceneDerivedPose) {
  for (const Variant& v : variants(0, 29)) {
    const Figures f = run(v, shippedOptions());
    report("defaults", v.name, f);
    EXPECT_EQ(f.withinScene, f.frames) << v.name;
    EXPECT_LE(f.worstScene_m(), kMaxWorstToScene_m) << v.name;
    EXPECT_LE(f.wrongWhileHidden, kMaxWrongWhileHidden) << v.name;
    EXPECT_EQ(f.detected, f.frames) << v.name;
    if (v.name == "every 3. frame") EXPECT_LE(f.worstScene_m(), kMaxWorstToSceneEveryThird_m);
    if (!v.depthOutOfStep.empty()) {
      // The session-7 handling does take the worse detection here: the variant can fail.
      const Figures old = run(v, session7(shippedOptions()));
      report("session 7 loss handling", v.name, old);
      EXPECT_GT(old.worstScene_m(), kMaxWorstToScene_m) << "the variant no longer stresses the re-initialisation";
    }
  }
}

// The re-initialisation gate (PerceptionOptions::mbtMinDetectionVisibleFraction):
// while the synthetic hand hides the cube (dev frames 10-13), no detection
// more than 1 cm off re-initialises the tracker; without the gate frame 11
// takes another object 21 cm away. The visible frames keep every detection.
TEST_F(RealCubeStress, GateStopsAHiddenCubeBeingDetected) {
  const auto all = variants(0, 29);
  const auto v = std::find_if(all.begin(), all.end(), [](const Variant& x) { return !x.occluded.empty(); });
  ASSERT_NE(v, all.end());
  const Figures gated = run(*v, shippedOptions());
  const Figures ungated = run(*v, noGate(shippedOptions()));
  report("defaults (gate)", v->name, gated);
  report("no gate", v->name, ungated);
  EXPECT_LE(gated.wrongWhileHidden, kMaxWrongWhileHidden);
  EXPECT_GT(ungated.wrongWhileHidden, kMaxWrongWhileHidden) << "the variant no longer stresses the gate";
  EXPECT_EQ(gated.detected, gated.frames);
  EXPECT_EQ(gated.withinScene, gated.frames);
}

// Exploration (prints only; README tables): the loss handling of session 7
// against this session's on the variants of frames 0-29, or of frames 30-49
// (own check) with SRP_CUBE_STRESS_RANGE=own. SRP_CUBE_STRESS_VARIANT=<part
// of a name> runs one variant, SRP_CUBE_STRESS_FRAMES=1 prints every frame.
TEST_F(RealCubeStress, DISABLED_ExploreVariants) {
  std::vector<std::pair<std::string, PerceptionOptions>> configs;
  configs.emplace_back("session 7 loss handling", session7(shippedOptions()));
  PerceptionOptions o = session7(shippedOptions());
  o.mbtCompareBeforeReinit = true;
  configs.emplace_back("compare only", o);
  o = session7(shippedOptions());
  o.mbtDepthShiftTolerance_m = 0.005;
  configs.emplace_back("shift 5 mm only", o);
  configs.emplace_back("no gate (shift 5 + compare)", noGate(shippedOptions()));
  configs.emplace_back("defaults (+ gate)", shippedOptions());
  if (std::getenv("SRP_CUBE_STRESS_GATE")) {  // "<visible fraction>,<support>" (exploration)
    o = shippedOptions();
    std::sscanf(std::getenv("SRP_CUBE_STRESS_GATE"), "%lf,%lf", &o.mbtMinDetectionVisibleFraction,
                &o.mbtMinDetectionSupport);
    configs.emplace_back("gate " + std::string(std::getenv("SRP_CUBE_STRESS_GATE")), o);
  }
  if (std::getenv("SRP_CUBE_STRESS_KEEP_MIN")) {
    o = shippedOptions();
    o.mbtKeepMinCoverage = std::atof(std::getenv("SRP_CUBE_STRESS_KEEP_MIN"));
    configs.emplace_back("defaults, keep min " + std::string(std::getenv("SRP_CUBE_STRESS_KEEP_MIN")), o);
  }
  const char* range = std::getenv("SRP_CUBE_STRESS_RANGE");
  const bool own = range && std::string(range) == "own";
  const bool print = std::getenv("SRP_CUBE_STRESS_FRAMES") != nullptr;
  const char* only = std::getenv("SRP_CUBE_STRESS_VARIANT");
  for (const auto& v : own ? variants(30, 49) : variants(0, 29))
    if (!only || v.name.find(only) != std::string::npos)
      for (const auto& [name, options] : configs) report(name, v.name, run(v, options, print));
}

// Exploration (prints only): can the colour edges tell the depth's offset?
// Per frame, the tracked pose (defaults) moved along its ray / sideways in
// 0.5 mm steps; the shift with the least edge distance vs the scene-derived
// pose's offset from the tracked one along the same direction.
TEST_F(RealCubeStress, DISABLED_ExploreEdgeOffset) {
  const auto& all = *frames_;
  const auto scenes = testing::storedScenePoses();
  std::vector<rawlog::RgbdFrame> frames(all.begin(), all.begin() + 30);
  const PerceptionResult r = perceiveFrames(frames, *catalogue_, shippedOptions());
  const kb::TriangleMesh mesh = kb::TriangleMesh::load(testing::rbtFolder() + "/cube.obj");
  const ModelBasedTracker edges(mesh, all[0].intrinsics, ModelBasedTracker::Options{});
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const core::Pose3 X = r.objects.front().samples[i].X_camera_object;
    const Eigen::Vector3d ray = X.translation().normalized();
    const Eigen::Vector3d side = ray.cross(Eigen::Vector3d::UnitY()).normalized();
    const Eigen::Vector3d up = side.cross(ray).normalized();
    std::printf("[ offset   ] %2zu", i);
    for (const Eigen::Vector3d& dir : {ray, side, up}) {
      double best = 1e9, bestShift = 0;
      for (int k = -20; k <= 20; ++k) {
        core::Pose3 Y = X;
        Y.translation() += dir * (0.0005 * k);
        const double e = edges.edgeDistance_px(frames[i], Y);
        if (e < best) {
          best = e;
          bestShift = 0.0005 * k;
        }
      }
      const double truth = (scenes[i].translation() - X.translation()).dot(dir);
      std::printf("   edges %+5.1f mm scene %+5.1f mm", bestShift * 1e3, truth * 1e3);
    }
    std::printf("\n");
  }
}

// Exploration (prints only): CPU time per frame of the whole perception of
// frames 0-49 (moving camera, MBT), defaults vs session 7's loss handling.
TEST_F(RealCubeStress, DISABLED_ExploreCost) {
  auto cpu_s = [] {
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
  };
  for (int repeat = 0; repeat < 3; ++repeat)
    for (const auto& [name, o] : {std::make_pair(std::string("defaults"), shippedOptions()),
                                  std::make_pair(std::string("session 7"), session7(shippedOptions()))}) {
      const double t0 = cpu_s();
      perceiveFrames(*frames_, *catalogue_, o);
      std::printf("[ cost     ] %-10s %.1f ms CPU per frame (frames 0-49)\n", name.c_str(),
                  (cpu_s() - t0) * 1e3 / static_cast<double>(frames_->size()));
    }
}

}  // namespace
}  // namespace srp::perception
