#pragma once
/// \file Viewpoint.h
/// \brief Camera placements for synthetic demonstrations beyond the scene's
/// own camera: at the demonstrator's head (egocentric), beside the table,
/// straight above it, across the table facing the demonstrator (at chest
/// height, or lower and off their direction), at a far corner of the table, at
/// a corner on the demonstrator's side, and beside the table just above its
/// top, each with variants (azimuth, distance).

#include <Eigen/Core>
#include <string>
#include <utility>

#include "srp/core/ObjectCatalogue.h"
#include "srp/core/Pose.h"
#include "srp/core/Scene.h"

namespace srp::synth {

/// A family of camera placements. Frames: `world` = table (z up, metres),
/// the camera's optical frame (x right, y down, z forward).
enum class ViewpointFamily {
  Egocentric,  ///< at the demonstrator's head, above and behind the hand: the arm enters from the bottom edge
  Side,        ///< beside the table, looking across it: the arm enters from the left or right edge
  TopDown,     ///< straight above the table, turned so that the arm enters from a side edge
  Front,       ///< across the table, facing the demonstrator at chest height: the arm comes towards the camera
               ///< from the top edge
  Oblique,     ///< high at a corner of the table opposite the demonstrator: the arm enters from a top corner
  NearCorner,  ///< at a corner of the table on the demonstrator's side, 50 deg off their direction, 0.55 m
               ///< above: the arm enters from the left or right edge (the side towards the demonstrator),
               ///< its back towards the camera
  TableLevel,  ///< beside the table, 0.85 m out, the lens 0.2 m above its top: the table and the boxes seen at a
               ///< grazing angle (their walls hide what lies inside), the arm entering from the left or right
               ///< edge at the camera's height, the hand seen edge-on
  Facing,      ///< across the table facing the demonstrator, lower than Front and off their direction: 0.6 m out,
               ///< 30-45 deg off the demonstrator's direction, 0.36 m above the table (the view 31 deg down): the
               ///< arm comes towards the camera from the top edge, the palm and the held part facing the lens
};

/// Where the camera is and where the demonstrator stands (DemoOptions::demonstratorSide_world).
struct Viewpoint {
  srp::core::Pose3 X_world_camera = srp::core::Pose3::Identity();
  Eigen::Vector2d demonstratorSide_world = Eigen::Vector2d::UnitY();
};

/// "egocentric", "side", "top-down", "front", "oblique", "near-corner", "table-level", "facing"; throws
/// InvalidInputError naming the text and the choices otherwise.
ViewpointFamily viewpointFamilyFromName(const std::string& name);
std::string viewpointFamilyName(ViewpointFamily family);

/// Variant `variant` (>= 0; any integer, they cycle) of `family`, looking at
/// `target_world` (a point on the table), with the demonstrator on the side
/// `demonstratorSide_world` (unit, horizontal) of the table. Variants turn
/// the camera about the vertical through the target by -20, 0, +20 deg and
/// change its distance by -10, 0, +10 % (3 x 3 = 9 before they repeat); the
/// side, oblique, near-corner and table-level families' even variants stand on
/// one side of the table, odd ones on the other. The table-level camera turns
/// by 0, 10 and 20 deg towards the demonstrator instead (turned away from them
/// it would look along their forearm and see the sleeve's end). The facing
/// camera stands 30, 37.5 or 45 deg off the demonstrator's direction instead
/// (variant % 3), on either side of it by the variant's parity.
Viewpoint makeViewpoint(ViewpointFamily family, int variant, const Eigen::Vector3d& target_world,
                        const Eigen::Vector2d& demonstratorSide_world = Eigen::Vector2d::UnitY());

/// The point the viewpoints look at in `scene`: the middle of its containers
/// (of all its objects when it has no container), on the table [m, world].
Eigen::Vector3d workCentre_world(const srp::core::Scene& scene, const srp::core::ObjectCatalogue& catalogue);

/// "FAMILY" or "FAMILY:VARIANT" (e.g. "side:1") as a family and a variant
/// (0 when not given); throws InvalidInputError naming the text otherwise.
std::pair<ViewpointFamily, int> viewpointFromText(const std::string& text);

/// The optical frame of a camera at `eye_world` looking at `target_world`,
/// its image's up towards `up_world` (as far as it is not along the view).
srp::core::Pose3 lookAt(const Eigen::Vector3d& eye_world, const Eigen::Vector3d& target_world,
                        const Eigen::Vector3d& up_world);

}  // namespace srp::synth
