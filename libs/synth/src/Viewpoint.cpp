#include "srp/synth/Viewpoint.h"

#include <Eigen/Geometry>
#include <cmath>

#include "srp/core/Angles.h"
#include "srp/core/Error.h"

namespace srp::synth {

ViewpointFamily viewpointFamilyFromName(const std::string& name) {
  if (name == "egocentric") return ViewpointFamily::Egocentric;
  if (name == "side") return ViewpointFamily::Side;
  if (name == "top-down") return ViewpointFamily::TopDown;
  if (name == "front") return ViewpointFamily::Front;
  if (name == "oblique") return ViewpointFamily::Oblique;
  if (name == "near-corner") return ViewpointFamily::NearCorner;
  if (name == "table-level") return ViewpointFamily::TableLevel;
  if (name == "facing") return ViewpointFamily::Facing;
  throw srp::core::InvalidInputError("viewpoint family '" + name +
                                     "' is unknown; use egocentric, side, top-down, front, oblique, near-corner, "
                                     "table-level or facing");
}

std::string viewpointFamilyName(ViewpointFamily family) {
  switch (family) {
    case ViewpointFamily::Egocentric:
      return "egocentric";
    case ViewpointFamily::Side:
      return "side";
    case ViewpointFamily::TopDown:
      return "top-down";
    case ViewpointFamily::Front:
      return "front";
    case ViewpointFamily::Oblique:
      return "oblique";
    case ViewpointFamily::NearCorner:
      return "near-corner";
    case ViewpointFamily::TableLevel:
      return "table-level";
    case ViewpointFamily::Facing:
      return "facing";
  }
  return "?";
}

Eigen::Vector3d workCentre_world(const srp::core::Scene& scene, const srp::core::ObjectCatalogue& catalogue) {
  Eigen::Vector3d containers = Eigen::Vector3d::Zero(), all = Eigen::Vector3d::Zero();
  int nContainers = 0;
  for (const auto& o : scene.objects) {
    const Eigen::Vector3d p = o.X_world_object.translation();
    all += p;
    if (catalogue.at(o.className).kind == srp::core::ObjectKind::Container) {
      containers += p;
      ++nContainers;
    }
  }
  if (nContainers > 0) return containers / nContainers;
  return scene.objects.empty() ? Eigen::Vector3d::Zero() : Eigen::Vector3d(all / static_cast<double>(scene.objects.size()));
}

std::pair<ViewpointFamily, int> viewpointFromText(const std::string& text) {
  const auto colon = text.find(':');
  const ViewpointFamily family = viewpointFamilyFromName(text.substr(0, colon));
  if (colon == std::string::npos) return {family, 0};
  const std::string number = text.substr(colon + 1);
  const bool digits = !number.empty() && number.size() <= 3 &&
                      number.find_first_not_of("0123456789") == std::string::npos;
  if (!digits)
    throw srp::core::InvalidInputError("viewpoint '" + text +
                                       "': the variant after ':' must be a number 0-999 (e.g. side:1)");
  return {family, std::stoi(number)};
}

srp::core::Pose3 lookAt(const Eigen::Vector3d& eye_world, const Eigen::Vector3d& target_world,
                        const Eigen::Vector3d& up_world) {
  const Eigen::Vector3d z = (target_world - eye_world).normalized();
  Eigen::Vector3d x = z.cross(up_world);
  if (x.norm() < 1e-9) x = z.unitOrthogonal();
  x.normalize();
  const Eigen::Vector3d y = z.cross(x);
  srp::core::Pose3 X = srp::core::Pose3::Identity();
  X.linear().col(0) = x;
  X.linear().col(1) = y;
  X.linear().col(2) = z;
  X.translation() = eye_world;
  return X;
}

Viewpoint makeViewpoint(ViewpointFamily family, int variant, const Eigen::Vector3d& target_world,
                        const Eigen::Vector2d& demonstratorSide_world) {
  srp::core::require(demonstratorSide_world.norm() > 1e-9, "makeViewpoint: demonstratorSide_world must not be zero");
  const int v = ((variant % 9) + 9) % 9;
  const double turn_rad = (v % 3 - 1) * 20.0 * srp::core::kPi / 180.0;
  const double distance = 1.0 + 0.1 * (v / 3 - 1);
  const Eigen::Vector2d s2 = demonstratorSide_world.normalized();
  const Eigen::Vector3d side(s2.x(), s2.y(), 0.0);
  const Eigen::Vector3d across = Eigen::Vector3d::UnitZ().cross(side);  // horizontal, perpendicular to the side
  const Eigen::AngleAxisd turn(turn_rad, Eigen::Vector3d::UnitZ());
  Viewpoint out;
  out.demonstratorSide_world = s2;
  switch (family) {
    case ViewpointFamily::Egocentric: {
      // A standing person's eyes: ~0.85 m above the table, ~0.55 m back from the work.
      const Eigen::Vector3d offset = turn * (0.55 * side) + Eigen::Vector3d(0, 0, 0.85);
      out.X_world_camera =
          lookAt(target_world + distance * offset, target_world - 0.05 * side, Eigen::Vector3d::UnitZ());
      break;
    }
    case ViewpointFamily::Side: {
      const double sign = v % 2 == 0 ? 1.0 : -1.0;  // the camera on either side of the table
      const Eigen::Vector3d offset = turn * (0.8 * sign * across) + Eigen::Vector3d(0, 0, 0.45);
      out.X_world_camera = lookAt(target_world + distance * offset, target_world, Eigen::Vector3d::UnitZ());
      break;
    }
    case ViewpointFamily::TopDown: {
      // Image up along `across` (turned): the demonstrator's side is a side edge.
      out.X_world_camera = lookAt(target_world + Eigen::Vector3d(0, 0, distance * 0.95), target_world, turn * across);
      break;
    }
    case ViewpointFamily::Front: {
      // A camera standing where a robot's head would, across the table from the demonstrator.
      const Eigen::Vector3d offset = turn * (-0.8 * side) + Eigen::Vector3d(0, 0, 0.5);
      out.X_world_camera = lookAt(target_world + distance * offset, target_world, Eigen::Vector3d::UnitZ());
      break;
    }
    case ViewpointFamily::Oblique: {
      const double sign = v % 2 == 0 ? 1.0 : -1.0;  // either far corner of the table
      const Eigen::Vector3d corner = (-side + sign * across).normalized();
      const Eigen::Vector3d offset = turn * (0.7 * corner) + Eigen::Vector3d(0, 0, 0.75);
      out.X_world_camera = lookAt(target_world + distance * offset, target_world, Eigen::Vector3d::UnitZ());
      break;
    }
    case ViewpointFamily::NearCorner: {
      const double sign = v % 2 == 0 ? 1.0 : -1.0;  // either corner on the demonstrator's side
      constexpr double kOff_rad = 50.0 * srp::core::kPi / 180.0;
      const Eigen::Vector3d corner = std::cos(kOff_rad) * side + sign * std::sin(kOff_rad) * across;
      const Eigen::Vector3d offset = turn * (0.7 * corner) + Eigen::Vector3d(0, 0, 0.55);
      out.X_world_camera = lookAt(target_world + distance * offset, target_world, Eigen::Vector3d::UnitZ());
      break;
    }
    case ViewpointFamily::TableLevel: {
      // Beside the table, the lens just above its top (a low tripod). The camera turns 0, 10 or 20 deg towards
      // the demonstrator only: turned away from them it looks along their forearm, whose sleeve ends in view.
      const double sign = v % 2 == 0 ? 1.0 : -1.0;
      const Eigen::AngleAxisd towards(-sign * (v % 3) * 10.0 * srp::core::kPi / 180.0, Eigen::Vector3d::UnitZ());
      const Eigen::Vector3d offset = towards * (0.85 * sign * across) + Eigen::Vector3d(0, 0, 0.2);
      out.X_world_camera = lookAt(target_world + distance * offset, target_world, Eigen::Vector3d::UnitZ());
      break;
    }
    case ViewpointFamily::Facing: {
      // Across the table, lower than front and off the demonstrator's direction. The view 31 deg down keeps the
      // image's top edge 9 deg below the horizon: the resting hand leaves the view a few decimetres beyond the
      // work, not metres (DemoTimeline walks it away until it is out of view).
      const double sign = v % 2 == 0 ? 1.0 : -1.0;
      const Eigen::AngleAxisd off(sign * (30.0 + 7.5 * (v % 3)) * srp::core::kPi / 180.0, Eigen::Vector3d::UnitZ());
      const Eigen::Vector3d offset = off * (-0.6 * side) + Eigen::Vector3d(0, 0, 0.36);
      out.X_world_camera = lookAt(target_world + distance * offset, target_world, Eigen::Vector3d::UnitZ());
      break;
    }
  }
  return out;
}

}  // namespace srp::synth
