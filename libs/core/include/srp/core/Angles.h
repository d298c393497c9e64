#pragma once
/// \file Angles.h
/// \brief The one definition of pi for the modules (radians everywhere;
/// angleDifference in Pose.h wraps an angle difference to (-pi, pi]).

namespace srp::core {

inline constexpr double kPi = 3.14159265358979323846;

}  // namespace srp::core
