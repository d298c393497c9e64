#include "srp/execution/TaskExecutor.h"

#include <chrono>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <sstream>

#include "srp/core/Error.h"
#include "srp/core/OutputFile.h"
#include "srp/core/Pose.h"
#include "srp/execution/MinimumJerkPathGenerator.h"
#include "srp/execution/PathRetimer.h"

namespace srp::execution {
namespace {

using srp::core::Pose3;
using Clock = std::chrono::steady_clock;

std::vector<WorldBox> containerWalls(const CellDescription& scene) {
  std::vector<WorldBox> walls;
  for (const auto& b : scene.staticBoxes())
    if (b.owner != "table") walls.push_back(b);
  return walls;
}

std::string describeRelations(const std::vector<SpatialRelation>& relations) {
  std::string s;
  for (const auto& r : relations)
    s += (s.empty() ? "" : ", ") + (r.corner.empty() ? r.relation : "in the " + r.corner + " corner of") + " " +
         r.landmark.describe() + (r.secondLandmark ? " and " + r.secondLandmark->describe() : "");
  return s.empty() ? "(no target)" : s;
}

Pose3 toolDownAt(const Pose3& X_world_object, double height_m) {
  Pose3 X = X_world_object * Eigen::Translation3d(0, 0, height_m);
  X.linear() = X.linear() * Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitX()).toRotationMatrix();
  return X;
}

Pose3 raised(Pose3 X, double dz_m) {
  X.translation().z() += dz_m;
  return X;
}

}  // namespace

TaskExecutor::TaskExecutor(const RobotModel& model, const CellDescription& scene, const JointVector& q_home,
                           std::shared_ptr<const CartesianPathGenerator> generator, Options options)
    : model_(model),
      ik_(model),
      scene_(scene),
      generator_(std::move(generator)),
      options_(options),
      safety_(model, scene.X_world_base, options.safety, containerWalls(scene)),
      placement_(options.placement),
      jointPlacement_(options.placement, options.jointPlacement),
      sim_(std::make_unique<CellSimulator>(model, scene, q_home, options.simulation)) {
  if (!generator_) throw srp::core::InvalidInputError("TaskExecutor: a Cartesian path generator is required");
  if (auto v = safety_.checkConfiguration(q_home, "home configuration"))
    throw srp::core::InvalidInputError("TaskExecutor: the start configuration is unsafe: " + v->message);
}

TaskExecutor::~TaskExecutor() = default;

JointVector TaskExecutor::defaultHome(const RobotModel& model, const Pose3& X_world_base, const Pose3& X_world_target) {
  const UrInverseKinematics ik(model);
  const Eigen::Vector3d p_base = X_world_base.inverse() * X_world_target.translation();
  JointVector seed;
  // At q1 = 0 the UR arm reaches along -x of its base: turn it towards the target.
  seed << core::angleDifference(std::atan2(p_base.y(), p_base.x()), M_PI), -1.6, 1.6, -1.57, -1.57, 0.0;
  const auto q = ik.solveNearestTcp(X_world_base.inverse() * X_world_target, seed);
  if (!q)
    throw srp::core::InvalidInputError("TaskExecutor::defaultHome: the home pose is out of the arm's reach; "
                                       "check X_world_base in the scene");
  return *q;
}

void TaskExecutor::writeJointLogCsv(const std::string& path) const {
  std::ostringstream out;
  out << "t_s";
  for (int i = 0; i < 6; ++i) out << "," << model_.joints()[i].name << "_rad";
  for (int i = 0; i < 6; ++i) out << "," << model_.joints()[i].name << "_ref_rad";
  out << ",grasped\n" << std::setprecision(8);
  for (const auto& s : sim_->log()) {
    out << s.t_s;
    for (int i = 0; i < 6; ++i) out << "," << s.q_rad[i];
    for (int i = 0; i < 6; ++i) out << "," << s.qRef_rad[i];
    out << "," << s.graspedPart.value_or("") << "\n";
  }
  srp::core::writeFileAtomically(path, out.str());
}

CellDescription TaskExecutor::perceive() const {
  CellDescription scene = scene_;
  for (auto& o : scene.objects)
    if (o.kind == CellObjectKind::Part) o.X_world_object = sim_->X_world_part(o.name);
  return scene;
}

ExecutionReport TaskExecutor::run(const ExecutionPlan& plan, const std::function<void(const StepReport&)>& onStep) {
  ExecutionReport report;
  report.pathGenerator = generator_->name();
  report.minTableClearance_m = std::numeric_limits<double>::infinity();
  const double t0 = sim_->time_s(), wall0 = sim_->wallSeconds();
  // Every step's placement, planned together before anything moves.
  const auto planStart = Clock::now();
  std::vector<PlannedPlacement> planned = jointPlacement_.plan(perceive(), plan);
  const double jointShare_s = std::chrono::duration<double>(Clock::now() - planStart).count() /
                              static_cast<double>(std::max<std::size_t>(1, plan.steps.size()));
  for (std::size_t i = 0; i < plan.steps.size(); ++i) {
    report.steps.push_back(runStep(i, plan, planned));
    report.steps.back().planning_s += jointShare_s;
    if (report.steps.back().status == StepStatus::Done)
      report.minTableClearance_m = std::min(report.minTableClearance_m, report.steps.back().minTableClearance_m);
    if (onStep) onStep(report.steps.back());
  }
  report.simulated_s = sim_->time_s() - t0;
  report.simulationWall_s = sim_->wallSeconds() - wall0;
  return report;
}

/// One planned segment of a step: its Cartesian path and the joint trajectory.
struct TaskExecutor::Segment {
  std::string what;
  CartesianPath path;
  JointTrajectory joints;
  double slowDown = 1.0;  ///< > 1: slowed (locally, PathRetimer) to respect the joint speed and acceleration limits
};

StepReport TaskExecutor::runStep(std::size_t index, const ExecutionPlan& plan, std::vector<PlannedPlacement>& planned) {
  const ExecutionStep& step = plan.steps[index];
  StepReport r;
  r.index = static_cast<int>(index);
  r.object = step.object.describe();
  r.relation = describeRelations(step.target);
  const auto planStart = Clock::now();
  const double simStart = sim_->time_s();
  auto finish = [&](StepStatus status, std::string reason) {
    r.status = status;
    r.reason = std::move(reason);
    if (r.planning_s == 0.0) r.planning_s = std::chrono::duration<double>(Clock::now() - planStart).count();
    r.simulated_s = sim_->time_s() - simStart;
    return r;
  };

  // --- perceive and find the source and target locations (fig. 7.11, lines 3-5)
  const CellDescription scene = perceive();
  // One instance: name, colour, ordinal, superlative, the phrase's relations and
  // the step's source locations (SceneGrounder); else the candidates or the reason.
  const CellObject* part = nullptr;
  try {
    part = &SceneGrounder(scene, options_.placement.grounding).ground(step.object, step.source, CellObjectKind::Part);
  } catch (const GroundingError& e) {
    return finish(StepStatus::Skipped, e.what());
  }
  r.object = part->name;
  r.X_world_start = part->X_world_object;
  // The planned place, recomputed from the landmarks where they came to rest (the same
  // candidate: within kSamePlace_m, a few times the placement error); else as planned if
  // the scene still allows it; else the scene is not what the plan expected (a part moved,
  // another instance): the remaining steps are planned again, together, from here.
  constexpr double kSamePlace_m = 5e-4;
  const std::optional<Placement> again =
      planned[index].part == part->name
          ? placement_.candidateNear(scene, *part, step, planned[index].placement, kSamePlace_m)
          : std::nullopt;
  if (again) {
    planned[index].placement = *again;
  } else if (planned[index].part != part->name ||
             (planned[index].placement.X_world_object &&
              !placement_.stillAllowed(scene, *part, step, planned[index].placement))) {
    ExecutionPlan rest;
    rest.steps.assign(plan.steps.begin() + static_cast<std::ptrdiff_t>(index), plan.steps.end());
    const std::vector<PlannedPlacement> replanned = jointPlacement_.plan(scene, rest);
    std::copy(replanned.begin(), replanned.end(), planned.begin() + static_cast<std::ptrdiff_t>(index));
  }
  const Placement placement = planned[index].placement;
  if (!placement.X_world_object) return finish(StepStatus::Skipped, placement.reason);
  r.X_world_planned = placement.X_world_object;

  // --- motion generation: Cartesian paths -> IK (nearest branch) -> safety check.
  std::vector<Segment> segments;
  if (auto failure = planMotion(scene, *part, *placement.X_world_object, segments))
    return finish(StepStatus::Refused, *failure);
  r.planning_s = std::chrono::duration<double>(Clock::now() - planStart).count();
  for (const auto& seg : segments) r.slowDown = std::max(r.slowDown, seg.slowDown);
  const std::string reachSource = generator_->sourceFor(srp::core::SkillType::Reach, part->name);
  const std::string moveSource = generator_->sourceFor(srp::core::SkillType::Move, part->name);
  r.pathSource = reachSource == moveSource ? reachSource : "Reach " + reachSource + ", Move " + moveSource;

  // --- execution on the simulated UR5
  if (auto failure = executeSegments(part->name, segments, r)) return finish(StepStatus::Failed, *failure);

  // --- check the outcome
  return finish(StepStatus::Done, checkOutcome(scene, *part, step, placement, r));
}

// The suction cup may take the part turned by 0 or pi about the tool axis (the
// part still ends at its planned yaw: the release turns by the same pi); both are
// planned and the one keeping the last wrist joint nearer zero is used, so wrist
// turns do not pile up over the steps until the joint limit forces a branch jump.
std::optional<std::string> TaskExecutor::planMotion(const CellDescription& scene, const CellObject& part,
                                                    const Pose3& X_world_target, std::vector<Segment>& segments) const {
  auto wristLoad = [](const std::vector<Segment>& s) {
    double m = 0.0;
    for (const auto& seg : s)
      for (const auto& sample : seg.joints.samples()) m = std::max(m, std::abs(sample.q_rad[5]));
    return m;
  };
  std::vector<Segment> alternative;
  const std::optional<std::string> failure = planVariant(scene, part, X_world_target, 0.0, segments);
  const std::optional<std::string> failureTurned = planVariant(scene, part, X_world_target, M_PI, alternative);
  if (failure && failureTurned) return failure;
  if (failure || (!failureTurned && wristLoad(alternative) < wristLoad(segments))) segments = std::move(alternative);
  return std::nullopt;
}

std::optional<std::string> TaskExecutor::planVariant(const CellDescription& scene, const CellObject& part,
                                                     const Pose3& X_world_target, double turn_rad,
                                                     std::vector<Segment>& segments) const {
  const double h = part.size_m.z();
  const MinimumJerkPathGenerator straight(MinimumJerkPathGenerator::Options{});
  const double dt = options_.sampleTime_s;
  const Pose3 X_base_world = scene.X_world_base.inverse();
  const Eigen::AngleAxisd turn(turn_rad, Eigen::Vector3d::UnitZ());
  const Pose3 grasp = toolDownAt(part.X_world_object, h) * turn;
  const Pose3 preGrasp = raised(grasp, options_.approachOffset_m);
  const Pose3 release = toolDownAt(X_world_target, h + options_.releaseHeight_m) * turn;
  const Pose3 preRelease = raised(release, options_.approachOffset_m);
  const Pose3 postRelease = raised(release, options_.retreat_m);
  try {
    segments.push_back({"Reach", generator_->generate(srp::core::SkillType::Reach, part.name, sim_->X_world_tcp(), preGrasp, dt), {}});
    segments.push_back({"approach", straight.straight(preGrasp, grasp, dt), {}});
    segments.push_back({"lift", straight.straight(grasp, preGrasp, dt), {}});
    segments.push_back({"Move", generator_->generate(srp::core::SkillType::Move, part.name, preGrasp, preRelease, dt), {}});
    segments.push_back({"lower", straight.straight(preRelease, release, dt), {}});
    segments.push_back({"retreat", straight.straight(release, postRelease, dt), {}});
  } catch (const srp::core::Error& e) {
    return std::string("path generation: ") + e.what();
  }
  const PathRetimer retimer(
      safety_, PathRetimer::Options{options_.velocityMargin, options_.accelerationMargin, options_.maxSlowDown});
  JointVector q = sim_->jointPositions();
  for (auto& seg : segments) {
    const std::string what = seg.what + " of the " + part.name;
    std::vector<double> times;
    std::vector<JointVector> qs;
    for (const auto& s : seg.path) {
      const auto sol = ik_.solveNearestTcp(X_base_world * s.X_world_tcp, q);
      if (!sol) {
        const Eigen::Vector3d p = s.X_world_tcp.translation();
        std::ostringstream why;
        why << what << ": tool pose at (" << p.x() << ", " << p.y() << ", " << p.z()
            << ") m is out of the arm's reach (no inverse kinematics solution within the joint limits)";
        return why.str();
      }
      q = *sol;
      times.push_back(s.t_s);
      qs.push_back(q);
    }
    // Same path, slower where it is too fast for the joints (PathRetimer); a path that
    // would need more than maxSlowDown is left as it is and refused by the check.
    RetimedTrajectory retimed = retimer.retime(JointTrajectory::fromPositions(times, qs));
    seg.joints = std::move(retimed.trajectory);
    if (retimed.method == RetimedTrajectory::Method::Topp || retimed.method == RetimedTrajectory::Method::Uniform)
      seg.slowDown = retimed.slowDown;
    if (auto v = safety_.check(seg.joints, what)) return "safety: " + v->message;
  }
  return std::nullopt;
}

std::optional<std::string> TaskExecutor::executeSegments(const std::string& part, const std::vector<Segment>& segments,
                                                         StepReport& r) {
  r.minTableClearance_m = std::numeric_limits<double>::infinity();
  auto track = [&](const Segment& seg) {
    const TrackingResult t = sim_->track(seg.joints, options_.settle_s);
    r.minTableClearance_m = std::min(r.minTableClearance_m, t.minTableClearance_m);
    r.maxJointError_rad = std::max(r.maxJointError_rad, t.maxJointError_rad);
  };
  track(segments[0]);
  track(segments[1]);
  if (auto failure = sim_->grasp(part)) return "Grasp: " + *failure;
  track(segments[2]);
  track(segments[3]);
  track(segments[4]);
  sim_->release();
  track(segments[5]);
  return std::nullopt;
}

std::string TaskExecutor::checkOutcome(const CellDescription& scene, const CellObject& part,
                                       const ExecutionStep& step, const Placement& placement, StepReport& r) const {
  const Pose3 X_final = sim_->X_world_part(part.name);
  r.X_world_final = X_final;
  r.placementError_m = (X_final.translation() - placement.X_world_object->translation()).norm();
  r.yawError_rad = srp::core::angleDifference(srp::core::yawOf(X_final.linear()),
                                              srp::core::yawOf(placement.X_world_object->linear()));
  const bool upright = X_final.linear().col(2).z() > std::cos(10.0 * M_PI / 180.0);
  CellObject placed = part;
  placed.X_world_object = X_final;
  bool holds = r.placementError_m <= options_.placementTolerance_m && upright;
  if (!placement.container.empty()) {
    r.insideContainer = isInside(placed, *scene.find(placement.container));
    holds = holds && r.insideContainer;
  }
  if (!placement.neighbour.empty()) {
    const CellObject& n = *scene.find(placement.neighbour);
    const Pose3 X_n = sim_->X_world_part(n.name);
    const Eigen::Vector2d d = X_final.translation().head<2>() - X_n.translation().head<2>();
    const Eigen::Vector2d dir = d.normalized();
    auto extent = [&](const Eigen::Vector3d& size, const Pose3& X) {
      const Eigen::Vector2d ax = X.linear().col(0).head<2>().normalized(), ay = X.linear().col(1).head<2>().normalized();
      return std::abs(dir.dot(ax)) * size.x() / 2 + std::abs(dir.dot(ay)) * size.y() / 2;
    };
    const double gap = d.norm() - extent(n.size_m, X_n) - extent(part.size_m, X_final);
    r.neighbourRelationHolds = gap > -1e-3 && gap <= placement_.options().neighbourGap_m + options_.neighbourTolerance_m;
    holds = holds && r.neighbourRelationHolds;
  }
  // Every target relation on the scene as it is now (the other parts may have moved too).
  CellDescription now = perceive();
  r.relationChecks = placement_.check(now, *now.find(part.name), step, placement.landmarkIds);
  for (const auto& c : r.relationChecks) holds = holds && c.holds;
  r.relationsHold = holds && r.minTableClearance_m > 0.0;
  if (holds) return "";
  // Say which check failed.
  std::ostringstream why;
  why << std::fixed << std::setprecision(1) << "placed, but";
  std::string sep = " ";
  if (r.placementError_m > options_.placementTolerance_m)
    why << sep << r.placementError_m * 1000 << " mm from the planned pose (tolerance "
        << options_.placementTolerance_m * 1000 << " mm)", sep = "; ";
  if (!upright) why << sep << "not upright", sep = "; ";
  if (!placement.container.empty() && !r.insideContainer) why << sep << "not inside the " << placement.container, sep = "; ";
  if (!placement.neighbour.empty() && !r.neighbourRelationHolds)
    why << sep << "not next to the " << placement.neighbour, sep = "; ";
  for (const auto& c : r.relationChecks)
    if (!c.holds) why << sep << c.relation << " " << c.landmarks << " does not hold (" << c.detail << ")", sep = "; ";
  return why.str();
}

}  // namespace srp::execution
