#include "srp/core/ViewFrame.h"

#include <Eigen/Geometry>
#include <cctype>

#include "srp/core/Error.h"

namespace srp::core {
namespace {

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

bool contains(const std::string& s, const std::string& word) { return s.find(word) != std::string::npos; }

ViewFrame fromRight(const Eigen::Vector2d& right) {
  ViewFrame v;
  v.right_world = right.normalized();
  v.front_world = Eigen::Vector2d(v.right_world.y(), -v.right_world.x());  // right x z
  return v;
}

}  // namespace

ViewFrame ViewFrame::fromCamera(const Pose3& X_world_camera) {
  const Eigen::Vector2d right = X_world_camera.linear().col(0).head<2>();
  if (right.norm() < 1e-3)
    throw InvalidInputError("ViewFrame::fromCamera: the camera's x axis is vertical, so 'left'/'right' have no "
                            "direction on the table; use ViewFrame::fromRobot or turn the camera");
  return fromRight(right);
}

ViewFrame ViewFrame::fromRobot(const Pose3& X_world_base, const Eigen::Vector2d& p_world_lookAt) {
  Eigen::Vector2d look = p_world_lookAt - X_world_base.translation().head<2>();
  if (look.norm() < 1e-3) look = -X_world_base.linear().col(0).head<2>();
  if (look.norm() < 1e-6)
    throw InvalidInputError("ViewFrame::fromRobot: the robot base's x axis is vertical; check X_world_base");
  look.normalize();
  return fromRight(Eigen::Vector2d(look.y(), -look.x()));  // look x z
}

std::string ViewFrame::directionWord(const std::string& relation) {
  const std::string r = " " + lower(relation) + " ";
  if (contains(r, " corner")) return "";
  if (contains(r, " left ")) return "left";
  if (contains(r, " right ")) return "right";
  if (contains(r, " front ")) return "front";
  if (contains(r, " behind ") || contains(r, " back of ") || contains(r, " rear of ")) return "behind";
  return "";
}

std::optional<Eigen::Vector2d> ViewFrame::direction(const std::string& relation) const {
  const std::string w = directionWord(relation);
  if (w == "left") return Eigen::Vector2d(-right_world);
  if (w == "right") return right_world;
  if (w == "front") return front_world;
  if (w == "behind") return Eigen::Vector2d(-front_world);
  return std::nullopt;
}

}  // namespace srp::core
