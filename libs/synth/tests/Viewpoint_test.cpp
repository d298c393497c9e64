// The viewpoint families against their geometry: every camera looks at the
// target, from the side of the table its family says, level (no roll) unless
// it looks straight down, at the distance its variant says.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "srp/core/Angles.h"
#include "srp/core/Error.h"
#include "srp/synth/Viewpoint.h"

namespace srp::synth {
namespace {

constexpr double kGeomTol = 1e-9;

const ViewpointFamily kFamilies[] = {ViewpointFamily::Egocentric, ViewpointFamily::Side,       ViewpointFamily::TopDown,
                                     ViewpointFamily::Front,      ViewpointFamily::Oblique,    ViewpointFamily::NearCorner,
                                     ViewpointFamily::TableLevel, ViewpointFamily::Facing};

/// Distance [m] from `p` to the camera's optical axis.
double offAxis_m(const core::Pose3& X_world_camera, const Eigen::Vector3d& p_world) {
  const Eigen::Vector3d p_camera = X_world_camera.inverse() * p_world;
  return p_camera.head<2>().norm();
}

TEST(Viewpoint, EveryFamilyLooksAtTheTargetFromAbove) {
  const Eigen::Vector3d target(0.1, -0.05, 0.02);
  for (const auto family : kFamilies)
    for (int v = 0; v < 9; ++v) {
      const auto view = makeViewpoint(family, v, target);
      const auto& X = view.X_world_camera;
      SCOPED_TRACE(viewpointFamilyName(family) + " variant " + std::to_string(v));
      // The egocentric camera looks 5 cm past the target, away from the demonstrator (default side: +y).
      const Eigen::Vector3d lookedAt =
          family == ViewpointFamily::Egocentric ? Eigen::Vector3d(target - Eigen::Vector3d(0, 0.05, 0)) : target;
      EXPECT_LT(offAxis_m(X, lookedAt), kGeomTol);
      EXPECT_GT((X.inverse() * target).z(), 0.3) << "the target in front of the camera";
      // The table-level camera: its lens 0.2 m above the table; facing: 0.36 m (+-10 % with the distance).
      const double minHeight_m = family == ViewpointFamily::TableLevel ? 0.17
                                 : family == ViewpointFamily::Facing   ? 0.32
                                                                       : 0.4;
      EXPECT_GT(X.translation().z() - target.z(), minHeight_m) << "the camera above the table";
      EXPECT_NEAR(X.linear().determinant(), 1.0, kGeomTol);
      if (family != ViewpointFamily::TopDown)
        EXPECT_NEAR(X.linear().col(0).z(), 0.0, kGeomTol) << "image x level: no roll";
    }
}

TEST(Viewpoint, FamiliesStandWhereTheySay) {
  const Eigen::Vector3d target(0, 0, 0);
  const Eigen::Vector2d side2(0.6, 0.8);  // the demonstrator's side of the table
  const Eigen::Vector3d side(side2.x(), side2.y(), 0), across = Eigen::Vector3d::UnitZ().cross(side);
  auto eye = [&](ViewpointFamily f, int v) { return makeViewpoint(f, v, target, side2).X_world_camera.translation(); };
  // Variant 4: no turn, nominal distance; variant 1: no turn, 10 % nearer, and odd (the other side).
  EXPECT_GT(eye(ViewpointFamily::Egocentric, 4).dot(side), 0.4) << "behind the hand, on the demonstrator's side";
  EXPECT_LT(eye(ViewpointFamily::Front, 4).dot(side), -0.6) << "across the table from the demonstrator";
  EXPECT_NEAR(eye(ViewpointFamily::Front, 4).dot(across), 0.0, kGeomTol);
  EXPECT_NEAR(std::abs(eye(ViewpointFamily::Side, 4).dot(across)), 0.8, kGeomTol);
  EXPECT_NEAR(eye(ViewpointFamily::Side, 4).dot(side), 0.0, kGeomTol);
  for (const auto& [v, scale] : {std::pair{4, 1.0}, std::pair{1, 0.9}}) {
    // either far corner: opposite the demonstrator and off to one side, equally
    const Eigen::Vector3d e = eye(ViewpointFamily::Oblique, v) / scale;
    EXPECT_NEAR(e.dot(side), -0.7 / std::sqrt(2.0), kGeomTol);
    EXPECT_NEAR(std::abs(e.dot(across)), 0.7 / std::sqrt(2.0), kGeomTol);
  }
  EXPECT_LT(eye(ViewpointFamily::Oblique, 4).dot(across) * eye(ViewpointFamily::Oblique, 1).dot(across), 0.0);
  // Near corner: on the demonstrator's side, 50 deg off their direction, either side.
  const double off_rad = 50.0 * core::kPi / 180.0;
  EXPECT_NEAR(eye(ViewpointFamily::NearCorner, 4).dot(side), 0.7 * std::cos(off_rad), kGeomTol);
  EXPECT_NEAR(std::abs(eye(ViewpointFamily::NearCorner, 4).dot(across)), 0.7 * std::sin(off_rad), kGeomTol);
  EXPECT_NEAR(eye(ViewpointFamily::NearCorner, 4).z(), 0.55, kGeomTol);
  EXPECT_LT(eye(ViewpointFamily::NearCorner, 4).dot(across) * eye(ViewpointFamily::NearCorner, 1).dot(across), 0.0);
  // Table level, variant 3: not turned, nominal distance, odd (variant 6: even, 10 % farther).
  EXPECT_NEAR(std::abs(eye(ViewpointFamily::TableLevel, 3).dot(across)), 0.85, kGeomTol) << "beside the table";
  EXPECT_NEAR(eye(ViewpointFamily::TableLevel, 3).dot(side), 0.0, kGeomTol);
  EXPECT_NEAR(eye(ViewpointFamily::TableLevel, 3).z(), 0.2, kGeomTol) << "just above its top";
  EXPECT_LT(eye(ViewpointFamily::TableLevel, 3).dot(across) * eye(ViewpointFamily::TableLevel, 6).dot(across), 0.0);
  // Facing: across the table, 0.6 m out and 0.36 m up (variants 3-5: nominal distance), 30/37.5/45 deg off the
  // demonstrator's direction, on either side of it by parity.
  for (int v = 0; v < 9; ++v) {
    const double scale = 1.0 + 0.1 * (v / 3 - 1);
    const Eigen::Vector3d e = eye(ViewpointFamily::Facing, v) / scale;
    const double off_deg = 30.0 + 7.5 * (v % 3);
    EXPECT_NEAR(e.dot(side), -0.6 * std::cos(off_deg * core::kPi / 180.0), kGeomTol) << "variant " << v;
    EXPECT_NEAR(e.dot(across), (v % 2 == 0 ? -1.0 : 1.0) * 0.6 * std::sin(off_deg * core::kPi / 180.0), kGeomTol)
        << "variant " << v;
    EXPECT_NEAR(e.z(), 0.36, kGeomTol) << "variant " << v;
  }
  for (int v = 0; v < 9; ++v)  // turned 0, 10, 20 deg towards the demonstrator, never away from them
    EXPECT_NEAR(eye(ViewpointFamily::TableLevel, v).dot(side) / eye(ViewpointFamily::TableLevel, v).head<2>().norm(),
                std::sin((v % 3) * 10.0 * core::kPi / 180.0), 1e-9)
        << "variant " << v;
  const Eigen::Vector3d top = eye(ViewpointFamily::TopDown, 4);
  EXPECT_NEAR(top.head<2>().norm(), 0.0, kGeomTol);
  EXPECT_NEAR(top.z(), 0.95, kGeomTol);
  // Distance variants 1 / 4 / 7: -10 %, 0, +10 % of the nominal offset.
  for (const auto family : kFamilies) {
    const double nominal = eye(family, 4).norm();
    EXPECT_NEAR(eye(family, 1).norm(), 0.9 * nominal, 1e-6 * nominal) << viewpointFamilyName(family);
    EXPECT_NEAR(eye(family, 7).norm(), 1.1 * nominal, 1e-6 * nominal) << viewpointFamilyName(family);
  }
}

TEST(Viewpoint, NamesAndVariantsReadBack) {
  for (const auto family : kFamilies) EXPECT_EQ(viewpointFamilyFromName(viewpointFamilyName(family)), family);
  EXPECT_EQ(viewpointFromText("side:3"), std::make_pair(ViewpointFamily::Side, 3));
  EXPECT_EQ(viewpointFromText("front"), std::make_pair(ViewpointFamily::Front, 0));
  EXPECT_EQ(viewpointFromText("near-corner:5"), std::make_pair(ViewpointFamily::NearCorner, 5));
  EXPECT_EQ(viewpointFromText("table-level:2"), std::make_pair(ViewpointFamily::TableLevel, 2));
  EXPECT_EQ(viewpointFromText("facing:4"), std::make_pair(ViewpointFamily::Facing, 4));
  EXPECT_EQ(viewpointFamilyName(ViewpointFamily::Facing), "facing");
  EXPECT_THROW(viewpointFromText("side:"), core::InvalidInputError);
  EXPECT_THROW(viewpointFromText("side:-1"), core::InvalidInputError);
  EXPECT_THROW(viewpointFromText("side:1x"), core::InvalidInputError);
  EXPECT_THROW(viewpointFromText("underneath"), core::InvalidInputError);
}

TEST(Viewpoint, WorkCentreIsTheMiddleOfTheContainers) {
  std::vector<core::ObjectClass> classes(2);
  classes[0].name = "box";
  classes[0].classId = 0;
  classes[0].kind = core::ObjectKind::Container;
  classes[1].name = "cube";
  classes[1].classId = 1;
  const core::ObjectCatalogue catalogue(classes);
  core::Scene scene;
  auto place = [&](const char* id, const char* cls, const Eigen::Vector3d& p) {
    core::SceneObject o;
    o.id = id;
    o.className = cls;
    o.X_world_object.translation() = p;
    scene.objects.push_back(o);
  };
  place("cube", "cube", {1.0, 1.0, 0.0});
  EXPECT_LT((workCentre_world(scene, catalogue) - Eigen::Vector3d(1, 1, 0)).norm(), kGeomTol) << "no container: the objects";
  place("box_a", "box", {0.2, 0.0, 0.0});
  place("box_b", "box", {0.0, 0.4, 0.0});
  EXPECT_LT((workCentre_world(scene, catalogue) - Eigen::Vector3d(0.1, 0.2, 0)).norm(), kGeomTol);
}

}  // namespace
}  // namespace srp::synth
