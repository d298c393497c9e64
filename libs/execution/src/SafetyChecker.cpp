#include "srp/execution/SafetyChecker.h"

#include <cmath>
#include <iomanip>
#include <sstream>

#include "srp/core/Error.h"

namespace srp::execution {
namespace {

std::string fmt(double v, int digits = 3) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(digits) << v;
  return s.str();
}

}  // namespace

SafetyChecker::SafetyChecker(RobotModel model, const srp::core::Pose3& X_world_base, SafetyLimits limits,
                             std::vector<WorldBox> obstacles)
    : model_(std::move(model)), X_world_base_(X_world_base), limits_(limits), obstacles_(std::move(obstacles)) {
  if (!(limits_.maxAcceleration_radps2 > 0.0) || !std::isfinite(limits_.maxAcceleration_radps2))
    throw srp::core::InvalidInputError("SafetyChecker: the joint acceleration limit must be a positive number of "
                                       "rad/s^2 (got " + fmt(limits_.maxAcceleration_radps2) +
                                       "); the default 5.0 is Universal Robots' MoveIt limit");
}

std::vector<ArmSphere> SafetyChecker::armSpheres(const JointVector& q) const {
  const auto X = model_.linkPoses(q);
  std::vector<ArmSphere> spheres;
  auto segment = [&](const std::string& link, const Eigen::Vector3d& a_base, const Eigen::Vector3d& b_base,
                     double radius) {
    const int n = std::max(2, static_cast<int>(std::ceil((b_base - a_base).norm() / radius)) + 1);
    for (int i = 0; i < n; ++i) {
      const Eigen::Vector3d p = a_base + (b_base - a_base) * (static_cast<double>(i) / (n - 1));
      spheres.push_back({link, X_world_base_ * p, radius});
    }
  };
  // UR5 link radii (physical_parameters.yaml): upper arm 0.054, forearm 0.04, wrists 0.045.
  segment(model_.links()[2].name, X[2].translation(), X[3].translation(), 0.054);
  segment(model_.links()[3].name, X[3].translation(), X[4].translation(), 0.045);
  segment(model_.links()[4].name, X[4].translation(), X[5].translation(), 0.045);
  segment(model_.links()[5].name, X[5].translation(), X[6].translation(), 0.045);
  const srp::core::Pose3 X_base_tool0 = X[6] * model_.X_wrist3_tool0();
  const srp::core::Pose3 X_base_tcp = X[6] * model_.X_wrist3_tcp();
  constexpr double kToolRadius_m = 0.02;
  // The tool's spheres stop one radius short of the cup, whose rim is the tcp itself.
  const Eigen::Vector3d axis = (X_base_tcp.translation() - X_base_tool0.translation()).normalized();
  segment("tool", X_base_tool0.translation(), X_base_tcp.translation() - kToolRadius_m * axis, kToolRadius_m);
  spheres.push_back({"tcp", X_world_base_ * X_base_tcp.translation(), 0.0});
  return spheres;
}

double SafetyChecker::tableClearance_m(const JointVector& q) const {
  double clearance = std::numeric_limits<double>::infinity();
  for (const auto& s : armSpheres(q)) clearance = std::min(clearance, s.centre_world_m.z() - s.radius_m);
  return clearance;
}

std::optional<SafetyViolation> SafetyChecker::checkConfiguration(const JointVector& q,
                                                                 const std::string& what) const {
  for (int i = 0; i < 6; ++i) {
    const auto& j = model_.joints()[i];
    if (!(q[i] >= j.lower_rad && q[i] <= j.upper_rad))
      return SafetyViolation{"joint limit", 0, 0.0,
                             what + ": joint " + j.name + " would reach " + fmt(q[i]) + " rad, outside its limits [" +
                                 fmt(j.lower_rad) + ", " + fmt(j.upper_rad) + "] rad"};
  }
  const Eigen::Vector3d p_tcp = X_world_base_ * model_.X_base_tcp(q).translation();
  if (!limits_.workspace_world_m.contains(p_tcp)) {
    const auto& w = limits_.workspace_world_m;
    return SafetyViolation{"workspace", 0, 0.0,
                           what + ": the tool centre point would leave the workspace box at (" + fmt(p_tcp.x()) +
                               ", " + fmt(p_tcp.y()) + ", " + fmt(p_tcp.z()) + ") m; the box is [" +
                               fmt(w.min().x()) + ", " + fmt(w.max().x()) + "] x [" + fmt(w.min().y()) + ", " +
                               fmt(w.max().y()) + "] x [" + fmt(w.min().z()) + ", " + fmt(w.max().z()) + "] m"};
  }
  for (const auto& s : armSpheres(q)) {
    const double gap = s.centre_world_m.z() - s.radius_m;
    if (gap < limits_.tableClearance_m)
      return SafetyViolation{"table", 0, 0.0,
                             what + ": " + s.link + " would come " + fmt(gap * 1000, 1) +
                                 " mm from the table plane (minimum " + fmt(limits_.tableClearance_m * 1000, 1) +
                                 " mm)"};
    for (const auto& box : obstacles_) {
      const double d = box.signedDistance(s.centre_world_m) - s.radius_m;
      if (d < limits_.obstacleClearance_m)
        return SafetyViolation{"collision", 0, 0.0,
                               what + ": " + s.link + " would hit the " + box.owner + " (gap " + fmt(d * 1000, 1) +
                                   " mm, minimum " + fmt(limits_.obstacleClearance_m * 1000, 1) + " mm)"};
    }
  }
  return std::nullopt;
}

namespace {
// Both the spline velocity and the chord between samples (catches IK branch jumps).
double jointSpeedAt(const std::vector<JointTrajectorySample>& samples, std::size_t k, int i) {
  double speed = std::abs(samples[k].qd_radps[i]);
  if (k > 0)
    speed = std::max(speed, std::abs(samples[k].q_rad[i] - samples[k - 1].q_rad[i]) /
                                (samples[k].t_s - samples[k - 1].t_s));
  return speed;
}
// |second derivative| of the cubic Hermite spline at sample k, the larger of the
// interval ending there and the one starting there (a cubic's q'' is linear in t, so
// these knots bound it everywhere).
double splineAccelerationAt(const std::vector<JointTrajectorySample>& samples, std::size_t k, int i) {
  double acc = 0.0;
  if (k > 0) {  // end of [k-1, k]
    const auto &a = samples[k - 1], &b = samples[k];
    const double h = b.t_s - a.t_s;
    acc = std::abs(6 * (a.q_rad[i] - b.q_rad[i]) + h * (2 * a.qd_radps[i] + 4 * b.qd_radps[i])) / (h * h);
  }
  if (k + 1 < samples.size()) {  // start of [k, k+1]
    const auto &a = samples[k], &b = samples[k + 1];
    const double h = b.t_s - a.t_s;
    acc = std::max(acc, std::abs(6 * (b.q_rad[i] - a.q_rad[i]) - h * (4 * a.qd_radps[i] + 2 * b.qd_radps[i])) / (h * h));
  }
  return acc;
}
}  // namespace

double SafetyChecker::splineAcceleration_radps2(const JointTrajectory& trajectory, std::size_t k, int joint) {
  return trajectory.samples().size() > 1 ? splineAccelerationAt(trajectory.samples(), k, joint) : 0.0;
}

double SafetyChecker::jointSpeed_radps(const JointTrajectory& trajectory, std::size_t k, int joint) {
  return jointSpeedAt(trajectory.samples(), k, joint);
}

double SafetyChecker::peakSplineAcceleration_radps2(const JointTrajectory& trajectory) {
  const auto& samples = trajectory.samples();
  double peak = 0.0;
  for (std::size_t k = 0; k < samples.size() && samples.size() > 1; ++k)
    for (int i = 0; i < 6; ++i) peak = std::max(peak, splineAccelerationAt(samples, k, i));
  return peak;
}

double SafetyChecker::peakAccelerationRatio(const JointTrajectory& trajectory) const {
  return peakSplineAcceleration_radps2(trajectory) / limits_.maxAcceleration_radps2;
}

JointVector SafetyChecker::maxVelocities_radps() const {
  return model_.maxVelocities_radps() * limits_.velocityFraction;
}

double SafetyChecker::peakVelocityRatio(const JointTrajectory& trajectory) const {
  const auto& samples = trajectory.samples();
  const JointVector vmax = maxVelocities_radps();
  double ratio = 0.0;
  for (std::size_t k = 0; k < samples.size(); ++k)
    for (int i = 0; i < 6; ++i) ratio = std::max(ratio, jointSpeedAt(samples, k, i) / vmax[i]);
  return ratio;
}

std::optional<SafetyViolation> SafetyChecker::check(const JointTrajectory& trajectory,
                                                    const std::string& what) const {
  const auto& samples = trajectory.samples();
  const JointVector vmax = model_.maxVelocities_radps() * limits_.velocityFraction;
  for (std::size_t k = 0; k < samples.size(); ++k) {
    const auto& s = samples[k];
    const std::string at = what + " at t = " + fmt(s.t_s, 2) + " s";
    if (auto v = checkConfiguration(s.q_rad, at)) {
      v->sampleIndex = k;
      v->t_s = s.t_s;
      return v;
    }
    for (int i = 0; i < 6; ++i) {
      const double speed = jointSpeedAt(samples, k, i);
      if (speed > vmax[i])
        return SafetyViolation{"velocity limit", k, s.t_s,
                               at + ": joint " + model_.joints()[i].name + " would move at " + fmt(speed) +
                                   " rad/s, above its limit " + fmt(vmax[i]) + " rad/s"};
      const double acc = samples.size() > 1 ? splineAccelerationAt(samples, k, i) : 0.0;
      if (acc > limits_.maxAcceleration_radps2 * (1.0 + 1e-9))
        return SafetyViolation{"acceleration limit", k, s.t_s,
                               at + ": joint " + model_.joints()[i].name + " would accelerate at " + fmt(acc, 2) +
                                   " rad/s^2, above its limit " + fmt(limits_.maxAcceleration_radps2, 2) +
                                   " rad/s^2 (slow the motion down or raise --max-acceleration)"};
    }
  }
  return std::nullopt;
}

}  // namespace srp::execution
