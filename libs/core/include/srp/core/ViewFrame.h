#pragma once
/// \file ViewFrame.h
/// \brief The table-plane directions in which "left of", "right of", "in front of"
/// and "behind" are read, shared by grounding ("the cube left of the star") and
/// placement ("put the star left of the cube").
///
/// Convention (default: the demonstrator's view): the camera's image axes projected
/// on the table. `right_world` is the camera's x axis (image right) projected on the
/// world x-y plane and normalised; `front_world` = right x z_world, i.e. towards the
/// viewer (image down for a camera looking down at the table, the bottom of the
/// image being nearest to the demonstrator). Left = -right, behind = -front.
/// Configurable to the robot's view (fromRobot): a viewer at the robot base looking
/// at the work area; front = towards the robot. Frames: world = table frame, z up.

#include <Eigen/Core>
#include <optional>
#include <string>

#include "srp/core/Pose.h"

namespace srp::core {

struct ViewFrame {
  Eigen::Vector2d right_world = Eigen::Vector2d::UnitX();   ///< unit vector, table plane
  Eigen::Vector2d front_world = -Eigen::Vector2d::UnitY();  ///< unit vector, towards the viewer

  /// The demonstrator's view from the camera pose. Throws InvalidInputError when
  /// the camera's x axis is (nearly) vertical, so it has no direction on the table.
  static ViewFrame fromCamera(const Pose3& X_world_camera);

  /// The robot's view: from the base origin towards p_world_lookAt (x, y); when the
  /// two (nearly) coincide, along the base's -x axis (where a UR arm reaches at q1 = 0).
  static ViewFrame fromRobot(const Pose3& X_world_base, const Eigen::Vector2d& p_world_lookAt);

  /// The unit direction from a landmark to where a part goes for a relation word:
  /// "left of"/"to the left of" -> -right, "right of" -> right, "in front of" ->
  /// front, "behind"/"in back of"/"at the back of" -> -front; nullopt for other words.
  std::optional<Eigen::Vector2d> direction(const std::string& relation) const;

  /// "left", "right", "front", "behind" for a direction word relation, "" otherwise.
  static std::string directionWord(const std::string& relation);
};

}  // namespace srp::core
