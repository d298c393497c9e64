#pragma once
/// \file ProgrammingPipeline.h
/// \brief The Programming Module (thesis ch. 7.3, fig. 7.7/7.8): one
/// instruction + one RGB-D demonstration -> one task model in the database.
///
/// Stages: Language (instruction -> plan) -> grounding of the plan's objects
/// in the knowledge base -> Environment (hand and object trajectories, guided
/// by the plan: step objects move, landmarks are static) -> Motion
/// (segmentation into Reach/Grasp/Move/Release, DMPs) -> one task model
/// written in a single transaction. Every check happens before the write, so a
/// bad input or a kill at any point leaves the database as it was.
///
/// \code
///   srp::programming::ProgrammingOptions o;
///   o.instruction = "Pick up the cuboid from the blue box and place it in the gray box.";
///   o.demoPath = "demo.rawlog";  o.dbPath = "task.db";  o.name = "cuboid";
///   srp::programming::ProgramResult r = srp::programming::programTask(o);
///   // r.taskModelId, r.objects[i].graspFrame / releaseFrame, r.skills
/// \endcode

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "srp/core/CameraIntrinsics.h"
#include "srp/core/ObjectCatalogue.h"
#include "srp/core/Pose.h"
#include "srp/core/PositionTrajectory.h"

namespace srp::programming {

/// Progress of one stage: (stage name, done, total); total 0 = unknown.
using StageProgress = std::function<void(const std::string& stage, std::size_t done, std::size_t total)>;

struct ProgrammingOptions {
  std::string instruction;
  std::string demoPath;           ///< MRPT rawlog of the demonstration
  std::string cataloguePath;      ///< empty: the bundled knowledge base
  /// The demo's scene file (srp synth-demo --scene; for a recording, one that
  /// lists its instances and their colours); empty: none. A class the scene
  /// holds several times is perceived per instance and the instruction's
  /// phrases are grounded to instances (ProgrammingStages.h groundInstances).
  std::string scenePath;
  std::optional<core::CameraIntrinsics> intrinsics;  ///< overrides the rawlog's (e.g. from calib/*.xml)
  std::string dbPath = "task.db";
  std::string name = "task";      ///< re-using a name makes a new version
  /// Hand detector: Auto (the glove's AprilTag when a preview of the
  /// recording shows it, else the marker-free hand), the tag, or marker-free.
  enum class Hand { Auto, Marker, MarkerFree };
  Hand hand = Hand::Auto;
  /// Empty: no report; else a folder (built aside and renamed into place when
  /// the model is stored: a failed run leaves none) with PNG figures, the
  /// contact sheet of what perception saw, the perceived scene as a scene file
  /// (scene.json) and summary.md. Its parent is checked before anything runs; an
  /// existing folder holding anything but a report is refused.
  std::string reportDir;
  /// A damaged demonstration rawlog fails the run (nothing stored) unless
  /// this is set; then the frames before the damage are used, with a warning.
  bool allowTruncated = false;
  /// A step of the plan without a grasp or a release in the demonstration
  /// fails the run (nothing stored, the step and the reason named) unless this
  /// is set; then the task model is stored without
  /// those skills and ProgramResult::problems says what is missing.
  bool allowPartial = false;
  /// The demonstration camera's pose in the robot base (`srp calibrate
  /// extrinsics` / `hand-eye`), stored as TaskModels.X_base_camera: execution
  /// then places the robot in the demonstration's scene from it.
  std::optional<core::Pose3> X_base_camera;
  std::string extrinsicsSource;  ///< the file X_base_camera came from, for the report
  StageProgress progress;
};

/// What was learned for one object of the plan.
struct ObjectOutcome {
  std::string name;        ///< knowledge-base class
  std::string instanceId;  ///< the perceived instance ("" = the class's one instance)
  int classId = -1;
  bool moved = false;
  int graspFrame = -1, releaseFrame = -1;
  int detectedFrames = 0;
  double reachLambda = 0.0, moveLambda = 0.0;  ///< ridge coefficients chosen for the DMPs
  std::string note;
};

struct StageTiming {
  std::string stage;
  double wall_s = 0.0;
};

struct ProgramResult {
  int taskModelId = 0;
  int version = 0;
  std::string name;
  std::vector<std::string> planLines;  ///< the plan, one readable line per step
  std::vector<ObjectOutcome> objects;  ///< plan order
  int frames = 0;
  int handDetectedFrames = 0;
  std::size_t skillCount = 0;
  std::vector<StageTiming> timings;
  double peakResidentMemory_MB = 0.0;  ///< the process' peak resident set size when the pipeline ended
  std::vector<std::string> warnings;
  /// With allowPartial: what the demonstration lacks for the plan, one line per
  /// step ("step 2 (star ...): no release ..."); empty when the task model is whole.
  std::vector<std::string> problems;
  /// The scene the demonstration showed was stored with the task model (false:
  /// no table plane was found; the warnings say so).
  bool sceneStored = false;
  std::string robotBase;  ///< where the report's scene file puts the robot, and why
  std::vector<std::string> reportFiles;
  std::string handDetector;            ///< "marker" or "marker-free" (the one used)
  bool cameraMoved = false;            ///< the demonstration's camera moved (trajectories kept in the first frame's camera)
  double cameraTravel_m = 0.0, cameraTurn_rad = 0.0;
  /// Objects the knowledge base did not know, found in the demonstration
  /// (perception::ObjectDiscovery): their classes as stored with the task
  /// model, and what was decided (one line each).
  std::vector<core::ObjectClass> observedClasses;
  std::vector<std::string> discoveryNotes;
};

/// Runs the whole pipeline and stores the task model with the scene the
/// demonstration showed. Throws (writing nothing: no database file is created
/// and no report folder is left) InvalidInputError when the instruction has no
/// steps (the message says why), names an object the knowledge base does not
/// know or the demo never shows, the hand is never seen, or (without
/// allowPartial) a step has no grasp or no release; FileError for a bad rawlog
/// or database.
ProgramResult programTask(const ProgrammingOptions& options);

/// Frame rate [Hz] of a recording from its timestamps (median frame period; 30 when unknown).
double frameRateOf(const core::PositionTrajectory& samples);

/// The result as JSON (`srp program --json`).
std::string toJsonText(const ProgramResult& result);

}  // namespace srp::programming
