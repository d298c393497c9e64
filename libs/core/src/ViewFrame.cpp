#include "srp/core/ViewFrame.h"

#include <Eigen/Geometry>

#include "srp/core/Error.h"

namespace srp::core {
namespace {

// Below this horizontal length an axis is too steep to give a table direction.
constexpr double kMinHorizontal = 0.2;

Eigen::Vector2d horizontal(const Eigen::Vector3d& axis, const std::string& what) {
  const Eigen::Vector2d h = axis.head<2>();
  if (h.norm() < kMinHorizontal)
    throw InvalidInputError(what + " is (nearly) vertical, so it gives no left/right direction on the table; "
                                   "use the robot's view (--view robot) or fix the pose");
  return h.normalized();
}

}  // namespace

Viewpoint viewpointFromString(const std::string& name) {
  if (name == "demonstrator" || name == "camera") return Viewpoint::Demonstrator;
  if (name == "robot") return Viewpoint::Robot;
  throw InvalidInputError("unknown viewpoint '" + name + "' (known: demonstrator, robot)");
}

std::string toString(Viewpoint viewpoint) { return viewpoint == Viewpoint::Robot ? "robot" : "demonstrator"; }

ViewFrame ViewFrame::fromCamera(const Pose3& X_world_camera) {
  ViewFrame f;
  f.right_world = horizontal(X_world_camera.linear().col(0), "the camera's x axis (X_world_camera)");
  // Image "down" projected on the table, made exactly perpendicular to "right".
  const Eigen::Vector2d down = X_world_camera.linear().col(1).head<2>();
  const Eigen::Vector2d perp(-f.right_world.y(), f.right_world.x());
  f.front_world = down.dot(perp) >= 0.0 ? perp : Eigen::Vector2d(-perp);
  return f;
}

ViewFrame ViewFrame::fromRobot(const Pose3& X_world_base) {
  ViewFrame f;
  f.right_world = -horizontal(X_world_base.linear().col(1), "the robot base's y axis (X_world_base)");
  f.front_world = Eigen::Vector2d(f.right_world.y(), -f.right_world.x());  // -x of the base for an upright base
  return f;
}

Eigen::Vector2d ViewFrame::direction(const std::string& word) const {
  if (word == "right") return right_world;
  if (word == "left") return -right_world;
  if (word == "front") return front_world;
  if (word == "behind" || word == "back") return -front_world;
  throw InvalidInputError("unknown direction word '" + word + "' (known: left, right, front, behind)");
}

}  // namespace srp::core
