#include "srp/synth/DemoTimeline.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <random>

#include "srp/core/Angles.h"
#include "srp/core/Error.h"
#include "srp/core/Pose.h"

namespace srp::synth {
namespace {

using core::kPi;
constexpr double kGraspPalmAboveTop_m = 0.022;   // palm centre above the object's top at grasp
constexpr double kGraspPalmBehind_m = 0.05;      // palm centre behind the object (fingers over it)
constexpr double kPalmPitch_rad = 8.0 * kPi / 180.0;  // fingers tilted down
constexpr double kClearance_m = 0.03;            // carried object above the container walls
constexpr double kSpotGap_m = 0.008;             // free space between placed objects
constexpr double kWallMargin_m = 0.004;          // free space to the container walls

// A hand key pose: palm centre [m], yaw of the fingers about world z [rad], grip.
struct Key {
  Eigen::Vector3d p_world;
  double yaw_rad = 0.0;
  double grip = 0.0;
};

struct Segment {
  double duration_s;
  Key from, to;
  std::string phase;
  int step;
  bool tremor;
  int attach;  // object index carried during this segment, -1 none
};

srp::core::Pose3 handPose(const Key& k) {
  srp::core::Pose3 X = srp::core::Pose3::Identity();
  X.translation() = k.p_world;
  X.linear() = (Eigen::AngleAxisd(k.yaw_rad, Eigen::Vector3d::UnitZ()) *
                Eigen::AngleAxisd(kPalmPitch_rad, Eigen::Vector3d::UnitY()))
                   .toRotationMatrix();
  return X;
}

double footprintRadius(const srp::core::ObjectClass& c) { return 0.5 * c.dimensions_m.head<2>().norm(); }

// Oriented rectangle of an object's footprint on the table (its bounding box seen from above).
struct Footprint {
  Eigen::Vector2d centre;
  double yaw;
  Eigen::Vector2d half;
};

Footprint footprintOf(const srp::core::ObjectClass& c, const Eigen::Vector3d& p_world, double yaw) {
  return {p_world.head<2>(), yaw, 0.5 * c.dimensions_m.head<2>()};
}

// Separating-axis test: true when the rectangles come closer than gap_m.
bool overlaps(const Footprint& a, const Footprint& b, double gap_m) {
  const Eigen::Rotation2Dd ra(a.yaw), rb(b.yaw);
  const Eigen::Matrix2d A = ra.toRotationMatrix(), B = rb.toRotationMatrix();
  const Eigen::Vector2d d = b.centre - a.centre;
  for (const Eigen::Vector2d& axis : {Eigen::Vector2d(A.col(0)), Eigen::Vector2d(A.col(1)), Eigen::Vector2d(B.col(0)),
                                      Eigen::Vector2d(B.col(1))}) {
    const double extentA = a.half.x() * std::abs(A.col(0).dot(axis)) + a.half.y() * std::abs(A.col(1).dot(axis));
    const double extentB = b.half.x() * std::abs(B.col(0).dot(axis)) + b.half.y() * std::abs(B.col(1).dot(axis));
    if (std::abs(d.dot(axis)) > extentA + extentB + gap_m) return false;
  }
  return true;
}

// Grasp frame of an object: hand above it, fingers along `yaw`.
srp::core::Pose3 graspOffset(double objectHeight_m) {
  srp::core::Pose3 G = srp::core::Pose3::Identity();
  G.translation() = Eigen::Vector3d(-kGraspPalmBehind_m, 0.0, objectHeight_m + kGraspPalmAboveTop_m);
  return G;
}

bool handOutOfView(const HandModel& hand, const srp::core::Pose3& X_world_hand, const srp::core::Scene& scene) {
  const srp::core::Pose3 X_camera_world = scene.X_world_camera.inverse();
  const auto poses = hand.partPoses(0.0);
  for (std::size_t i = 0; i < poses.size(); ++i) {
    const auto& b = hand.parts()[i].bounds_part;
    for (int c = 0; c < 8; ++c) {
      const Eigen::Vector3d corner = b.corner(static_cast<Eigen::AlignedBox3d::CornerType>(c));
      const Eigen::Vector3d p = X_camera_world * X_world_hand * poses[i] * corner;
      const auto uv = scene.intrinsics.project(p);
      if (uv && uv->x() > -20 && uv->x() < scene.intrinsics.width_px + 20 && uv->y() > -20 &&
          uv->y() < scene.intrinsics.height_px + 20)
        return false;
    }
  }
  return true;
}

}  // namespace

double minimumJerk(double tau) {
  const double t = std::clamp(tau, 0.0, 1.0);
  return t * t * t * (10.0 - 15.0 * t + 6.0 * t * t);
}

namespace {

using Uniform = std::uniform_real_distribution<double>;

const srp::core::ObjectClass& classOf(const srp::core::ObjectCatalogue& catalogue, const srp::core::SceneObject& o) {
  return catalogue.at(o.className);
}

int indexOf(const srp::core::Scene& scene, const std::string& id) {
  for (std::size_t i = 0; i < scene.objects.size(); ++i)
    if (scene.objects[i].id == id) return static_cast<int>(i);
  throw srp::core::InvalidInputError("planDemonstration: no object '" + id + "' in the scene");
}

// Randomisation by seed: speed, camera pose jitter, lighting and colours, and
// the moved parts re-placed at random free spots of their source container.
void randomiseScene(DemoTimeline& out, const srp::core::ObjectCatalogue& catalogue,
                    const std::vector<PickPlaceStep>& steps, std::mt19937& rng, Uniform& unit) {
  srp::core::Scene& scene = out.scene;
  out.speedFactor *= 1.0 + 0.15 * unit(rng);
  Eigen::Vector3d dt(unit(rng), unit(rng), unit(rng));
  const Eigen::Vector3d axis = Eigen::Vector3d(unit(rng), unit(rng), unit(rng)).normalized();
  srp::core::Pose3 jitter = srp::core::Pose3::Identity();
  jitter.translation() = 0.005 * dt;
  jitter.linear() = Eigen::AngleAxisd(0.5 * kPi / 180.0 * unit(rng), axis).toRotationMatrix();
  scene.X_world_camera = scene.X_world_camera * jitter;
  scene.lighting.ambient *= 1.0 + 0.1 * unit(rng);
  scene.lighting.diffuse *= 1.0 + 0.1 * unit(rng);
  scene.lighting.direction_world += Eigen::Vector3d(0.15 * unit(rng), 0.15 * unit(rng), 0.0);
  scene.tableRgb = (scene.tableRgb * (1.0 + 0.06 * unit(rng))).cwiseMin(1.0);
  for (auto& [id, rgb] : out.objectRgb) rgb = (rgb * (1.0 + 0.1 * unit(rng))).cwiseMin(1.0).cwiseMax(0.0);
  // Re-place the moved parts at random free spots of their source container.
  std::vector<int> placed, seen;
  for (const auto& s : steps) {
    if (s.sourceId.empty()) continue;
    const int oi = indexOf(scene, s.objectId);
    // Only where an object starts: a later step moving it again starts where the previous one put it.
    if (std::find(seen.begin(), seen.end(), oi) != seen.end()) continue;
    seen.push_back(oi);
    const auto& box = *scene.findObject(s.sourceId);
    const auto& boxClass = classOf(catalogue, box);
    const double r = footprintRadius(classOf(catalogue, scene.objects[oi]));
    const double hx = 0.5 * boxClass.dimensions_m.x() - boxClass.wallThickness_m - kWallMargin_m - r;
    const double hy = 0.5 * boxClass.dimensions_m.y() - boxClass.wallThickness_m - kWallMargin_m - r;
    if (hx <= 0.0 || hy <= 0.0) continue;
    const auto& cls = classOf(catalogue, scene.objects[oi]);
    for (int attempt = 0; attempt < 500; ++attempt) {
      const Eigen::Vector3d p_box(hx * unit(rng), hy * unit(rng), boxClass.wallThickness_m);
      const Eigen::Vector3d p_world = box.X_world_object * p_box;
      const double yaw = srp::core::yawOf(box.X_world_object.linear()) + kPi * unit(rng);
      bool free = true;
      for (int other : placed) {
        const auto& X = scene.objects[other].X_world_object;
        if (overlaps(footprintOf(cls, p_world, yaw),
                     footprintOf(classOf(catalogue, scene.objects[other]), X.translation(), srp::core::yawOf(X.linear())),
                     kSpotGap_m))
          free = false;
      }
      if (!free) continue;
      scene.objects[oi].X_world_object = srp::core::makePoseYPR(p_world, yaw, 0.0, 0.0);
      placed.push_back(oi);
      break;
    }
  }
}

// Where the demonstrator stands: opposite the robot, the hand's rest just out of view.
struct Stance {
  Key rest;
  Eigen::Vector3d shoulder;
};

Stance demonstratorStance(const srp::core::Scene& scene, const HandModel& hand, const DemoOptions& options) {
  Eigen::Vector3d cameraFoot(scene.X_world_camera.translation().x(), scene.X_world_camera.translation().y(), 0.0);
  Eigen::Vector3d away = cameraFoot - Eigen::Vector3d(scene.X_world_base.translation().x(),
                                                      scene.X_world_base.translation().y(), 0.0);
  if (options.demonstratorSide_world.norm() > 1e-9) {
    // A given side: from the table point on the camera's optical axis (the
    // camera's foot when the axis does not meet the table).
    away = Eigen::Vector3d(options.demonstratorSide_world.x(), options.demonstratorSide_world.y(), 0.0);
    const Eigen::Vector3d o = scene.X_world_camera.translation(), d = scene.X_world_camera.linear().col(2);
    if (d.z() < -1e-6 && o.z() > 0.0) cameraFoot = o - (o.z() / d.z()) * d;
  }
  if (away.norm() < 1e-6) away = Eigen::Vector3d::UnitY();
  away.normalize();
  const double restYaw = std::atan2(-away.y(), -away.x());
  Key rest{cameraFoot + Eigen::Vector3d(0, 0, 0.22), restYaw, 0.0};
  for (int i = 0; i < 200 && !handOutOfView(hand, handPose(rest), scene); ++i) rest.p_world += 0.02 * away;
  const Eigen::Vector3d shoulder = rest.p_world + 0.25 * away + Eigen::Vector3d(0, 0, 0.15);
  return {rest, shoulder};
}

/// The heading from `from` to `target` in the table plane.
double yawFrom(const Eigen::Vector3d& from, const Eigen::Vector3d& target) {
  const Eigen::Vector3d d = target - from;
  return std::atan2(d.y(), d.x());
}

/// The free spot for step `si` (object `oi`) in its target container, beside the reference when given:
/// the one nearest the goal (moved by `spotJitter`) where the part, turned as the hand turns toward
/// the spot from `shoulder` (plus `yawTurn`), overlaps no other part where the plan leaves it.
Eigen::Vector3d freeSpot(const srp::core::Scene& scene, const srp::core::ObjectCatalogue& catalogue,
                         const PickPlaceStep& s, std::size_t si, int oi,
                         const std::vector<srp::core::Pose3>& finalPoses, const Eigen::Vector3d& shoulder,
                         double yawObject, double yawGrasp, double yawTurn, const Eigen::Vector2d& spotJitter) {
  const auto& cls = classOf(catalogue, scene.objects[oi]);
  const auto& box = *scene.findObject(s.targetId);
  const auto& boxClass = classOf(catalogue, box);
  const double r = footprintRadius(cls);
  const double hx = 0.5 * boxClass.dimensions_m.x() - boxClass.wallThickness_m - kWallMargin_m - r;
  const double hy = 0.5 * boxClass.dimensions_m.y() - boxClass.wallThickness_m - kWallMargin_m - r;
  Eigen::Vector3d goal_world = box.X_world_object * Eigen::Vector3d(-0.25 * boxClass.dimensions_m.x(), 0, 0);
  if (!s.referenceId.empty()) goal_world = finalPoses[indexOf(scene, s.referenceId)].translation();
  double bestScore = std::numeric_limits<double>::infinity();
  Eigen::Vector3d best_world = Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
  for (double x = -hx; x <= hx + 1e-9; x += 0.0025)
    for (double y = -hy; y <= hy + 1e-9; y += 0.0025) {
      const Eigen::Vector3d p_world = box.X_world_object * Eigen::Vector3d(x, y, boxClass.wallThickness_m);
      const double yawEnd = yawObject + yawFrom(shoulder, p_world) + yawTurn - yawGrasp;
      bool free = true;
      for (std::size_t j = 0; j < scene.objects.size() && free; ++j) {
        if (static_cast<int>(j) == oi || classOf(catalogue, scene.objects[j]).kind != srp::core::ObjectKind::Part) continue;
        if (overlaps(footprintOf(cls, p_world, yawEnd),
                     footprintOf(classOf(catalogue, scene.objects[j]), finalPoses[j].translation(),
                                 srp::core::yawOf(finalPoses[j].linear())),
                     kSpotGap_m))
          free = false;
      }
      if (!free) continue;
      const double score = ((p_world - goal_world).head<2>() + spotJitter).norm();
      if (score < bestScore) {
        bestScore = score;
        best_world = p_world;
      }
    }
  if (!std::isfinite(bestScore))
    throw srp::core::InvalidInputError("plan step " + std::to_string(si + 1) + ": no free spot for the " +
                                       s.objectId + " in the " + s.targetId);
  return best_world;
}

// The demonstration as hand key-pose segments: idle at rest; per step reach,
// grasp, move (carrying the object) to a free spot of the target container,
// release, retract; back to rest; idle.
std::vector<Segment> planSegments(const srp::core::Scene& scene, const srp::core::ObjectCatalogue& catalogue,
                                  const std::vector<PickPlaceStep>& steps, const DemoOptions& options,
                                  const Stance& stance, double speed, std::mt19937& rng, Uniform& unit) {
  const Key& rest = stance.rest;
  auto yawToward = [&](const Eigen::Vector3d& target) { return yawFrom(stance.shoulder, target); };
  double wallTop_m = 0.0;
  for (const auto& o : scene.objects)
    if (classOf(catalogue, o).kind == srp::core::ObjectKind::Container)
      wallTop_m = std::max(wallTop_m, o.X_world_object.translation().z() + classOf(catalogue, o).dimensions_m.z());

  std::vector<Segment> segments;
  std::vector<srp::core::Pose3> X_world_objects;
  for (const auto& o : scene.objects) X_world_objects.push_back(o.X_world_object);
  std::vector<srp::core::Pose3> finalPoses = X_world_objects;  // where each object ends (planning state)

  segments.push_back({options.idleStart_s, rest, rest, "idle", -1, false, -1});
  Key current = rest;
  for (std::size_t si = 0; si < steps.size(); ++si) {
    const auto& s = steps[si];
    const int step = static_cast<int>(si);
    const int oi = indexOf(scene, s.objectId);
    const auto& cls = classOf(catalogue, scene.objects[oi]);
    const double h = cls.dimensions_m.z();
    const srp::core::Pose3 X_world_start = finalPoses[oi];
    const Eigen::Vector3d p_start = X_world_start.translation();
    const double yawObject = srp::core::yawOf(X_world_start.linear());

    // Grasp pose: fingers along the approach direction.
    const double yawGrasp = yawToward(p_start);
    const srp::core::Pose3 G = graspOffset(h);
    auto palmAt = [&](const Eigen::Vector3d& p_object, double yaw) {
      Key k;
      k.yaw_rad = yaw;
      k.p_world = p_object + Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) * G.translation();
      return k;
    };
    Key grasp = palmAt(p_start, yawGrasp);
    const double travelZ = wallTop_m + kClearance_m + h + kGraspPalmAboveTop_m;
    Key preGrasp = grasp;
    preGrasp.p_world.z() = std::max(travelZ, grasp.p_world.z() + 0.05);

    // Free spot in the target container, beside the reference when given.
    const Eigen::Vector2d spotJitter = options.randomise ? Eigen::Vector2d(0.003 * unit(rng), 0.003 * unit(rng))
                                                         : Eigen::Vector2d::Zero();
    const double yawTurn = options.randomise ? 0.2 * unit(rng) : 0.0;
    const Eigen::Vector3d best_world =
        freeSpot(scene, catalogue, s, si, oi, finalPoses, stance.shoulder, yawObject, yawGrasp, yawTurn, spotJitter);
    const double yawPlace = yawToward(best_world) + yawTurn;
    Key place = palmAt(best_world, yawPlace);
    place.grip = 1.0;
    Key prePlace = place;
    prePlace.p_world.z() = std::max(travelZ, place.p_world.z() + 0.05);
    const srp::core::Pose3 X_world_end =
        srp::core::makePoseYPR(best_world, core::angleDifference(yawObject + yawPlace - yawGrasp, 0.0), 0.0, 0.0);
    finalPoses[oi] = X_world_end;

    // Durations grow with distance; the final approach is slow (slow-down before grasp).
    auto travel = [&](const Key& a, const Key& b, double base_s, double perMetre_s) {
      return (base_s + perMetre_s * (b.p_world - a.p_world).norm()) / speed;
    };
    Key graspClosed = grasp;
    graspClosed.grip = 1.0;
    Key lift = graspClosed;
    lift.p_world.z() = preGrasp.p_world.z();
    Key released = place;
    released.grip = 0.0;
    Key retract = released;
    retract.p_world.z() = prePlace.p_world.z();
    Key preGraspOpen = preGrasp;
    preGraspOpen.grip = 0.0;
    segments.push_back({travel(current, preGrasp, 0.7, 1.6), current, preGraspOpen, "reach", step, true, -1});
    segments.push_back({0.6 / speed, preGraspOpen, grasp, "reach", step, true, -1});
    segments.push_back({0.45 / speed, grasp, graspClosed, "grasp", step, false, -1});
    segments.push_back({0.5 / speed, graspClosed, lift, "move", step, true, oi});
    Key prePlaceCarry = prePlace;
    segments.push_back({travel(lift, prePlace, 0.6, 1.8), lift, prePlaceCarry, "move", step, true, oi});
    segments.push_back({0.6 / speed, prePlaceCarry, place, "move", step, true, oi});
    segments.push_back({0.4 / speed, place, released, "release", step, false, -1});
    segments.push_back({0.4 / speed, released, retract, "retract", step, true, -1});
    current = retract;
  }
  Key restEnd = rest;
  segments.push_back({(0.8 + 1.2 * (restEnd.p_world - current.p_world).norm()) / speed, current, restEnd, "retract", -1, true, -1});
  segments.push_back({options.idleEnd_s, restEnd, restEnd, "idle", -1, false, -1});
  return segments;
}

// Sampling at the camera rate: minimum-jerk interpolation within each
// segment, tremor, and the carried object attached to the hand from the
// first to the last frame of its carrying segments (the events).
void sampleFrames(DemoTimeline& out, const std::vector<Segment>& segments, const std::vector<PickPlaceStep>& steps,
                  const DemoOptions& options, std::mt19937& rng, Uniform& unit) {
  const srp::core::Scene& scene = out.scene;
  std::vector<srp::core::Pose3> X_world_objects;
  for (const auto& o : scene.objects) X_world_objects.push_back(o.X_world_object);
  double total_s = 0.0;
  for (const auto& seg : segments) total_s += seg.duration_s;
  const int frameCount = static_cast<int>(std::floor(total_s * scene.fps)) + 1;
  // Tremor: three sinusoids per axis at 8-12 Hz with random phases.
  std::array<std::array<double, 3>, 3> tremorFreq{}, tremorPhase{};
  for (auto& axis : tremorFreq)
    for (auto& f : axis) f = 10.0 + 2.0 * unit(rng);
  for (auto& axis : tremorPhase)
    for (auto& ph : axis) ph = kPi * unit(rng);

  std::vector<int> segmentOfFrame(frameCount);
  out.frames.reserve(frameCount);
  std::size_t segIndex = 0;
  double segStart_s = 0.0;
  int attached = -1;
  srp::core::Pose3 X_hand_attached = srp::core::Pose3::Identity();
  std::map<int, int> eventOf;  // object index -> index in out.events
  for (int k = 0; k < frameCount; ++k) {
    const double t = k / scene.fps;
    while (segIndex + 1 < segments.size() && t >= segStart_s + segments[segIndex].duration_s - 1e-12) {
      segStart_s += segments[segIndex].duration_s;
      ++segIndex;
    }
    const Segment& seg = segments[segIndex];
    const double tau = seg.duration_s > 0.0 ? (t - segStart_s) / seg.duration_s : 1.0;
    const double m = minimumJerk(tau);
    Key key;
    key.p_world = seg.from.p_world + m * (seg.to.p_world - seg.from.p_world);
    key.yaw_rad = seg.from.yaw_rad + m * core::angleDifference(seg.to.yaw_rad, seg.from.yaw_rad);
    key.grip = seg.from.grip + m * (seg.to.grip - seg.from.grip);
    if (seg.tremor) {
      const double envelope = std::sin(kPi * std::clamp(tau, 0.0, 1.0));
      for (int a = 0; a < 3; ++a) {
        double v = 0.0;
        for (int j = 0; j < 3; ++j) v += std::sin(2.0 * kPi * tremorFreq[a][j] * t + tremorPhase[a][j]) / 3.0;
        key.p_world[a] += options.tremorAmplitude_m * envelope * v;
      }
    }
    FrameState f;
    f.index = k;
    f.t_s = t;
    f.X_world_hand = handPose(key);
    f.grip = key.grip;
    f.phase = seg.phase;
    f.step = seg.step;
    // Attach at the first frame of a carrying segment, detach after its last.
    if (seg.attach >= 0 && attached != seg.attach) {
      attached = seg.attach;
      X_hand_attached = f.X_world_hand.inverse() * X_world_objects[attached];
      ObjectEvent e;
      e.objectId = scene.objects[attached].id;
      e.step = seg.step;
      e.graspFrame = k;
      const auto& s = steps[seg.step];
      e.sourceId = s.sourceId;
      e.targetId = s.targetId;
      e.referenceId = s.referenceId;
      e.X_world_object_start = X_world_objects[attached];
      e.X_hand_object = X_hand_attached;
      eventOf[attached] = static_cast<int>(out.events.size());
      out.events.push_back(e);
    } else if (seg.attach < 0 && attached >= 0) {
      ObjectEvent& e = out.events[eventOf[attached]];
      e.releaseFrame = k - 1;
      e.X_world_object_end = X_world_objects[attached];
      attached = -1;
    }
    if (attached >= 0) X_world_objects[attached] = f.X_world_hand * X_hand_attached;
    f.carriedObject = attached;
    f.X_world_objects = X_world_objects;
    out.frames.push_back(std::move(f));
  }
}

}  // namespace

DemoTimeline planDemonstration(const srp::core::Scene& sceneIn, const srp::core::ObjectCatalogue& catalogue,
                               const std::vector<PickPlaceStep>& steps, const HandModel& hand,
                               const DemoOptions& options) {
  srp::core::require(!steps.empty(), "planDemonstration: the plan has no steps");
  srp::core::require(sceneIn.fps > 0.0, "planDemonstration: scene camera fps must be positive");
  std::mt19937 rng(options.seed);
  Uniform unit(-1.0, 1.0);

  DemoTimeline out;
  out.scene = sceneIn;
  out.steps = steps;
  for (const auto& o : out.scene.objects) out.objectRgb[o.id] = srp::core::instanceRgb(o, classOf(catalogue, o));  // each instance in its own colour
  out.speedFactor = options.speedFactor;
  if (options.randomise) randomiseScene(out, catalogue, steps, rng, unit);
  const double speed = std::max(out.speedFactor, 0.1);
  const Stance stance = demonstratorStance(out.scene, hand, options);
  const std::vector<Segment> segments = planSegments(out.scene, catalogue, steps, options, stance, speed, rng, unit);
  sampleFrames(out, segments, steps, options, rng, unit);
  return out;
}

}  // namespace srp::synth
