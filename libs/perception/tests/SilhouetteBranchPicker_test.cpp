#include "srp/kb/KnowledgeBase.h"
#include "srp/perception/SilhouetteBranchPicker.h"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "srp/core/ObjectCatalogue.h"
#include "srp/perception/ObjectModel.h"
#include "srp/perception/ObjectPoseFitter.h"

namespace srp::perception {
namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;

ObjectModel model(const std::string& name) {
  static const auto c = kb::loadCatalogue(core::ObjectCatalogue::defaultPath());
  return ObjectModel::fromCatalogue(c.at(name));
}

/// Ray-cast image of a part's top face (yellow) on a blue floor, camera
/// looking straight down from 0.84 m: each pixel centre's ray against the top
/// triangles (independent of the picker's polygon filling).
cv::Mat renderTop(const ObjectModel& m, const core::Pose3& X_camera_object, const CameraModel& camera,
                  std::vector<cv::Point>& partPixels) {
  const auto& k = camera.intrinsics();
  cv::Mat img(k.height_px, k.width_px, CV_8UC3, cv::Scalar(200, 80, 40));
  const core::Pose3 X_object_camera = X_camera_object.inverse();
  const double top = m.dimensions_m.z();
  for (int v = 0; v < k.height_px; ++v)
    for (int u = 0; u < k.width_px; ++u) {
      const Eigen::Vector3d ray = X_object_camera.linear() * Eigen::Vector3d((u - k.cx_px) / k.fx_px, (v - k.cy_px) / k.fy_px, 1.0);
      const Eigen::Vector3d o = X_object_camera.translation();
      const double s = (top - o.z()) / ray.z();
      const Eigen::Vector2d p = (o + s * ray).head<2>();
      bool inside = false;
      for (const auto& t : m.mesh.triangles()) {
        const Eigen::Vector3d &a = t[0], &b = t[1], &c = t[2];
        if (std::min({a.z(), b.z(), c.z()}) < top - 1e-6) continue;
        const auto cross = [](const Eigen::Vector2d& x, const Eigen::Vector2d& y) { return x.x() * y.y() - x.y() * y.x(); };
        const double d1 = cross(b.head<2>() - a.head<2>(), p - a.head<2>());
        const double d2 = cross(c.head<2>() - b.head<2>(), p - b.head<2>());
        const double d3 = cross(a.head<2>() - c.head<2>(), p - c.head<2>());
        if ((d1 >= 0 && d2 >= 0 && d3 >= 0) || (d1 <= 0 && d2 <= 0 && d3 <= 0)) {
          inside = true;
          break;
        }
      }
      if (inside) {
        img.at<cv::Vec3b>(v, u) = cv::Vec3b(25, 215, 240);
        partPixels.emplace_back(u, v);
      }
    }
  return img;
}

TEST(SilhouetteBranchPicker, OnlyTheStarHasOffCentreSymmetry) {
  EXPECT_TRUE(ObjectPoseFitter(model("star")).hasOffCentreSymmetry());
  for (const char* name : {"cuboid", "octagon", "parallelogram"})
    EXPECT_FALSE(ObjectPoseFitter(model(name)).hasOffCentreSymmetry()) << name;
}

TEST(SilhouetteBranchPicker, StarTurnWithTheRightOriginFromTheColourOutline) {
  const ObjectModel star = model("star");
  const ObjectPoseFitter fitter(star);
  const CameraModel camera(core::CameraIntrinsics{607.0, 607.0, 321.4, 241.9, 640, 480});
  core::Pose3 X_camera_table = core::Pose3::Identity();  // table plane facing the camera
  X_camera_table.linear() = Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitX()).toRotationMatrix();
  X_camera_table.translation() = Eigen::Vector3d(-0.16, 0.015, 0.84);
  constexpr double kOriginTol_m = 5e-4;
  for (double yaw_deg : {131.4, 17.0, -60.0}) {
    core::Pose3 X_table_star = core::Pose3::Identity();
    X_table_star.linear() = Eigen::AngleAxisd(yaw_deg * kDeg, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    const core::Pose3 truth = X_camera_table * X_table_star;
    std::vector<cv::Point> pixels;
    const cv::Mat colour = renderTop(star, truth, camera, pixels);
    ASSERT_GT(pixels.size(), 500u);
    // What depth would give: the truth turned by two fifths about the star's centre.
    const core::Pose3 fitted = fitter.symmetricBranches(truth)[2];
    EXPECT_GT(core::translationDistance(fitted, truth), 3e-3) << "the turn moves the origin (the test's premise)";
    const auto branches = fitter.symmetricBranches(fitted);
    ASSERT_EQ(branches.size(), 5u);
    std::vector<double> iou;
    const auto k = SilhouetteBranchPicker().pick(star.mesh, branches, pixels, colour,
                                                 camera, &iou);
    ASSERT_TRUE(k.has_value()) << yaw_deg;
    EXPECT_LT(core::translationDistance(branches[*k], truth), kOriginTol_m) << yaw_deg << " deg";
    EXPECT_LT(core::rotationAngleBetween(branches[*k].linear(), truth.linear()), 0.1 * kDeg) << yaw_deg << " deg";
  }
}

TEST(SilhouetteBranchPicker, PartialViewIsInconclusive) {
  const ObjectModel star = model("star");
  const ObjectPoseFitter fitter(star);
  const CameraModel camera(core::CameraIntrinsics{607.0, 607.0, 321.4, 241.9, 640, 480});
  core::Pose3 truth = core::Pose3::Identity();
  truth.linear() = Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitX()).toRotationMatrix();
  truth.translation() = Eigen::Vector3d(0.0, 0.0, 0.84);
  std::vector<cv::Point> pixels;
  cv::Mat colour = renderTop(star, truth, camera, pixels);
  // A hand (skin) over the left half of the star.
  const cv::Rect box = cv::boundingRect(pixels);
  cv::rectangle(colour, cv::Rect(box.x - 5, box.y - 5, box.width / 2 + 5, box.height + 10), cv::Scalar(120, 150, 210), cv::FILLED);
  std::vector<cv::Point> visible;
  for (const auto& p : pixels)
    if (p.x >= box.x + box.width / 2) visible.push_back(p);
  EXPECT_FALSE(SilhouetteBranchPicker().pick(star.mesh, fitter.symmetricBranches(truth), visible,
                                             colour, camera).has_value());
}

TEST(SilhouetteBranchPicker, NoColourNoAnswer) {
  const ObjectModel star = model("star");
  const CameraModel camera(core::CameraIntrinsics{607.0, 607.0, 321.4, 241.9, 640, 480});
  EXPECT_FALSE(SilhouetteBranchPicker().pick(star.mesh, {core::Pose3::Identity()}, {{1, 1}}, cv::Mat(),
                                             camera).has_value());
}

}  // namespace
}  // namespace srp::perception
