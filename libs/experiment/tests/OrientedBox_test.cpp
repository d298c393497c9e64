#include "srp/experiment/OrientedBox.h"

#include <gtest/gtest.h>

#include <cmath>

#include "srp/core/Error.h"

using namespace srp::experiment;

namespace {

constexpr double kIoUTol = 1e-9;
constexpr double kAreaTol_px2 = 1e-6;

OrientedBox2d box(double cx, double cy, double w, double h, double angle_rad)
{
  const Eigen::Vector2d u(std::cos(angle_rad), std::sin(angle_rad)), v(-std::sin(angle_rad), std::cos(angle_rad));
  const Eigen::Vector2d c(cx, cy);
  return {{c - 0.5 * w * u - 0.5 * h * v, c + 0.5 * w * u - 0.5 * h * v, c + 0.5 * w * u + 0.5 * h * v,
           c - 0.5 * w * u + 0.5 * h * v}};
}

}  // namespace

TEST(OrientedBox, IoUOfKnownAxisAlignedOverlaps)
{
  EXPECT_NEAR(orientedBoxIoU(box(0, 0, 1, 1, 0), box(0, 0, 1, 1, 0)), 1.0, kIoUTol);
  // Shifted by half a side: intersection 1/2, union 3/2.
  EXPECT_NEAR(orientedBoxIoU(box(0, 0, 1, 1, 0), box(0.5, 0, 1, 1, 0)), 1.0 / 3.0, kIoUTol);
  // A 1x1 square inside a 2x2 one.
  EXPECT_NEAR(orientedBoxIoU(box(0, 0, 2, 2, 0), box(0.3, -0.2, 1, 1, 0)), 0.25, kIoUTol);
  // Touching at an edge, and apart.
  EXPECT_NEAR(orientedBoxIoU(box(0, 0, 1, 1, 0), box(1, 0, 1, 1, 0)), 0.0, kIoUTol);
  EXPECT_NEAR(orientedBoxIoU(box(0, 0, 1, 1, 0), box(5, 5, 1, 1, 0)), 0.0, kIoUTol);
}

TEST(OrientedBox, IoUOfRotatedSquareIsTheOctagonRatio)
{
  // A unit square and itself turned 45 deg: the overlap is a regular octagon
  // of area 2(sqrt 2 - 1); IoU = that / (2 - that) = 1/sqrt 2.
  const double octagon = 2.0 * (std::sqrt(2.0) - 1.0);
  const OrientedBox2d upright = box(0, 0, 1, 1, 0), turned = box(0, 0, 1, 1, M_PI / 4);
  EXPECT_NEAR(convexIntersectionArea({upright.corners_px.begin(), upright.corners_px.end()},
                                     {turned.corners_px.begin(), turned.corners_px.end()}),
              octagon, kAreaTol_px2);
  EXPECT_NEAR(orientedBoxIoU(box(0, 0, 1, 1, 0), box(0, 0, 1, 1, M_PI / 4)), 1.0 / std::sqrt(2.0), kIoUTol);
  // The same with the corners of one box in the other sense, and both boxes moved and turned together.
  OrientedBox2d clockwise = box(0, 0, 1, 1, M_PI / 4);
  std::swap(clockwise.corners_px[1], clockwise.corners_px[3]);
  EXPECT_NEAR(orientedBoxIoU(box(0, 0, 1, 1, 0), clockwise), 1.0 / std::sqrt(2.0), kIoUTol);
  EXPECT_NEAR(orientedBoxIoU(box(320, 240, 40, 40, 0.3), box(320, 240, 40, 40, 0.3 + M_PI / 4)), 1.0 / std::sqrt(2.0), 1e-6);
  // A 2x1 rectangle and the same turned 90 deg about its centre: overlap 1x1, union 3.
  EXPECT_NEAR(orientedBoxIoU(box(10, 10, 2, 1, 0.2), box(10, 10, 2, 1, 0.2 + M_PI / 2)), 1.0 / 3.0, kIoUTol);
}

TEST(OrientedBox, MinAreaBoxRecoversARotatedRectangle)
{
  const OrientedBox2d truth = box(100, 50, 30, 12, 0.4);
  std::vector<Eigen::Vector2d> points(truth.corners_px.begin(), truth.corners_px.end());
  points.push_back(truth.centre_px());                                        // interior points do not matter
  points.push_back(0.5 * (truth.corners_px[0] + truth.corners_px[2]) + Eigen::Vector2d(3, -1));
  const OrientedBox2d found = minAreaBox(points);
  EXPECT_NEAR(found.area_px2(), 30.0 * 12.0, kAreaTol_px2);
  EXPECT_NEAR(orientedBoxIoU(found, truth), 1.0, 1e-9);
  EXPECT_THROW(minAreaBox({}), srp::core::InvalidInputError);
}

TEST(OrientedBox, ProjectedBoxOfAnObjectFacingTheCamera)
{
  srp::core::CameraIntrinsics K;
  K.fx_px = K.fy_px = 600.0;
  K.cx_px = 320.0;
  K.cy_px = 240.0;
  K.width_px = 640;
  K.height_px = 480;
  // Object frame = camera frame moved 1 m forward: its bottom face (0.10 x
  // 0.05 m) is the near face, 60 x 30 px; the far face (z = 1.04 m) projects inside it.
  const auto X_camera_object = srp::core::makePose(Eigen::Vector3d(0, 0, 1.0), Eigen::Quaterniond::Identity());
  const OrientedBox2d b = projectObjectBox(K, X_camera_object, Eigen::Vector3d(0.10, 0.05, 0.04));
  constexpr double kPixelTol_px = 1e-6;
  EXPECT_NEAR(b.area_px2(), 60.0 * 30.0, 60.0 * 30.0 * 1e-9);
  EXPECT_NEAR(b.centre_px().x(), 320.0, kPixelTol_px);
  EXPECT_NEAR(b.centre_px().y(), 240.0, kPixelTol_px);
  // Turned 90 deg about the optical axis: 30 x 60 px across 60 x 30 px,
  // overlap 30 x 30 = 900, union 2700.
  const auto turned = srp::core::makePose(Eigen::Vector3d(0, 0, 1.0),
                                          Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ())));
  EXPECT_NEAR(orientedBoxIoU(projectObjectBox(K, turned, Eigen::Vector3d(0.10, 0.05, 0.04)), b), 1.0 / 3.0, 1e-9);
  const auto behind = srp::core::makePose(Eigen::Vector3d(0, 0, -1.0), Eigen::Quaterniond::Identity());
  EXPECT_THROW(projectObjectBox(K, behind, Eigen::Vector3d(0.1, 0.05, 0.04)), srp::core::InvalidInputError);
}
