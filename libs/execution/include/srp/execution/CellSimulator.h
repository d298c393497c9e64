#pragma once
/// \file CellSimulator.h
/// \brief The simulated work cell: the UR5 (from its URDF) with a suction tool, the
/// table, the containers and the parts, as a Simbody multibody system.
///
/// - The arm's links carry the URDF masses and inertias; the base is welded to the
///   table at X_world_base (from the scene). Gravity is -9.81 m/s^2 along world z.
/// - A computed-torque joint controller (inverse dynamics of the arm plus PD
///   feedback on the tracking error, torques saturated at the URDF effort limits)
///   tracks the current JointTrajectory and holds the last position afterwards.
/// - Parts are free rigid bodies (box-shaped, catalogue size and mass); the table
///   top and every container's floor and walls are fixed boxes. Contact is a
///   penalty model between each part's contact points (a grid on the bottom face, the
///   top corners; see CellSimulator::Options::bottomContactGrid) and every other box (table,
///   container floor/walls, other parts): a spring-damper normal force and a
///   regularised Coulomb friction force. A released part falls and rests where it lands.
/// - Grasp is a Simbody Weld constraint between the tool and the part, created at
///   the part's actual pose relative to the tool when Grasp is called, and disabled
///   at Release.
/// Frames: world = table frame (z up); units SI.

#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "srp/execution/CellDescription.h"
#include "srp/execution/JointTrajectory.h"
#include "srp/execution/RobotModel.h"

namespace srp::execution {

/// Everything needed to draw or check the cell at one instant.
struct CellSnapshot {
  double t_s = 0.0;
  JointVector q_rad = JointVector::Zero();
  JointVector qRef_rad = JointVector::Zero();
  std::map<std::string, srp::core::Pose3> X_world_parts;
  std::optional<std::string> graspedPart;
};

/// A grasp or release of the suction tool, at simulated time t_s (what an exporter
/// turns into a tool digital output).
struct GripperEvent {
  enum class Kind { Grasp, Release };
  Kind kind = Kind::Grasp;
  double t_s = 0.0;   ///< simulated time of the event (same clock as CellSnapshot::t_s)
  std::string part;   ///< the part grasped or released
};

/// Result of tracking one joint trajectory.
struct TrackingResult {
  double simulated_s = 0.0;
  double maxJointError_rad = 0.0;      ///< max |q - q_ref| over the run
  double finalJointError_rad = 0.0;    ///< |q - q_ref| at the end
  double minTableClearance_m = 0.0;    ///< from SafetyChecker's arm spheres, over the run
  int torqueSaturations = 0;           ///< controller evaluations that hit an effort limit
};

class CellSimulator {
 public:
  struct Options {
    /// Simbody RK-Merson relative accuracy. 1e-2 let a part dropped on another part gain
    /// energy in its stiff contact and bounce off (a cuboid released 3 mm above an octagon
    /// hopped 5 mm and fell off); 1e-3 lets it settle. Cost: 50 random scenes took 103 s
    /// of integration for 1732 s simulated (87 s for 2175 s at 1e-2, another load).
    double integratorAccuracy = 1e-3;
    double maxStep_s = 1e-2;  ///< integrator step cap
    /// Per-corner contact spring and damper are scaled with the part's mass so every
    /// part sinks g / omega^2 into its support (27 um at 600 rad/s) and rings alike.
    double contactFrequency_radps = 600.0;
    double contactDampingRatio = 0.7;
    double frictionCoefficient = 0.6;
    /// Contact points per side of a part's bottom face (2: the four corners only). With 3,
    /// the edge midpoints and the centre too, so a part stacked across a narrower part
    /// (no corner of either inside the other) is held; the points share the weight.
    int bottomContactGrid = 3;
    /// The contact points sit this far inside the part's footprint edges. On a part
    /// stacked on one of the same footprint (two cuboids, two stars, a cuboid along a
    /// star) points exactly on the edges lie on the lower box's side faces: a box point
    /// takes the normal of its shallowest face, so they were pushed sideways or got no
    /// force, the part rested on its centre point alone and tipped over. 2 mm is five
    /// times the deepest impact penetration (a release 3 mm up: 0.24 m/s / 600 rad/s).
    double contactInset_m = 0.002;
    double frictionRate_1ps = 300.0;          ///< viscous slope of the regularised friction, per unit corner mass
    double controllerBandwidth_radps = 25.0;  ///< closed-loop natural frequency of every joint
    /// Lock parts that came to rest (checked between trajectories) until they are
    /// grasped: same resting poses, several times faster (see CellSimulator.cpp).
    bool sleepRestingParts = true;
    double logPeriod_s = 0.02;  ///< period of the state log and the snapshot callback
  };

  /// Builds the system; the arm starts at rest at q_initial, the parts at their
  /// scene poses. Throws InvalidInputError on a part with non-positive size or mass.
  CellSimulator(const RobotModel& model, const CellDescription& cell, const JointVector& q_initial, Options options);
  CellSimulator(const RobotModel& model, const CellDescription& cell, const JointVector& q_initial)
      : CellSimulator(model, cell, q_initial, Options{}) {}
  ~CellSimulator();
  CellSimulator(const CellSimulator&) = delete;
  CellSimulator& operator=(const CellSimulator&) = delete;

  double time_s() const;
  JointVector jointPositions() const;
  JointVector jointVelocities() const;
  srp::core::Pose3 X_world_tcp() const;
  srp::core::Pose3 X_world_part(const std::string& name) const;
  std::vector<std::string> partNames() const;
  std::optional<std::string> graspedPart() const;

  /// Tracks `trajectory` from the current time, then keeps holding its end for settle_s.
  TrackingResult track(const JointTrajectory& trajectory, double settle_s = 0.2);

  /// Lets the cell evolve for duration_s holding the current reference.
  void settle(double duration_s);

  /// Suction grasp: succeeds when the tcp is within maxGap_m of the part's top face
  /// and above its footprint; otherwise returns the reason. Welds the part to the tool.
  std::optional<std::string> grasp(const std::string& part, double maxGap_m = 0.005);

  /// Disables the grasp weld; the part falls under gravity and contact.
  void release();

  /// The joint reference the controller was commanded from t = 0 (construction) to
  /// now: every tracked trajectory at its start time and the holds between them, as
  /// one trajectory whose spline equals each tracked one (knots and velocities kept).
  /// What the safety checker saw, in simulated time: the exporters replay it. Where a
  /// new trajectory starts a few micro-radians off the held reference (TaskExecutor
  /// plans each step from the measured joints), the held position is kept: no jump.
  JointTrajectory commandedTrajectory() const;

  /// Every successful grasp and every release so far, in time order.
  const std::vector<GripperEvent>& gripperEvents() const;

  /// The state log (every logPeriod_s) of everything simulated so far.
  const std::vector<CellSnapshot>& log() const;

  /// Called for each logged snapshot (e.g. to render frames).
  void setSnapshotCallback(std::function<void(const CellSnapshot&)> callback);

  /// Total wall-clock seconds spent integrating.
  double wallSeconds() const;

  /// Total number of integrator steps taken.
  long integratorSteps() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace srp::execution
