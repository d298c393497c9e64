#include "srp/execution/CellSimulator.h"

#include <Simbody.h>

#include <array>
#include <chrono>
#include <cmath>

#include "srp/core/Error.h"
#include "srp/execution/SafetyChecker.h"

namespace srp::execution {
namespace {

using srp::core::Pose3;
namespace stk = SimTK;

stk::Transform toTransform(const Pose3& X) {
  const Eigen::Quaterniond q(X.linear());
  return stk::Transform(stk::Rotation(stk::Quaternion(q.w(), q.x(), q.y(), q.z())),
                        stk::Vec3(X.translation().x(), X.translation().y(), X.translation().z()));
}

Pose3 toPose(const stk::Transform& T) {
  const stk::Quaternion q = T.R().convertRotationToQuaternion();
  return srp::core::makePose(Eigen::Vector3d(T.p()[0], T.p()[1], T.p()[2]),
                             Eigen::Quaterniond(q[0], q[1], q[2], q[3]));
}

stk::Vec3 toVec3(const Eigen::Vector3d& v) { return stk::Vec3(v.x(), v.y(), v.z()); }

stk::MassProperties massProperties(double mass_kg, const Eigen::Vector3d& com, const Eigen::Matrix3d& I_com) {
  stk::Mat33 m;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) m(r, c) = 0.5 * (I_com(r, c) + I_com(c, r));
  const stk::Inertia Icom(m);
  return stk::MassProperties(mass_kg, toVec3(com), Icom.shiftFromMassCenter(toVec3(com), mass_kg));
}

/// The reference the joint controller tracks: a trajectory started at tStart_s.
struct Reference {
  JointTrajectory trajectory;
  double tStart_s = 0.0;
  JointTrajectorySample at(double t_s) const { return trajectory.at(t_s - tStart_s); }
};

/// A box collision shape fixed to a body (Ground for the table and containers).
struct ContactBox {
  stk::MobilizedBodyIndex body;
  stk::Transform X_B_box;
  stk::Vec3 half;
  double boundRadius = 0.0;
  int part = -1;  ///< index of the part owning the box, -1 for static boxes
};

struct PartGeometry {
  stk::MobilizedBodyIndex body;
  std::vector<stk::Vec3> corners_B;  ///< contact points in the part frame
  int bottomPoints = 4;              ///< how many of them lie on the bottom face (they share the weight)
  stk::Vec3 centre_B;
  double boundRadius = 0.0;
  double mass_kg = 0.0;
};

/// Computed-torque joint controller: tau = M(q)(qdd_ref + Kp e + Kd e') + c(q, q') + g(q),
/// from Simbody's inverse dynamics, saturated at the URDF effort limits.
class JointController : public stk::Force::Custom::Implementation {
 public:
  JointController(const stk::SimbodyMatterSubsystem& matter, std::vector<stk::MobilizedBody> arm,
                  std::vector<double> maxEffort, std::vector<double> armMasses, std::vector<stk::Vec3> armComs,
                  double bandwidth_radps, const Reference* reference)
      : matter_(matter), arm_(std::move(arm)), maxEffort_(std::move(maxEffort)), masses_(std::move(armMasses)),
        coms_(std::move(armComs)), kp_(bandwidth_radps * bandwidth_radps), kd_(2.0 * bandwidth_radps),
        reference_(reference) {}

  void calcForce(const stk::State& s, stk::Vector_<stk::SpatialVec>&, stk::Vector_<stk::Vec3>&,
                 stk::Vector& mobilityForces) const override {
    const JointTrajectorySample ref = reference_->at(s.getTime());
    if (udot_.size() != s.getNU()) {  // buffers and indices once: the layout never changes
      udot_.resize(s.getNU());
      gravity_.resize(matter_.getNumBodies());
      for (int i = 0; i < 6; ++i) uIndex_[i] = arm_[i].getFirstUIndex(s);
    }
    udot_ = 0.0;
    const stk::Vector& q = s.getQ();
    const stk::Vector& u = s.getU();
    for (int i = 0; i < 6; ++i) {
      const int ui = uIndex_[i];  // a Pin has one q and one u, in the same order as u
      const double qi = q[arm_[i].getFirstQIndex(s)], uu = u[ui];
      udot_[ui] = ref.qdd_radps2[i] + kp_ * (ref.q_rad[i] - qi) + kd_ * (ref.qd_radps[i] - uu);
    }
    gravity_ = stk::SpatialVec(stk::Vec3(0), stk::Vec3(0));
    const stk::Vec3 g(0, 0, -9.81);
    for (int i = 0; i < 6; ++i) arm_[i].applyForceToBodyPoint(s, coms_[i], masses_[i] * g, gravity_);
    if (payloadMass_kg > 0.0) arm_[5].applyForceToBodyPoint(s, payloadCom_B, payloadMass_kg * g, gravity_);
    matter_.calcResidualForceIgnoringConstraints(s, stk::Vector(), gravity_, udot_, residual_);
    for (int i = 0; i < 6; ++i) {
      const int ui = uIndex_[i];
      double tau = residual_[ui];
      if (std::abs(tau) > maxEffort_[i]) {
        tau = std::copysign(maxEffort_[i], tau);
        ++saturations;
      }
      mobilityForces[ui] += tau;
    }
  }
  stk::Real calcPotentialEnergy(const stk::State&) const override { return 0.0; }

  double payloadMass_kg = 0.0;   ///< grasped part, compensated as a load on the last link
  stk::Vec3 payloadCom_B{0.0};  ///< its centre of mass in the last link's frame
  mutable int saturations = 0;

 private:
  const stk::SimbodyMatterSubsystem& matter_;
  std::vector<stk::MobilizedBody> arm_;
  std::vector<double> maxEffort_, masses_;
  std::vector<stk::Vec3> coms_;
  double kp_, kd_;
  const Reference* reference_;
  mutable stk::Vector udot_, residual_;
  mutable stk::Vector_<stk::SpatialVec> gravity_;
  mutable std::array<int, 6> uIndex_{};
};

/// Penalty contact between part box corners and every other box.
class BoxContact : public stk::Force::Custom::Implementation {
 public:
  BoxContact(const stk::SimbodyMatterSubsystem& matter, std::vector<PartGeometry> parts, std::vector<ContactBox> boxes,
             const CellSimulator::Options& o)
      : matter_(matter), parts_(std::move(parts)), boxes_(std::move(boxes)), o_(o) {}

  void calcForce(const stk::State& s, stk::Vector_<stk::SpatialVec>& bodyForces, stk::Vector_<stk::Vec3>&,
                 stk::Vector&) const override {
    // Per-corner spring and damper scaled with the part's mass, so every part sinks
    // g / omega^2 into its support and rings at the same frequency.
    const double kOmega_radps = o_.contactFrequency_radps, kZeta = o_.contactDampingRatio,
                 kFrictionRate_1ps = o_.frictionRate_1ps;
    // Body poses and velocities once per evaluation (Simbody's accessors are not free).
    const int nb = matter_.getNumBodies();
    X_GB_.resize(nb);
    V_GB_.resize(nb);
    for (stk::MobilizedBodyIndex b(0); b < nb; ++b) {
      const stk::MobilizedBody& B = matter_.getMobilizedBody(b);
      X_GB_[b] = B.getBodyTransform(s);
      V_GB_[b] = B.getBodyVelocity(s);
    }
    auto stationVelocity = [&](stk::MobilizedBodyIndex b, const stk::Vec3& p_G) {
      const stk::SpatialVec& V = V_GB_[b];
      return V[1] + stk::cross(V[0], p_G - X_GB_[b].p());
    };
    for (std::size_t p = 0; p < parts_.size(); ++p) {
      const PartGeometry& part = parts_[p];
      const stk::MobilizedBody& P = matter_.getMobilizedBody(part.body);
      const stk::Transform& X_GP = X_GB_[part.body];
      const stk::Vec3 centre_G = X_GP * part.centre_B;
      // The bottom points share the part's mass: resting flat, the total spring is the same
      // whatever the grid (g / omega^2 sink, omega ringing).
      const double mCorner = part.mass_kg / part.bottomPoints;
      const double k = mCorner * kOmega_radps * kOmega_radps, c = 2.0 * kZeta * kOmega_radps * mCorner;
      const double cFriction = mCorner * kFrictionRate_1ps;
      for (const ContactBox& box : boxes_) {
        if (box.part == static_cast<int>(p)) continue;
        const stk::Transform X_Gbox = X_GB_[box.body] * box.X_B_box;
        if ((X_Gbox.p() - centre_G).norm() > part.boundRadius + box.boundRadius) continue;
        for (const stk::Vec3& corner : part.corners_B) {
          const stk::Vec3 p_G = X_GP * corner;
          const stk::Vec3 p_box = ~X_Gbox * p_G;
          int axis = -1;
          double depth = 1e9;
          for (int a = 0; a < 3; ++a) {
            const double d = box.half[a] - std::abs(p_box[a]);
            if (d <= 0.0) {
              axis = -1;
              break;
            }
            if (d < depth) {
              depth = d;
              axis = a;
            }
          }
          if (axis < 0) continue;
          stk::Vec3 n_box(0);
          n_box[axis] = p_box[axis] >= 0 ? 1.0 : -1.0;
          const stk::Vec3 n = X_Gbox.R() * n_box;
          const stk::Vec3 vRel = stationVelocity(part.body, p_G) - stationVelocity(box.body, p_G);
          const double vn = stk::dot(vRel, n);
          const double fn = k * depth - c * vn;
          if (fn <= 0.0) continue;
          const stk::Vec3 vt = vRel - vn * n;
          const double slip = vt.norm();
          stk::Vec3 ft(0);
          if (slip > 1e-12) ft = -vt * std::min(cFriction, o_.frictionCoefficient * fn / slip);
          const stk::Vec3 F = fn * n + ft;
          P.applyForceToBodyPoint(s, corner, F, bodyForces);
          if (box.body != 0) {
            const stk::MobilizedBody& B = matter_.getMobilizedBody(box.body);
            B.applyForceToBodyPoint(s, ~X_GB_[box.body] * p_G, -F, bodyForces);
          }
        }
      }
    }
  }
  stk::Real calcPotentialEnergy(const stk::State&) const override { return 0.0; }

 private:
  const stk::SimbodyMatterSubsystem& matter_;
  std::vector<PartGeometry> parts_;
  std::vector<ContactBox> boxes_;
  CellSimulator::Options o_;
  mutable std::vector<stk::Transform> X_GB_;
  mutable std::vector<stk::SpatialVec> V_GB_;
};

/// The contact geometry of a box part of size `s` (its frame at the bottom face's centre).
/// Bottom face: an n x n grid (corners, edge points, centre), so a part stacked
/// crosswise on a narrower one (no corner of either inside the other) still rests
/// on the points of its bottom that lie over the lower part. Top face: the corners.
/// The points lie contactInset_m inside the edges (see CellSimulator::Options).
PartGeometry partGeometry(stk::MobilizedBodyIndex body, double mass_kg, const Eigen::Vector3d& s,
                          const Eigen::Vector3d& com, const CellSimulator::Options& options) {
  PartGeometry g;
  g.body = body;
  g.centre_B = toVec3(com);
  g.mass_kg = mass_kg;
  g.boundRadius = 0.5 * s.norm() + 0.01;
  const int n = std::max(2, options.bottomContactGrid);
  const double ex = std::max(0.0, s.x() - 2 * options.contactInset_m), ey = std::max(0.0, s.y() - 2 * options.contactInset_m);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      g.corners_B.emplace_back(ex * (double(i) / (n - 1) - 0.5), ey * (double(j) / (n - 1) - 0.5), 0.0);
  g.bottomPoints = n * n;
  for (double x : {-ex / 2, ex / 2})
    for (double y : {-ey / 2, ey / 2}) g.corners_B.emplace_back(x, y, s.z());
  return g;
}

}  // namespace

struct CellSimulator::Impl {
  RobotModel model;
  CellDescription cell;
  CellSimulator::Options options;
  stk::MultibodySystem system;
  stk::SimbodyMatterSubsystem matter{system};
  stk::GeneralForceSubsystem forces{system};
  std::vector<stk::MobilizedBody> arm;  // the six Pin mobilizers
  std::vector<std::string> partNames;
  std::vector<stk::MobilizedBody::Free> partBodies;
  std::vector<stk::Constraint::Weld> grasps;
  JointController* controller = nullptr;  // owned by the force subsystem
  Reference reference;
  std::vector<Reference> commanded;           // every reference, in time order (commandedTrajectory)
  std::vector<GripperEvent> gripperEvents;
  stk::State state;
  std::unique_ptr<stk::Integrator> integrator;
  std::optional<int> grasped;
  std::vector<CellSnapshot> log;
  std::function<void(const CellSnapshot&)> callback;
  SafetyChecker monitor;
  std::vector<bool> asleep;
  std::vector<double> wokeAt_s;
  std::vector<std::optional<double>> slowSince_s;  ///< since when a part has been slow (sleep candidate)
  static constexpr double kRestConfirm_s = 0.04;
  double wall_s = 0.0;
  double callbackWall_s = 0.0;
  long stepsBefore = 0, stepsSoFar = 0;
  double nextLog_s = 0.0;

  Impl(const RobotModel& m, const CellDescription& c, CellSimulator::Options o)
      : model(m), cell(c), options(o), monitor(m, c.X_world_base, SafetyLimits{}, {}) {}

  /// Parts at rest (and not held) are locked in place until grasped, like the
  /// "sleeping" bodies of game physics engines: a resting part has no dynamics
  /// worth integrating, and its stiff contact would otherwise limit the step size.
  /// A locked part still supports and blocks other parts through its contact box.
  bool sleepRestingParts() {
    if (!options.sleepRestingParts) return false;
    system.realize(state, stk::Stage::Velocity);
    bool changed = false;
    for (std::size_t i = 0; i < partBodies.size(); ++i) {
      if (asleep[i] || (grasped && *grasped == static_cast<int>(i))) continue;
      const stk::SpatialVec V = partBodies[i].getBodyVelocity(state);
      const double now = state.getTime();
      if (!(V[0].norm() < 0.1 && V[1].norm() < 0.01 && now - wokeAt_s[i] > 0.1)) {
        slowSince_s[i].reset();
        continue;
      }
      // Slow at two checks kRestConfirm_s apart: a dropped part at the top of a bounce is
      // slow for an instant only (gravity adds 0.2 m/s in 20 ms), and was locked in mid-air.
      if (!slowSince_s[i]) slowSince_s[i] = now;
      if (now - *slowSince_s[i] >= kRestConfirm_s - 1e-9) {
        asleep[i] = true;
        changed = true;
      }
    }
    if (changed) applyLocks();
    return changed;
  }

  void applyLocks() {
    for (std::size_t i = 0; i < partBodies.size(); ++i) {
      if (asleep[i] && !partBodies[i].isLocked(state)) {
        partBodies[i].lock(state, stk::Motion::Position);
        partBodies[i].setU(state, stk::Vec6(0));
      } else if (!asleep[i] && partBodies[i].isLocked(state)) {
        partBodies[i].unlock(state);
      }
    }
    system.realize(state, stk::Stage::Instance);
  }

  void restartIntegrator() {
    integrator = std::make_unique<stk::RungeKuttaMersonIntegrator>(system);
    integrator->setAccuracy(options.integratorAccuracy);
    integrator->setMaximumStepSize(options.maxStep_s);
    integrator->setReturnEveryInternalStep(false);
    integrator->initialize(state);
    stepsBefore += stepsSoFar;
    stepsSoFar = 0;
    state = integrator->getState();
  }

  JointVector q() const {
    JointVector v;
    for (int i = 0; i < 6; ++i) v[i] = arm[i].getOneQ(state, stk::QIndex(0));
    return v;
  }

  CellSnapshot snapshot() const {
    CellSnapshot s;
    s.t_s = state.getTime();
    s.q_rad = q();
    s.qRef_rad = reference.at(s.t_s).q_rad;
    for (std::size_t i = 0; i < partBodies.size(); ++i)
      s.X_world_parts[partNames[i]] = toPose(partBodies[i].getBodyTransform(state));
    if (grasped) s.graspedPart = partNames[*grasped];
    return s;
  }

  /// Integrates to t_end, logging every logPeriod_s; returns the per-log monitor values.
  void advance(double tEnd_s, TrackingResult* result) {
    const auto start = std::chrono::steady_clock::now();
    while (state.getTime() < tEnd_s - 1e-12) {
      const double target = std::min(tEnd_s, std::max(nextLog_s, state.getTime() + 1e-9));
      integrator->stepTo(target);
      stepsSoFar = integrator->getNumStepsTaken();
      state = integrator->getState();
      if (state.getTime() >= nextLog_s - 1e-12) {
        nextLog_s += options.logPeriod_s;
        system.realize(state, stk::Stage::Position);
        log.push_back(snapshot());
        if (result) {
          const double e = (log.back().q_rad - log.back().qRef_rad).cwiseAbs().maxCoeff();
          result->maxJointError_rad = std::max(result->maxJointError_rad, e);
          result->minTableClearance_m = std::min(result->minTableClearance_m, monitor.tableClearance_m(log.back().q_rad));
        }
        if (callback) {  // rendering etc. is not simulation time
          const auto c0 = std::chrono::steady_clock::now();
          callback(log.back());
          callbackWall_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - c0).count();
        }
        if (sleepRestingParts()) restartIntegrator();
      }
    }
    wall_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() - callbackWall_s;
    callbackWall_s = 0.0;
  }

  /// Re-realizes the topology after a grasp frame changed, keeping time, q and u.
  void rebuildKeepingState(std::optional<int> enabledGrasp) {
    const double t = state.getTime();
    const stk::Vector qv = state.getQ(), uv = state.getU();
    system.realizeTopology();
    state = system.getDefaultState();
    state.setTime(t);
    state.updQ() = qv;
    state.updU() = uv;
    for (std::size_t i = 0; i < grasps.size(); ++i) {
      if (enabledGrasp && static_cast<int>(i) == *enabledGrasp)
        grasps[i].enable(state);
      else
        grasps[i].disable(state);
    }
    system.realizeModel(state);
    applyLocks();
    restartIntegrator();
  }
};

CellSimulator::CellSimulator(const RobotModel& model, const CellDescription& cell, const JointVector& q_initial,
                             Options options)
    : impl_(std::make_unique<Impl>(model, cell, options)) {
  Impl& m = *impl_;
  stk::Force::Gravity(m.forces, m.matter, -stk::ZAxis, 9.81);

  const auto& links = model.links();
  stk::Body::Rigid baseBody(massProperties(links[0].mass_kg, links[0].p_link_com_m, links[0].I_com_kgm2));
  stk::MobilizedBody parent =
      stk::MobilizedBody::Weld(m.matter.updGround(), toTransform(cell.X_world_base), baseBody, stk::Transform());
  std::vector<double> maxEffort, masses;
  std::vector<stk::Vec3> coms;
  for (int i = 0; i < 6; ++i) {
    const LinkInertia& li = links[i + 1];
    stk::Body::Rigid body(massProperties(li.mass_kg, li.p_link_com_m, li.I_com_kgm2));
    stk::MobilizedBody::Pin pin(parent, toTransform(model.joints()[i].X_parent_joint), body, stk::Transform());
    m.arm.push_back(pin);
    parent = pin;
    maxEffort.push_back(model.joints()[i].maxEffort_Nm);
    masses.push_back(li.mass_kg);
    coms.push_back(toVec3(li.p_link_com_m));
  }

  std::vector<PartGeometry> parts;
  std::vector<ContactBox> boxes;
  for (const WorldBox& b : cell.staticBoxes()) {
    ContactBox cb;
    cb.body = stk::GroundIndex;
    cb.X_B_box = toTransform(b.X_world_box);
    cb.half = toVec3(b.halfExtents_m);
    cb.boundRadius = b.halfExtents_m.norm();
    boxes.push_back(cb);
  }
  for (const CellObject& o : cell.objects) {
    if (o.kind != CellObjectKind::Part) continue;
    if (!(o.mass_kg > 0.0) || !(o.size_m.minCoeff() > 0.0))
      throw srp::core::InvalidInputError("CellSimulator: part '" + o.name +
                                         "' needs a positive mass and size (check the object catalogue)");
    const Eigen::Vector3d s = o.size_m;
    const Eigen::Vector3d com(0, 0, s.z() / 2);
    Eigen::Matrix3d I = Eigen::Matrix3d::Zero();
    I(0, 0) = o.mass_kg * (s.y() * s.y() + s.z() * s.z()) / 12.0;
    I(1, 1) = o.mass_kg * (s.x() * s.x() + s.z() * s.z()) / 12.0;
    I(2, 2) = o.mass_kg * (s.x() * s.x() + s.y() * s.y()) / 12.0;
    stk::Body::Rigid body(massProperties(o.mass_kg, com, I));
    stk::MobilizedBody::Free free(m.matter.updGround(), stk::Transform(), body, stk::Transform());
    const int index = static_cast<int>(m.partBodies.size());
    m.partBodies.push_back(free);
    m.partNames.push_back(o.name);
    parts.push_back(partGeometry(free.getMobilizedBodyIndex(), o.mass_kg, s, com, options));
    ContactBox cb;
    cb.body = free.getMobilizedBodyIndex();
    cb.X_B_box = stk::Transform(toVec3(com));
    cb.half = toVec3(s / 2);
    cb.boundRadius = 0.5 * s.norm() + 0.01;
    cb.part = index;
    boxes.push_back(cb);
    stk::Constraint::Weld weld(m.arm[5], stk::Transform(), free, stk::Transform());
    weld.setDisabledByDefault(true);
    m.grasps.push_back(weld);
  }

  m.reference.trajectory = JointTrajectory::hold(q_initial, 1.0);
  m.reference.tStart_s = 0.0;
  m.commanded.push_back(m.reference);
  m.controller = new JointController(m.matter, m.arm, maxEffort, masses, coms, options.controllerBandwidth_radps,
                                     &m.reference);
  stk::Force::Custom(m.forces, m.controller);
  stk::Force::Custom(m.forces, new BoxContact(m.matter, parts, boxes, options));

  m.system.realizeTopology();
  m.state = m.system.getDefaultState();
  m.system.realizeModel(m.state);
  for (int i = 0; i < 6; ++i) m.arm[i].setOneQ(m.state, stk::QIndex(0), q_initial[i]);
  std::size_t k = 0;
  for (const CellObject& o : cell.objects)
    if (o.kind == CellObjectKind::Part) m.partBodies[k++].setQToFitTransform(m.state, toTransform(o.X_world_object));
  m.asleep.assign(m.partBodies.size(), false);
  m.wokeAt_s.assign(m.partBodies.size(), 0.0);
  m.slowSince_s.assign(m.partBodies.size(), std::nullopt);
  m.restartIntegrator();
  m.nextLog_s = 0.0;
  // Let the parts settle onto their supports before the first motion.
  if (!m.partBodies.empty()) settle(0.1);
}

CellSimulator::~CellSimulator() = default;

double CellSimulator::time_s() const { return impl_->state.getTime(); }

JointVector CellSimulator::jointPositions() const { return impl_->q(); }

JointVector CellSimulator::jointVelocities() const {
  JointVector v;
  for (int i = 0; i < 6; ++i) v[i] = impl_->arm[i].getOneU(impl_->state, stk::MobilizerUIndex(0));
  return v;
}

srp::core::Pose3 CellSimulator::X_world_tcp() const {
  impl_->system.realize(impl_->state, stk::Stage::Position);
  return toPose(impl_->arm[5].getBodyTransform(impl_->state)) * impl_->model.X_wrist3_tcp();
}

srp::core::Pose3 CellSimulator::X_world_part(const std::string& name) const {
  impl_->system.realize(impl_->state, stk::Stage::Position);
  for (std::size_t i = 0; i < impl_->partNames.size(); ++i)
    if (impl_->partNames[i] == name) return toPose(impl_->partBodies[i].getBodyTransform(impl_->state));
  throw srp::core::InvalidInputError("CellSimulator: no part named '" + name + "' in the cell");
}

std::vector<std::string> CellSimulator::partNames() const { return impl_->partNames; }

std::optional<std::string> CellSimulator::graspedPart() const {
  if (!impl_->grasped) return std::nullopt;
  return impl_->partNames[*impl_->grasped];
}

TrackingResult CellSimulator::track(const JointTrajectory& trajectory, double settle_s) {
  Impl& m = *impl_;
  if (trajectory.empty()) throw srp::core::InvalidInputError("CellSimulator::track: empty trajectory");
  m.reference.trajectory = trajectory;
  m.reference.tStart_s = m.state.getTime();
  m.commanded.push_back(m.reference);
  m.sleepRestingParts();
  m.restartIntegrator();  // the reference changed: forces cached in the integrator are stale
  TrackingResult r;
  r.minTableClearance_m = std::numeric_limits<double>::infinity();
  const int saturationsBefore = m.controller->saturations;
  const double t0 = m.state.getTime();
  m.advance(t0 + trajectory.duration_s() + settle_s, &r);
  r.simulated_s = m.state.getTime() - t0;
  r.finalJointError_rad = (m.q() - trajectory.samples().back().q_rad).cwiseAbs().maxCoeff();
  r.torqueSaturations = m.controller->saturations - saturationsBefore;
  return r;
}

void CellSimulator::settle(double duration_s) {
  Impl& m = *impl_;
  const JointVector qRef = m.reference.at(m.state.getTime()).q_rad;
  m.reference.trajectory = JointTrajectory::hold(qRef, duration_s);
  m.reference.tStart_s = m.state.getTime();
  m.commanded.push_back(m.reference);
  m.sleepRestingParts();
  m.restartIntegrator();
  m.advance(m.state.getTime() + duration_s, nullptr);
}

std::optional<std::string> CellSimulator::grasp(const std::string& part, double maxGap_m) {
  Impl& m = *impl_;
  if (m.grasped) return "the tool already holds the " + m.partNames[*m.grasped];
  int index = -1;
  for (std::size_t i = 0; i < m.partNames.size(); ++i)
    if (m.partNames[i] == part) index = static_cast<int>(i);
  if (index < 0) throw srp::core::InvalidInputError("CellSimulator::grasp: no part named '" + part + "'");
  const CellObject* spec = m.cell.find(part);
  m.system.realize(m.state, stk::Stage::Position);
  const Pose3 X_world_part = toPose(m.partBodies[index].getBodyTransform(m.state));
  const Pose3 X_world_tcp = toPose(m.arm[5].getBodyTransform(m.state)) * m.model.X_wrist3_tcp();
  const Eigen::Vector3d p_part_tcp = X_world_part.inverse() * X_world_tcp.translation();
  const double gap = p_part_tcp.z() - spec->size_m.z();
  if (std::abs(p_part_tcp.x()) > spec->size_m.x() / 2 || std::abs(p_part_tcp.y()) > spec->size_m.y() / 2 ||
      std::abs(gap) > maxGap_m) {
    std::ostringstream why;
    why << "suction cup not on the " << part << "'s top face (offset " << p_part_tcp.x() * 1000 << ", "
        << p_part_tcp.y() * 1000 << " mm, gap " << gap * 1000 << " mm)";
    return why.str();
  }
  const stk::Transform X_wrist3_part =
      ~m.arm[5].getBodyTransform(m.state) * m.partBodies[index].getBodyTransform(m.state);
  m.grasps[index].setDefaultFrameOnBody1(X_wrist3_part);
  m.grasps[index].setDefaultFrameOnBody2(stk::Transform());
  m.controller->payloadMass_kg = spec->mass_kg;
  m.controller->payloadCom_B = X_wrist3_part * stk::Vec3(0, 0, spec->size_m.z() / 2);
  m.grasped = index;
  m.gripperEvents.push_back({GripperEvent::Kind::Grasp, m.state.getTime(), part});
  m.asleep[index] = false;
  m.wokeAt_s[index] = m.state.getTime();
  m.rebuildKeepingState(index);
  return std::nullopt;
}

void CellSimulator::release() {
  Impl& m = *impl_;
  if (!m.grasped) return;
  m.gripperEvents.push_back({GripperEvent::Kind::Release, m.state.getTime(), m.partNames[*m.grasped]});
  m.wokeAt_s[*m.grasped] = m.state.getTime();
  m.grasped.reset();
  m.controller->payloadMass_kg = 0.0;
  m.rebuildKeepingState(std::nullopt);
}

const std::vector<CellSnapshot>& CellSimulator::log() const { return impl_->log; }

JointTrajectory CellSimulator::commandedTrajectory() const {
  const Impl& m = *impl_;
  const double now = m.state.getTime();
  std::vector<JointTrajectorySample> samples;
  auto holdTo = [&](double t_s) {  // the controller holds the last reference until t_s
    if (!samples.empty() && t_s > samples.back().t_s + 1e-9) {
      JointTrajectorySample s = samples.back();
      s.t_s = t_s;
      s.qd_radps.setZero();
      s.qdd_radps2.setZero();
      samples.push_back(s);
    }
  };
  for (std::size_t i = 0; i < m.commanded.size(); ++i) {
    const Reference& r = m.commanded[i];
    const double end = i + 1 < m.commanded.size() ? m.commanded[i + 1].tStart_s : now;
    for (const auto& s0 : r.trajectory.samples()) {
      JointTrajectorySample s = s0;
      s.t_s += r.tStart_s;
      if (s.t_s > end + 1e-9) break;  // a reference replaced before its end (not done by TaskExecutor)
      if (!samples.empty() && s.t_s <= samples.back().t_s + 1e-9) continue;  // the joint of two pieces
      samples.push_back(s);
    }
    holdTo(end);
  }
  return JointTrajectory::fromSamples(std::move(samples));
}

const std::vector<GripperEvent>& CellSimulator::gripperEvents() const { return impl_->gripperEvents; }

void CellSimulator::setSnapshotCallback(std::function<void(const CellSnapshot&)> callback) {
  impl_->callback = std::move(callback);
}

double CellSimulator::wallSeconds() const { return impl_->wall_s; }

long CellSimulator::integratorSteps() const { return impl_->stepsBefore + impl_->stepsSoFar; }

}  // namespace srp::execution
