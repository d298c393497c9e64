// ModelBasedTracker: the CAO model built from a CAD mesh, and tracking on the
// real RealSense frames 0-9 of datasets/real/visp-rbt-cube (development
// frames: the camera barely moves) from the stored frame-0 pose.
#include "srp/perception/ModelBasedTracker.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <sstream>

#include "RealData.h"
#include "srp/core/Error.h"
#include "srp/perception/RgbdFolder.h"

namespace srp::perception {
namespace {

// Tracked vs the board-derived reference, frames 1-9 (modulo the cube's
// rotations). KLT on the colour image stays on the reference (0.1-0.7 mm in
// frames 1-8, 2.5 mm in frame 9 as the camera starts to move); dense depth
// pulls the pose 4-6 mm / 2 deg off it at once: the depth image and the
// colour-derived reference disagree by that much on this sensor (README).
constexpr double kKltPositionTol_m = 0.003;
constexpr double kKltAngleTol_rad = 0.5 * M_PI / 180.0;
constexpr double kDepthPositionTol_m = 0.007;
constexpr double kDepthAngleTol_rad = 3.0 * M_PI / 180.0;

TEST(ModelBasedTracker, CaoModelMergesEachCoplanarPairOfTrianglesIntoOneFace) {
  const kb::TriangleMesh mesh = kb::TriangleMesh::load(testing::rbtFolder() + "/cube.obj");
  ASSERT_EQ(mesh.size(), 12u);
  std::istringstream cao(ModelBasedTracker::caoModel(mesh));
  std::string line;
  std::getline(cao, line);
  EXPECT_EQ(line, "V1");
  std::getline(cao, line);  // # 3D Points
  int points = 0;
  cao >> points;
  EXPECT_EQ(points, 8);  // the soup's 36 corners are 8 vertices
  for (int i = 0; i < points; ++i) {
    double x, y, z;
    cao >> x >> y >> z;
    EXPECT_NEAR(std::abs(x), 0.0425, 1e-6);
  }
  std::string rest((std::istreambuf_iterator<char>(cao)), std::istreambuf_iterator<char>());
  const auto at = rest.find("# Faces from 3D points\n");
  ASSERT_NE(at, std::string::npos);
  std::istringstream faces(rest.substr(at + 23));
  int nFaces = 0;
  faces >> nFaces;
  EXPECT_EQ(nFaces, 6);  // quads, no diagonals for the edge tracker
  for (int i = 0; i < nFaces; ++i) {
    int n = 0;
    faces >> n;
    EXPECT_EQ(n, 4);
    for (int k = 0; k < n; ++k) faces >> points;
  }
}

TEST(ModelBasedTracker, RejectsAnEmptyMeshAndAllFeaturesOff) {
  core::CameraIntrinsics k{600, 600, 320, 240, 640, 480};
  EXPECT_THROW(ModelBasedTracker(kb::TriangleMesh{}, k, {}), core::InvalidInputError);
  ModelBasedTracker::Options none;
  none.useKlt = none.useEdges = none.useDepthDense = false;
  const kb::TriangleMesh mesh = kb::TriangleMesh::load(testing::rbtFolder() + "/cube.obj");
  EXPECT_THROW(ModelBasedTracker(mesh, k, none), core::InvalidInputError);
}

TEST(ModelBasedTracker, FollowsTheRealCubeFromItsStoredPoseThroughFrames1To9) {
  const auto frames = readRgbdFolder(testing::rbtFolder());
  ASSERT_GE(frames.size(), 10u) << "datasets/real/visp-rbt-cube should hold frames 0-49";
  const auto boards = testing::storedBoardPoses();
  const core::Pose3 X_c0_cube = testing::storedCubePoseFrame0();
  const kb::TriangleMesh mesh = kb::TriangleMesh::load(testing::rbtFolder() + "/cube.obj");
  for (const bool depth : {false, true}) {
    ModelBasedTracker::Options o;
    o.useDepthDense = depth;
    ModelBasedTracker tracker(mesh, frames[0].intrinsics, o);
    tracker.initialise(frames[0], X_c0_cube);
    for (std::size_t i = 1; i < 10; ++i) {
      const ModelBasedTracker::Result r = tracker.track(frames[i]);
      ASSERT_TRUE(r.tracked) << "frame " << i << (depth ? " (KLT + dense depth)" : " (KLT)");
      const core::Pose3 truth = testing::trueCubePose(boards, X_c0_cube, i);
      std::printf("[ figures  ] %s frame %zu: %.2f mm, %.2f deg\n", depth ? "KLT + dense depth" : "KLT", i,
                  core::translationDistance(r.X_camera_mesh, truth) * 1e3,
                  testing::cubeAngleError(r.X_camera_mesh.linear(), truth.linear()) * 180 / M_PI);
      EXPECT_LT(core::translationDistance(r.X_camera_mesh, truth), depth ? kDepthPositionTol_m : kKltPositionTol_m)
          << "frame " << i;
      EXPECT_LT(testing::cubeAngleError(r.X_camera_mesh.linear(), truth.linear()),
                depth ? kDepthAngleTol_rad : kKltAngleTol_rad)
          << "frame " << i;
      EXPECT_GE(r.kltPoints, o.minKltPoints);
      if (depth) EXPECT_GE(r.depthFeatures, o.minDepthFeatures);
    }
  }
}

// edgeDistance_px on the real frames 0-8 (camera still, development): the
// stored (colour-derived) pose lies on the image's edges (notebook: 2.2 px
// median; here 2.0-2.4 px), the same pose 1 cm sideways is farther in every
// frame -- but only by 0.5-0.7 px: the cube's printed texture has edges
// everywhere, so the measure orders poses weakly (README, session 8). Depth
// 25 cm in front of every edge (a hand) leaves no evidence: the truncation.
constexpr double kMaxEdgeDistanceOnThePart_px = 2.6;
constexpr double kMinEdgeDistanceGain_px = 0.4;  // 1 cm sideways: at least this much farther

TEST(ModelBasedTracker, EdgeDistanceIsSmallAtTheStoredPoseAndGrowsOffIt) {
  const auto frames = readRgbdFolder(testing::rbtFolder());
  ASSERT_GE(frames.size(), 9u);
  const auto boards = testing::storedBoardPoses();
  const core::Pose3 X_c0_cube = testing::storedCubePoseFrame0();
  const kb::TriangleMesh mesh = kb::TriangleMesh::load(testing::rbtFolder() + "/cube.obj");
  const ModelBasedTracker tracker(mesh, frames[0].intrinsics, ModelBasedTracker::Options{});
  for (std::size_t i = 0; i <= 8; ++i) {
    const core::Pose3 truth = testing::trueCubePose(boards, X_c0_cube, i);
    core::Pose3 off = truth;
    off.translation().x() += 0.01;
    const double on_px = tracker.edgeDistance_px(frames[i], truth), off_px = tracker.edgeDistance_px(frames[i], off);
    std::printf("[ figures  ] frame %zu: edge distance %.2f px at the stored pose, %.2f px 1 cm sideways\n", i, on_px,
                off_px);
    EXPECT_LT(on_px, kMaxEdgeDistanceOnThePart_px) << "frame " << i;
    EXPECT_GT(off_px - on_px, kMinEdgeDistanceGain_px) << "frame " << i;
  }
  // Hidden: depth 25 cm in front of every edge -> no sample left -> the truncation.
  rawlog::RgbdFrame hidden = frames[0];
  hidden.depth_m = cv::Mat(frames[0].depth_m.size(), CV_32FC1, cv::Scalar(0.25f));
  EXPECT_DOUBLE_EQ(tracker.edgeDistance_px(hidden, X_c0_cube), ModelBasedTracker::Options{}.supportTruncation_px);
}

}  // namespace
}  // namespace srp::perception
