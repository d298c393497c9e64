#pragma once
/// \file ProgrammingOptions.h
/// \brief What one run of the Programming Module (programTask, ProgrammingPipeline.h)
/// is given: the instruction, the demonstration, the knowledge base, the database
/// and the report folder, and how progress is reported.

#include <functional>
#include <optional>
#include <string>

#include "srp/core/CameraIntrinsics.h"
#include "srp/core/Pose.h"

namespace srp::programming {

/// Progress of one stage: (stage name, done, total); total 0 = unknown.
using StageProgress = std::function<void(const std::string& stage, std::size_t done, std::size_t total)>;

struct ProgrammingOptions {
  std::string instruction;
  std::string demoPath;       ///< MRPT rawlog of the demonstration
  std::string cataloguePath;  ///< empty: the bundled knowledge base
  /// The demo's scene file (srp synth-demo --scene; for a recording, one that
  /// lists its instances and their colours); empty: none. A class the scene
  /// holds several times is perceived per instance and the instruction's
  /// phrases are grounded to instances (ProgrammingStages.h groundInstances).
  std::string scenePath;
  std::optional<core::CameraIntrinsics> intrinsics;  ///< overrides the rawlog's (e.g. from calib/*.xml)
  std::string dbPath = "task.db";
  std::string name = "task";  ///< re-using a name makes a new version
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

}  // namespace srp::programming
