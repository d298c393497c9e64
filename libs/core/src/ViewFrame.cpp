#include "srp/core/ViewFrame.h"

#include <Eigen/Geometry>
#include <cctype>

#include "srp/core/Text.h"
#include "srp/core/Error.h"

namespace srp::core {
namespace {

// Below this horizontal length an axis is too steep to give a table direction.
constexpr double kMinHorizontal = 0.2;

bool contains(const std::string& s, const std::string& word) { return s.find(word) != std::string::npos; }

ViewFrame fromRight(const Eigen::Vector2d& right) {
  ViewFrame v;
  v.right_world = right.normalized();
  v.front_world = Eigen::Vector2d(v.right_world.y(), -v.right_world.x());  // right x z
  return v;
}

}  // namespace

Viewpoint viewpointFromString(const std::string& name) {
  if (name == "demonstrator" || name == "camera") return Viewpoint::Demonstrator;
  if (name == "robot") return Viewpoint::Robot;
  throw InvalidInputError("unknown viewpoint '" + name + "' (known: demonstrator, robot)");
}

std::string toString(Viewpoint viewpoint) { return viewpoint == Viewpoint::Robot ? "robot" : "demonstrator"; }

ViewFrame ViewFrame::fromCamera(const Pose3& X_world_camera) {
  const Eigen::Vector2d right = X_world_camera.linear().col(0).head<2>();
  if (right.norm() < kMinHorizontal)
    throw InvalidInputError("ViewFrame::fromCamera: the camera's x axis (X_world_camera) is (nearly) vertical, so "
                            "'left'/'right' have no direction on the table; use the robot's view (--view robot) "
                            "or turn the camera");
  ViewFrame f;
  f.right_world = right.normalized();
  // Image "down" projected on the table, made exactly perpendicular to "right".
  const Eigen::Vector2d down = X_world_camera.linear().col(1).head<2>();
  const Eigen::Vector2d perp(-f.right_world.y(), f.right_world.x());
  f.front_world = down.dot(perp) >= 0.0 ? perp : Eigen::Vector2d(-perp);
  return f;
}

ViewFrame ViewFrame::fromRobot(const Pose3& X_world_base, const Eigen::Vector2d& p_world_lookAt) {
  Eigen::Vector2d look = p_world_lookAt - X_world_base.translation().head<2>();
  if (look.norm() < 1e-3) look = -X_world_base.linear().col(0).head<2>();
  if (look.norm() < 1e-6)
    throw InvalidInputError("ViewFrame::fromRobot: the robot base's x axis is vertical; check X_world_base");
  look.normalize();
  return fromRight(Eigen::Vector2d(look.y(), -look.x()));  // look x z
}

std::string ViewFrame::directionWord(const std::string& wordOrRelation) {
  const std::string w = toLowerAscii(wordOrRelation);
  if (w == "back") return "behind";  // the bare word only: "back to the box" is a return, not a direction
  const std::string r = " " + w + " ";
  if (contains(r, " corner")) return "";
  if (contains(r, " left ")) return "left";
  if (contains(r, " right ")) return "right";
  if (contains(r, " front ")) return "front";
  if (contains(r, " behind ") || contains(r, " back of ") || contains(r, " rear of ")) return "behind";
  return "";
}

std::optional<Eigen::Vector2d> ViewFrame::direction(const std::string& wordOrRelation) const {
  const std::string w = directionWord(wordOrRelation);
  if (w == "left") return Eigen::Vector2d(-right_world);
  if (w == "right") return right_world;
  if (w == "front") return front_world;
  if (w == "behind") return Eigen::Vector2d(-front_world);
  return std::nullopt;
}

}  // namespace srp::core
