#include "srp/kb/KnowledgeBase.h"
#include "srp/perception/EdgeYawRefiner.h"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "srp/core/ObjectCatalogue.h"
#include "srp/kb/ShapeMeshes.h"

namespace srp::perception {
namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;

const core::ObjectCatalogue& catalogue() {
  static const auto c = kb::loadCatalogue(core::ObjectCatalogue::defaultPath());
  return c;
}

/// A camera 0.85 m above a table, looking straight down.
struct TopDownScene {
  CameraModel camera{core::CameraIntrinsics{607.0, 607.0, 321.4, 241.9, 640, 480}};
  Plane table;
  TopDownScene() {
    table.n = {0, 0, -1};
    table.d = 0.85;
  }
  core::Pose3 objectAt(double x_m, double y_m, double yaw_rad) const {
    core::Pose3 X_plane_object = core::Pose3::Identity();
    X_plane_object.translation() = Eigen::Vector3d(x_m, y_m, 0.0);
    X_plane_object.linear() = Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    return table.X_camera_plane() * X_plane_object;
  }
  /// The model's top face, filled (anti-aliased) in `rgb` on `background`; its pixels.
  cv::Mat render(const ObjectModel& model, const core::Pose3& X_camera_object, const cv::Scalar& bgr,
                 const cv::Scalar& backgroundBgr, std::vector<cv::Point>& pixels) const {
    const kb::TriangleMesh mesh = kb::makeClassMesh(catalogue().at(model.name));
    std::vector<cv::Point> top;
    for (const auto& t : mesh.triangles())
      for (const Eigen::Vector3d& v : t)
        if (std::abs(v.z() - model.dimensions_m.z()) < 1e-9) {
          const Eigen::Vector2d px = camera.cameraToPixel(X_camera_object * v);
          top.emplace_back(static_cast<int>(std::lround(px.x() * 16)), static_cast<int>(std::lround(px.y() * 16)));
        }
    std::vector<cv::Point> hull;
    cv::convexHull(top, hull);
    cv::Mat image(480, 640, CV_8UC3, backgroundBgr), mask(480, 640, CV_8U, cv::Scalar(0));
    cv::fillConvexPoly(image, hull, bgr, cv::LINE_AA, 4);  // 4 fractional bits: sub-pixel corners
    cv::fillConvexPoly(mask, hull, cv::Scalar(255), cv::LINE_8, 4);
    cv::findNonZero(mask, pixels);
    return image;
  }
};

double planeYaw(const Plane& plane, const core::Pose3& X_camera_object) {
  const core::Pose3 X = plane.X_camera_plane().inverse() * X_camera_object;
  return std::atan2(X.linear()(1, 0), X.linear()(0, 0));
}

TEST(EdgeYawRefiner, OrderFromTheOutline) {
  EXPECT_EQ(EdgeYawRefiner(ObjectModel::fromCatalogue(catalogue().at("octagon"))).order(), 8);
  EXPECT_EQ(EdgeYawRefiner(ObjectModel::fromCatalogue(catalogue().at("cuboid"))).order(), 4);
  EXPECT_EQ(EdgeYawRefiner(ObjectModel::fromCatalogue(catalogue().at("star"))).order(), 0);
  EXPECT_EQ(EdgeYawRefiner(ObjectModel::fromCatalogue(catalogue().at("parallelogram"))).order(), 0);
}

// An orange octagon on the blue box floor, the fit 7 deg off: the edges bring
// the yaw back within 1 deg; the same with a grey floor of the octagon's
// brightness (the colour structure tensor sees chroma edges).
TEST(EdgeYawRefiner, OctagonYawFromColourEdges) {
  constexpr double kYawTol_rad = 1.0 * kDeg, kPositionTol_m = 1e-9;
  const TopDownScene scene;
  const ObjectModel octagon = ObjectModel::fromCatalogue(catalogue().at("octagon"));
  const EdgeYawRefiner refiner(octagon);
  for (const cv::Scalar& floor : {cv::Scalar(199, 71, 31), cv::Scalar(150, 150, 150)}) {
    for (double trueYaw : {3.0 * kDeg, 17.0 * kDeg, 31.0 * kDeg}) {
      const core::Pose3 truth = scene.objectAt(0.05, -0.03, trueYaw);
      std::vector<cv::Point> pixels;
      const cv::Mat image = scene.render(octagon, truth, cv::Scalar(20, 133, 242), floor, pixels);
      const core::Pose3 fitted = scene.objectAt(0.05, -0.03, trueYaw + 7.0 * kDeg);
      const auto refined = refiner.refine(fitted, pixels, image, scene.camera, scene.table);
      ASSERT_TRUE(refined.has_value()) << "yaw " << trueYaw / kDeg;
      const double err = std::remainder(planeYaw(scene.table, *refined) - trueYaw, 45.0 * kDeg);
      EXPECT_LT(std::abs(err), kYawTol_rad) << "yaw " << trueYaw / kDeg << " deg: " << err / kDeg << " deg off";
      EXPECT_LT((refined->translation() - fitted.translation()).norm(), kPositionTol_m);  // turned in place
    }
  }
}

// A green parallelogram (two side directions, not m-fold regular) on the
// blue floor, the fit 4 deg off either way: the edge normals bring it back.
TEST(EdgeYawRefiner, ParallelogramYawFromItsTwoEdgeDirections) {
  constexpr double kYawTol_rad = 0.5 * kDeg, kPositionTol_m = 1e-9;
  const TopDownScene scene;
  const ObjectModel parallelogram = ObjectModel::fromCatalogue(catalogue().at("parallelogram"));
  const EdgeYawRefiner refiner(parallelogram);
  ASSERT_EQ(refiner.sideNormals_rad().size(), 2u);
  EXPECT_TRUE(EdgeYawRefiner(ObjectModel::fromCatalogue(catalogue().at("star"))).sideNormals_rad().empty())
      << "ten short edges: depth gives the star's yaw";
  for (double trueYaw : {5.0 * kDeg, 71.0 * kDeg, 150.0 * kDeg}) {
    for (double off : {-4.0 * kDeg, 4.0 * kDeg}) {
      const core::Pose3 truth = scene.objectAt(-0.04, 0.02, trueYaw);
      std::vector<cv::Point> pixels;
      const cv::Mat image = scene.render(parallelogram, truth, cv::Scalar(77, 173, 46), cv::Scalar(199, 71, 31), pixels);
      const core::Pose3 fitted = scene.objectAt(-0.04, 0.02, trueYaw + off);
      const auto refined = refiner.refine(fitted, pixels, image, scene.camera, scene.table);
      ASSERT_TRUE(refined.has_value()) << "yaw " << trueYaw / kDeg;
      const double err = std::remainder(planeYaw(scene.table, *refined) - trueYaw, 180.0 * kDeg);
      EXPECT_LT(std::abs(err), kYawTol_rad) << "yaw " << trueYaw / kDeg << " deg: " << err / kDeg << " deg off";
      EXPECT_LT((refined->translation() - fitted.translation()).norm(), kPositionTol_m);
    }
  }
}

TEST(EdgeYawRefiner, NoEdgesOrTooLargeACorrectionLeaveThePose) {
  const TopDownScene scene;
  const ObjectModel octagon = ObjectModel::fromCatalogue(catalogue().at("octagon"));
  const EdgeYawRefiner refiner(octagon);
  const core::Pose3 truth = scene.objectAt(0.0, 0.0, 10.0 * kDeg);
  std::vector<cv::Point> pixels;
  scene.render(octagon, truth, cv::Scalar(20, 133, 242), cv::Scalar(199, 71, 31), pixels);
  const cv::Mat flat(480, 640, CV_8UC3, cv::Scalar(100, 100, 100));
  EXPECT_FALSE(refiner.refine(truth, pixels, flat, scene.camera, scene.table).has_value());
  EXPECT_FALSE(refiner.refine(truth, pixels, cv::Mat(), scene.camera, scene.table).has_value());
  // A cuboid 30 deg off is beyond maxCorrection: distrusted, not "corrected" to a wrong branch.
  const ObjectModel cuboid = ObjectModel::fromCatalogue(catalogue().at("cuboid"));
  const cv::Mat image = scene.render(cuboid, truth, cv::Scalar(36, 46, 217), cv::Scalar(199, 71, 31), pixels);
  EXPECT_FALSE(EdgeYawRefiner(cuboid).refine(scene.objectAt(0, 0, 40.0 * kDeg), pixels, image, scene.camera,
                                             scene.table).has_value());
}

}  // namespace
}  // namespace srp::perception
