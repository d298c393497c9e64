#pragma once
/// \file ViewFrame.h
/// \brief The one convention for reading "left", "right", "in front of" and
/// "behind" on the table: two unit vectors in the table plane (world x, y).
///
/// - Demonstrator's view (the default of the stack): the camera's image axes
///   projected on the table. `right_world` is the camera's x axis (image
///   columns grow to the right), `front_world` its y axis (image rows grow
///   downwards, i.e. towards the person looking at the picture). For a camera
///   looking down from above the demonstrator's side of the table, "in front
///   of X" is nearer to the demonstrator than X and "left of X" is left in the
///   camera image.
/// - Robot's view: the robot stands at its base looking along the base's x
///   axis (ROS base_link): `front_world` is -x of the base (towards the robot),
///   `right_world` is -y of the base (its right hand side).
/// Both vectors are unit length, horizontal (z = 0 in world) and perpendicular;
/// "left" is -right_world, "behind" is -front_world. Grounding ("the cube left of
/// the star"), ordinals ("the second cube": counted left to right) and placement
/// ("put it left of the star") all use this frame.

#include <Eigen/Core>
#include <string>

#include "srp/core/Pose.h"

namespace srp::core {

enum class Viewpoint { Demonstrator, Robot };

/// Parses "demonstrator"/"camera" or "robot"; throws InvalidInputError naming the word.
Viewpoint viewpointFromString(const std::string& name);
std::string toString(Viewpoint viewpoint);

struct ViewFrame {
  Eigen::Vector2d right_world = Eigen::Vector2d::UnitX();   ///< table-plane "right", world x/y
  Eigen::Vector2d front_world = -Eigen::Vector2d::UnitY();  ///< table-plane "towards the viewer"

  /// The demonstrator's view from the camera pose (optical frame: x right, y down,
  /// z forward). Throws InvalidInputError when the camera's x axis is (nearly)
  /// vertical, so that "right" has no direction on the table.
  static ViewFrame fromCamera(const Pose3& X_world_camera);
  /// The robot's view from its base pose (ROS base_link: x forward, y left, z up).
  static ViewFrame fromRobot(const Pose3& X_world_base);

  /// Coordinate of a world point along "right" [m] (larger = further right).
  double rightOf(const Eigen::Vector3d& p_world_m) const { return right_world.dot(p_world_m.head<2>()); }
  /// Coordinate of a world point along "front" [m] (larger = nearer the viewer).
  double frontOf(const Eigen::Vector3d& p_world_m) const { return front_world.dot(p_world_m.head<2>()); }
  /// The table-plane unit vector of a direction word: "left", "right", "front", "behind"/"back".
  /// Throws InvalidInputError for any other word.
  Eigen::Vector2d direction(const std::string& word) const;
};

}  // namespace srp::core
