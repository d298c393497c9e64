#include "srp/kb/KnowledgeBase.h"
#include "srp/perception/ObjectPoseFitter.h"

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>
#include <opencv2/imgcodecs.hpp>

#include "RealData.h"
#include "srp/core/Error.h"
#include "srp/perception/AprilTagDetector.h"
#include "srp/perception/DepthCloud.h"
#include "srp/perception/ObjectDetector.h"
#include "srp/perception/RgbdFolder.h"
#include "srp/perception/TagBoard.h"

namespace srp::perception {
namespace {

// Issue 5 acceptance on the real recording: cube within 1 cm and 5 deg.
constexpr double kCubePositionTol_m = 0.01;
constexpr double kCubeAngleTol_rad = 5.0 * M_PI / 180.0;
constexpr double kCubeHalfSide_m = 0.0425;

using testing::cubeAngleError;

ObjectModel cubeModel() {
  // cube.obj is centred; the model frame is its bottom-face centre.
  return ObjectModel::fromMesh("cube", kb::TriangleMesh::load(testing::rbtFolder() + "/cube.obj"));
}

TEST(ObjectModel, CubeFromObjHasSizeAndFourFoldSymmetry) {
  const ObjectModel m = cubeModel();
  EXPECT_NEAR(m.dimensions_m.x(), 0.085, 1e-6);
  EXPECT_NEAR(m.dimensions_m.z(), 0.085, 1e-6);
  EXPECT_NEAR(m.yawSymmetry_rad, M_PI / 2, 1e-9);
  EXPECT_GT(m.surface.size(), 500u);
  EXPECT_NEAR(m.X_model_mesh.translation().z(), kCubeHalfSide_m, 1e-9) << "the mesh's centre, half a side up";
  EXPECT_NEAR(m.X_model_mesh.translation().head<2>().norm(), 0.0, 1e-9);
}

TEST(ObjectModel, CatalogueShapesHaveTheirSymmetry) {
  const auto cat = kb::loadCatalogue(core::ObjectCatalogue::defaultPath());
  EXPECT_NEAR(ObjectModel::fromCatalogue(cat.at("cuboid")).yawSymmetry_rad, M_PI, 1e-9);
  EXPECT_NEAR(ObjectModel::fromCatalogue(cat.at("star")).yawSymmetry_rad, 2 * M_PI / 5, 1e-9);
  EXPECT_NEAR(ObjectModel::fromCatalogue(cat.at("octagon")).yawSymmetry_rad, M_PI / 4, 1e-9);
  const ObjectModel box = ObjectModel::fromCatalogue(cat.at("gray box"));
  constexpr double kStlFloatTol_m = 1e-6;  // meshes are float STL once `srp kb build` made them
  EXPECT_NEAR(box.dimensions_m.x(), 0.22, kStlFloatTol_m);
  EXPECT_NEAR(box.dimensions_m.z(), 0.06, kStlFloatTol_m);
}

// Two parts in one place: the less confident is named; parts side by side,
// stacked or in a container are not.
TEST(ObjectDetector, OverlappingPartsLoseTheLessConfident) {
  const auto cat = kb::loadCatalogue(core::ObjectCatalogue::defaultPath());
  const ObjectDetector detector(ObjectDetector::modelsFromCatalogue(cat, {"star", "octagon", "cuboid", "gray box"}));
  Plane plane;  // camera looking straight down on a table 0.8 m away
  plane.n = Eigen::Vector3d(0, 0, -1);
  plane.d = 0.8;
  const core::Pose3 X_camera_plane = plane.X_camera_plane();
  auto at = [&](const std::string& name, double x, double y, double z, double confidence) {
    ObjectDetection d;
    d.key = name;
    core::Pose3 X_plane_object = core::Pose3::Identity();
    X_plane_object.translation() = Eigen::Vector3d(x, y, z);
    d.X_camera_object = X_camera_plane * X_plane_object;
    d.confidence = confidence;
    return d;
  };
  // The star (diagonal 7.1 cm) read on the octagon's place, 1 cm off: it goes.
  EXPECT_EQ(detector.overlappingParts({at("octagon", 0.10, 0.0, 0.0, 0.9), at("star", 0.11, 0.0, 0.0, 0.42)}, plane),
            std::set<std::string>{"star"});
  EXPECT_EQ(detector.overlappingParts({at("octagon", 0.10, 0.0, 0.0, 0.3), at("star", 0.11, 0.0, 0.0, 0.42)}, plane),
            std::set<std::string>{"octagon"});
  // Side by side (3 cm apart: more than half the octagon's 5.7 cm diagonal).
  EXPECT_TRUE(detector.overlappingParts({at("octagon", 0.10, 0.0, 0.0, 0.9), at("star", 0.13, 0.0, 0.0, 0.4)}, plane).empty());
  // Stacked: the star on the 2.5 cm high octagon.
  EXPECT_TRUE(detector.overlappingParts({at("octagon", 0.10, 0.0, 0.0, 0.9), at("star", 0.10, 0.0, 0.025, 0.4)}, plane).empty());
  // A part in a container, at its centre: a container is not a part.
  EXPECT_TRUE(detector.overlappingParts({at("gray box", 0.10, 0.0, 0.0, 0.9), at("star", 0.10, 0.0, 0.003, 0.4)}, plane).empty());
}

// Acceptance (issue 5): the cube found from its CAD model alone on frame 0
// within 1 cm and 5 deg of the stored pose, and in frames 1-9 consistently:
// there the reference is the frame-0 pose carried by the board's motion
// (X_ck_cube = X_ck_board X_c0_board^-1 X_c0_cube), since the camera moves a little.
TEST(ObjectDetector, RealCubeFromCadModelAlone) {
  const auto frames = readRgbdFolder(testing::rbtFolder(), 10);
  const auto boards = testing::storedBoardPoses();
  const core::Pose3 X_c0_cube = testing::storedCubePoseFrame0();
  ObjectDetector detector({cubeModel()});
  core::Pose3 X_centre_offset = core::Pose3::Identity();
  X_centre_offset.translation().z() = kCubeHalfSide_m;
  double worstPos_m = 0.0, worstAngle_rad = 0.0;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const auto detections = detector.detect(frames[i]);
    ASSERT_FALSE(detections.empty()) << "frame " << i;
    const ObjectDetection& cube = detections.front();
    const core::Pose3 X_camera_cube = cube.X_camera_object * X_centre_offset;
    const core::Pose3 expected = boards[i] * boards[0].inverse() * X_c0_cube;
    const double dp = core::translationDistance(X_camera_cube, expected);
    const double da = cubeAngleError(X_camera_cube.linear(), expected.linear());
    EXPECT_LT(dp, kCubePositionTol_m) << "frame " << i;
    EXPECT_LT(da, kCubeAngleTol_rad) << "frame " << i;
    EXPECT_GT(cube.confidence, 0.5) << "frame " << i;
    worstPos_m = std::max(worstPos_m, dp);
    worstAngle_rad = std::max(worstAngle_rad, da);
    std::printf("[ figures  ] cube frame %zu: %.2f mm, %.2f deg, confidence %.2f\n", i, dp * 1e3, da * 180 / M_PI,
                cube.confidence);
  }
  std::printf("[ figures  ] cube worst of 10 frames: %.2f mm, %.2f deg\n", worstPos_m * 1e3, worstAngle_rad * 180 / M_PI);
}

}  // namespace
}  // namespace srp::perception
