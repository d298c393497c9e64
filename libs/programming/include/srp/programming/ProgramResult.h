#pragma once
/// \file ProgramResult.h
/// \brief What one run of the Programming Module (programTask, ProgrammingPipeline.h)
/// learned and stored, per object of the plan, and its JSON form (`srp program --json`).

#include <string>
#include <vector>

#include "srp/core/ObjectCatalogue.h"

namespace srp::programming {

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
  std::string handDetector;  ///< "marker" or "marker-free" (the one used)
  bool cameraMoved = false;  ///< the demonstration's camera moved (trajectories kept in the first frame's camera)
  double cameraTravel_m = 0.0, cameraTurn_rad = 0.0;
  /// Objects the knowledge base did not know, found in the demonstration
  /// (perception::ObjectDiscovery): their classes as stored with the task
  /// model, and what was decided (one line each).
  std::vector<core::ObjectClass> observedClasses;
  std::vector<std::string> discoveryNotes;
};

/// The result as JSON (`srp program --json`).
std::string toJsonText(const ProgramResult& result);

}  // namespace srp::programming
