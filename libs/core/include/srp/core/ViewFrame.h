#pragma once
/// \file ViewFrame.h
/// \brief The one convention for reading "left", "right", "in front of" and
/// "behind" on the table: two unit vectors in the table plane (world x, y),
/// shared by grounding ("the cube left of the star", "the second cube": counted
/// left to right) and placement ("put the star left of the cube").
///
/// - Demonstrator's view (Viewpoint::Demonstrator, the default of the stack): the
///   camera's image axes projected on the table. `right_world` is the camera's x
///   axis (image columns grow to the right), `front_world` its y axis (image rows
///   grow downwards, i.e. towards the person looking at the picture), made exactly
///   perpendicular to `right_world`. For a camera looking down from above the
///   demonstrator's side of the table, "in front of X" is nearer to the
///   demonstrator than X and "left of X" is left in the camera image.
/// - Robot's view (Viewpoint::Robot): a viewer at the robot base looking at the
///   work area (p_world_lookAt, e.g. the table centre); front = towards the robot,
///   right = look x z_world. When the look-at point (nearly) coincides with the
///   base, the viewer looks along the base's -x axis (where a UR arm reaches at
///   q1 = 0).
/// Both vectors are unit length, horizontal and perpendicular; "left" is
/// -right_world, "behind" is -front_world. Frames: world = table frame, z up.

#include <Eigen/Core>
#include <optional>
#include <string>

#include "srp/core/Pose.h"

namespace srp::core {

/// Whose left/right the words are read in.
enum class Viewpoint { Demonstrator, Robot };

/// Parses "demonstrator"/"camera" or "robot"; throws InvalidInputError naming the word.
Viewpoint viewpointFromString(const std::string& name);
std::string toString(Viewpoint viewpoint);

struct ViewFrame {
  Eigen::Vector2d right_world = Eigen::Vector2d::UnitX();   ///< unit vector, table plane
  Eigen::Vector2d front_world = -Eigen::Vector2d::UnitY();  ///< unit vector, towards the viewer

  /// The demonstrator's view from the camera pose (optical frame: x right, y down,
  /// z forward). Throws InvalidInputError when the camera's x axis is (nearly)
  /// vertical, so that "right" has no direction on the table.
  static ViewFrame fromCamera(const Pose3& X_world_camera);

  /// The robot's view: from the base origin towards p_world_lookAt (x, y); when the
  /// two (nearly) coincide, along the base's -x axis.
  static ViewFrame fromRobot(const Pose3& X_world_base, const Eigen::Vector2d& p_world_lookAt);

  /// Coordinate of a world point along "right" [m] (larger = further right).
  double rightOf(const Eigen::Vector3d& p_world_m) const { return right_world.dot(p_world_m.head<2>()); }
  /// Coordinate of a world point along "front" [m] (larger = nearer the viewer).
  double frontOf(const Eigen::Vector3d& p_world_m) const { return front_world.dot(p_world_m.head<2>()); }

  /// The table-plane unit direction of a direction word or relation phrase: the bare
  /// words "left", "right", "front", "behind"/"back" and the phrases "left of"/"to
  /// the left of" -> -right, "right of" -> right, "in front of" -> front,
  /// "behind"/"in back of"/"at the back of" -> -front. nullopt for anything else
  /// ("next to", "in", "back to", "in the front left corner of", "up").
  std::optional<Eigen::Vector2d> direction(const std::string& wordOrRelation) const;

  /// "left", "right", "front", "behind" for a direction word or relation phrase, "" otherwise.
  static std::string directionWord(const std::string& wordOrRelation);
};

}  // namespace srp::core
