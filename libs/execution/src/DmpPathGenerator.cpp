#include "srp/execution/DmpPathGenerator.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <vector>

#include "srp/core/Error.h"
#include "srp/core/SafeText.h"

namespace srp::execution {

namespace {
/// Longest demonstrated Reach or Move segment a DMP may replay [s].
constexpr double kMaxSegmentDuration_s = 600.0;

double minimumJerk(double tau) {
  tau = std::clamp(tau, 0.0, 1.0);
  return tau * tau * tau * (10.0 - 15.0 * tau + 6.0 * tau * tau);
}

// Distance of p from the straight line through a and b (its side step; a move along
// the line, early, late or past an end, is not counted). 0 when a == b.
double sideStep(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& p) {
  const Eigen::Vector3d chord = b - a;
  if (chord.norm() < 1e-9) return 0.0;
  const Eigen::Vector3d u = chord.normalized(), d = p - a;
  return (d - d.dot(u) * u).norm();
}

// How far p lies beyond the ends of the segment a -> b along its line (past b, or
// behind a); 0 between them and when a == b.
double overshoot(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& p) {
  const Eigen::Vector3d chord = b - a;
  const double length = chord.norm();
  if (length < 1e-9) return 0.0;
  const double along = (p - a).dot(chord / length);
  return std::max({0.0, along - length, -along});
}

/// The demonstration's own largest side step and overshoot [m]: the learned DMP
/// replayed with its own start, goal and duration.
struct DemonstratedExcursion {
  double sideStep_m = 0.0;
  double overshoot_m = 0.0;
};

DemonstratedExcursion demonstratedExcursion(const srp::motion::Dmp& learned, double dt_s) {
  const srp::motion::DmpRollout r = learned.rollout(dt_s);
  const Eigen::Vector3d a = learned.start(), b = learned.goal();
  DemonstratedExcursion e;
  for (long i = 0; i < r.t_s.size(); ++i) {
    const Eigen::Vector3d p = r.y.row(i).transpose();
    e.sideStep_m = std::max(e.sideStep_m, sideStep(a, b, p));
    e.overshoot_m = std::max(e.overshoot_m, overshoot(a, b, p));
  }
  return e;
}

// A smooth clamp of x >= 0 to below `limit`: x where x << limit, tangent to it at 0.
double softClamp(double x, double limit) { return limit > 1e-9 ? limit * std::tanh(x / limit) : 0.0; }
}  // namespace

DmpPathGenerator::DmpPathGenerator(std::map<std::string, LearnedPathSkills> skillsByObject,
                                   const srp::core::Pose3& X_world_demo, MinimumJerkPathGenerator::Options fallback,
                                   double endHeight_m, std::optional<double> moveEndHeight_m)
    : skills_(std::move(skillsByObject)),
      X_world_demo_(X_world_demo),
      fallback_(fallback),
      endHeight_m_(endHeight_m),
      moveEndHeight_m_(moveEndHeight_m.value_or(endHeight_m)) {}

DmpPathGenerator DmpPathGenerator::fromTaskModel(const srp::taskdb::TaskModel& model,
                                                 const srp::core::Pose3& X_world_camera,
                                                 MinimumJerkPathGenerator::Options fallback, double endHeight_m,
                                                 std::optional<double> moveEndHeight_m) {
  std::map<std::string, LearnedPathSkills> skills;
  for (const auto& row : model.skills) {
    if (row.skill != srp::core::SkillType::Reach && row.skill != srp::core::SkillType::Move) continue;
    const auto* grounded = model.findGrounded(row.classId);
    const std::string object = grounded ? grounded->objectName : "class " + std::to_string(row.classId);
    const std::string where = "Skills row " + srp::core::toString(row.skill) + " of the " + object + " of task model " +
                              std::to_string(model.info.id) + ", column Parameters";
    // A row that is there must be usable: never a silent fall-back to another path.
    if (!row.parameters.is_object() || !row.parameters.contains("dmp") || !row.parameters.at("dmp").is_object())
      throw srp::core::InvalidInputError(where + ": no learned DMP (field 'dmp' " +
                                         (row.parameters.is_object() && row.parameters.contains("dmp")
                                              ? std::string("is ") + row.parameters.at("dmp").type_name()
                                              : std::string("is missing")) +
                                         "); re-learn the skills with 'srp motion', or remove the task's Skills rows "
                                         "to execute with minimum-jerk paths");
    const std::string frame = row.parameters.value("frame", std::string("camera"));
    if (frame != "camera")
      throw srp::core::InvalidInputError(where + ": frame '" + srp::core::exportSafeText(frame, 40) +
                                         "' is not supported (DMPs are executed from the camera frame)");
    try {
      srp::motion::Dmp dmp = srp::motion::Dmp::fromJson(row.parameters.at("dmp"));
      // Re-targeted to a start/goal in another direction, an unscaled forcing term
      // replays the demo's excursion in metres along the demo's direction (a 0.3 m
      // detour for a 0.2 m move); the spatial scaling turns and scales it with the
      // new displacement, so the lift stays a lift (srp::motion::ForcingScaling).
      if (dmp.options().mode == srp::motion::Dmp::Options::Mode::Default &&
          dmp.options().scaling != srp::motion::ForcingScaling::Spatial) {
        nlohmann::json j = row.parameters.at("dmp");
        j["config"]["scaling"] = "spatial";
        dmp = srp::motion::Dmp::fromJson(j);
      }
      if (dmp.dimensions() != 3)
        throw srp::core::InvalidInputError("the DMP has " + std::to_string(dmp.dimensions()) + " dimensions, not 3");
      // A rollout is as long as the demonstrated segment: bound it before anything is allocated.
      if (!(dmp.demoDuration_s() <= kMaxSegmentDuration_s))
        throw srp::core::InvalidInputError("the DMP's demonstrated duration " + std::to_string(dmp.demoDuration_s()) +
                                           " s is above " + std::to_string(kMaxSegmentDuration_s) + " s");
      (row.skill == srp::core::SkillType::Reach ? skills[object].reach : skills[object].move) = std::move(dmp);
    } catch (const srp::core::Error& e) {
      throw srp::core::InvalidInputError(where + ": " + e.what() + " (re-learn the skills with 'srp motion')");
    } catch (const nlohmann::json::exception& e) {
      throw srp::core::InvalidInputError(where + ": " + e.what() + " (re-learn the skills with 'srp motion')");
    }
  }
  return DmpPathGenerator(std::move(skills), X_world_camera, fallback, endHeight_m, moveEndHeight_m);
}

const srp::motion::Dmp* DmpPathGenerator::find(srp::core::SkillType skill, const std::string& object) const {
  const auto it = skills_.find(object);
  if (it == skills_.end()) return nullptr;
  const auto& dmp = skill == srp::core::SkillType::Reach ? it->second.reach : it->second.move;
  return dmp ? &*dmp : nullptr;
}

std::string DmpPathGenerator::name() const { return skills_.empty() ? fallback_.name() : "dmp"; }

std::string DmpPathGenerator::sourceFor(srp::core::SkillType skill, const std::string& object) const {
  return find(skill, object) ? "dmp" : fallback_.name();
}

CartesianPath DmpPathGenerator::generate(srp::core::SkillType skill, const std::string& object,
                                         const srp::core::Pose3& X_world_start, const srp::core::Pose3& X_world_goal,
                                         double dt_s) const {
  if (skill != srp::core::SkillType::Reach && skill != srp::core::SkillType::Move)
    throw srp::core::InvalidInputError("DmpPathGenerator: paths exist for Reach and Move only, not " +
                                       srp::core::toString(skill));
  if (!(dt_s > 0.0)) throw srp::core::InvalidInputError("DmpPathGenerator: the sample time must be > 0 s");
  const srp::motion::Dmp* learned = find(skill, object);
  if (!learned) return fallback_.generate(skill, object, X_world_start, X_world_goal, dt_s);
  const double endHeight_m = skill == srp::core::SkillType::Move ? moveEndHeight_m_ : endHeight_m_;
  if (endHeight_m > 0.0) {
    // The tool and the carried part leave and enter a container vertically: a human
    // hand approaches diagonally (so does the demo's DMP), which would sweep the part
    // or the tool through a container wall. The DMP runs between the raised ends.
    srp::core::Pose3 up = X_world_start, down = X_world_goal;
    up.translation().z() = std::max(up.translation().z(), endHeight_m);
    down.translation().z() = std::max(down.translation().z(), endHeight_m);
    CartesianPath path;
    const double kMinSegment_m = 1e-3;
    if ((up.translation() - X_world_start.translation()).norm() > kMinSegment_m)
      path = fallback_.straight(X_world_start, up, dt_s);
    const CartesianPath middle = rollout(*learned, object, up, down, dt_s);
    if (path.empty()) path = middle; else appendPath(path, middle);
    if ((X_world_goal.translation() - down.translation()).norm() > kMinSegment_m)
      appendPath(path, fallback_.straight(down, X_world_goal, dt_s));
    return path;
  }
  return rollout(*learned, object, X_world_start, X_world_goal, dt_s);
}

namespace {

// The rollout ends near, not at, the goal and still moving (the forcing term is not
// quite zero at t = T, and the re-targeted system lags). A quintic correction spread
// over the path (zero, with zero velocity and acceleration, at the start) cancels the
// remaining offset, the end velocity and the end acceleration, so the path ends
// exactly at the goal and at rest: the next segment starts from rest, and a path
// stopped abruptly demanded up to 87 rad/s^2 of a wrist on the demo task's steps.
std::vector<Eigen::Vector3d> endCorrectedPositions(const srp::motion::DmpRollout& r, const Eigen::Vector3d& p_demo_goal) {
  const long n = r.t_s.size();
  const Eigen::Vector3d residual_demo = p_demo_goal - Eigen::Vector3d(r.y.row(n - 1).transpose());
  const double T = r.t_s(n - 1);
  // End velocity and acceleration from the positions themselves (backward differences),
  // as the joint spline through the samples sees them.
  Eigen::Vector3d v_end = Eigen::Vector3d::Zero(), a_end = Eigen::Vector3d::Zero();
  if (n >= 3) {
    const double h1 = r.t_s(n - 1) - r.t_s(n - 2), h2 = r.t_s(n - 2) - r.t_s(n - 3);
    const Eigen::Vector3d v1 = (r.y.row(n - 1) - r.y.row(n - 2)).transpose() / h1;
    const Eigen::Vector3d v2 = (r.y.row(n - 2) - r.y.row(n - 3)).transpose() / h2;
    v_end = v1 + 0.5 * h1 * (v1 - v2) / (0.5 * (h1 + h2));
    a_end = (v1 - v2) / (0.5 * (h1 + h2));
  }
  auto correction = [&](double tau) -> Eigen::Vector3d {
    const double t3 = tau * tau * tau, t4 = t3 * tau, t5 = t4 * tau;
    return minimumJerk(tau) * residual_demo + (-4 * t3 + 7 * t4 - 3 * t5) * (-v_end * T) +
           (0.5 * t3 - t4 + 0.5 * t5) * (-a_end * T * T);
  };
  std::vector<Eigen::Vector3d> p_demo(static_cast<std::size_t>(n));
  for (long i = 0; i < n; ++i) p_demo[i] = Eigen::Vector3d(r.y.row(i).transpose()) + correction(r.t_s(i) / T);
  return p_demo;
}

}  // namespace

CartesianPath DmpPathGenerator::rollout(const srp::motion::Dmp& learned, const std::string& object,
                                        const srp::core::Pose3& X_world_start, const srp::core::Pose3& X_world_goal,
                                        double dt_s) const {

  const Eigen::Vector3d p_world_start = X_world_start.translation(), p_world_goal = X_world_goal.translation();
  const srp::core::Pose3 X_demo_world = X_world_demo_.inverse();
  const MinimumJerkPathGenerator::Options& o = fallback_.options();
  const double chord_m = (p_world_goal - p_world_start).norm();
  const double turn_rad = srp::core::rotationAngleBetween(X_world_start.linear(), X_world_goal.linear());
  const double duration_s = std::max({learned.demoDuration_s(), chord_m / o.meanSpeed_mps,
                                      turn_rad / o.meanAngularSpeed_radps, o.minSegmentDuration_s});

  srp::motion::Dmp dmp = learned;
  const Eigen::Vector3d zero = Eigen::Vector3d::Zero();
  dmp.configure(X_demo_world * p_world_start, X_demo_world * p_world_goal, duration_s, Eigen::VectorXd(zero),
                Eigen::VectorXd(zero));
  const srp::motion::DmpRollout r = dmp.rollout(dt_s);
  const long n = r.t_s.size();
  if (n < 2) throw srp::core::InvalidInputError("DmpPathGenerator: the " + object + " DMP rollout has < 2 samples");

  const Eigen::Quaterniond q_start(X_world_start.linear()), q_goal(X_world_goal.linear());
  const double T = r.t_s(n - 1);
  // The side step is capped at the demonstrator's own, in metres: the spatial scaling
  // scales the demo's excursion with the new chord, and a short demonstrated chord (a
  // hand that hovers or dips before it grasps) re-targeted to a long one would grow
  // into a plunge through the table. Side step = distance from the straight line
  // through start and goal; a path within the demo's largest one is kept as it is, a
  // larger one has its side steps shrunk by one factor (smooth; same ends, at rest;
  // the motion along the line, and so the timing, unchanged).
  //
  // Past the goal (or behind the start) along that line the same holds: the spatial
  // scaling grows a hand that passed the part by 5 cm on a 10 cm demonstrated Reach
  // into a tool that passes the pre-grasp by a quarter of a metre on the robot's
  // 50 cm one, out of the arm's reach. A path that overshoots farther than the
  // demonstrator did (in metres) has its overshoot smoothly clamped to the demo's
  // (softClamp: nearly unchanged where small, tangent at the segment's ends; slower
  // there, the same ends).
  const Eigen::Vector3d p_demo_start = X_demo_world * p_world_start, p_demo_goal = X_demo_world * p_world_goal;
  const std::vector<Eigen::Vector3d> p_demo = endCorrectedPositions(r, p_demo_goal);
  double step_m = 0.0, overshoot_m = 0.0;
  for (long i = 0; i < n; ++i) {
    step_m = std::max(step_m, sideStep(p_demo_start, p_demo_goal, p_demo[i]));
    overshoot_m = std::max(overshoot_m, overshoot(p_demo_start, p_demo_goal, p_demo[i]));
  }
  const DemonstratedExcursion demo = demonstratedExcursion(learned, dt_s);
  const double keep = step_m > demo.sideStep_m ? demo.sideStep_m / step_m : 1.0;
  const bool clampOvershoot = overshoot_m > demo.overshoot_m;
  const Eigen::Vector3d chord = p_demo_goal - p_demo_start;
  const double length = chord.norm();
  const Eigen::Vector3d u = length < 1e-9 ? Eigen::Vector3d::Zero() : Eigen::Vector3d(chord / length);
  CartesianPath path;
  path.reserve(static_cast<std::size_t>(n));
  for (long i = 0; i < n; ++i) {
    CartesianPathSample s;
    s.t_s = r.t_s(i);
    const Eigen::Vector3d d = p_demo[i] - p_demo_start;
    double along = d.dot(u);
    const Eigen::Vector3d side = d - along * u;
    if (clampOvershoot) {
      if (along > length) along = length + softClamp(along - length, demo.overshoot_m);
      if (along < 0.0) along = -softClamp(-along, demo.overshoot_m);
    }
    s.X_world_tcp = srp::core::Pose3::Identity();
    s.X_world_tcp.linear() = q_start.slerp(minimumJerk(s.t_s / T), q_goal).toRotationMatrix();
    s.X_world_tcp.translation() =
        X_world_demo_ * (keep < 1.0 || clampOvershoot ? Eigen::Vector3d(p_demo_start + along * u + keep * side)
                                                      : p_demo[i]);
    path.push_back(s);
  }
  // The rollout converges to the goal; the path contract is start and goal exactly.
  path.front().X_world_tcp = X_world_start;
  path.back().X_world_tcp = X_world_goal;
  // The rollout's last sample lands at T even when T is a hair past the previous
  // sample: two knots microseconds apart made the joint spline's acceleration there
  // 982 rad/s^2 (a random scene's Move). Drop the one before the goal.
  if (path.size() >= 3 && path[path.size() - 1].t_s - path[path.size() - 2].t_s < 0.5 * dt_s)
    path.erase(path.end() - 2);
  return path;
}

}  // namespace srp::execution
