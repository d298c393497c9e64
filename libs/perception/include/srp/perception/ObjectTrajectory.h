#pragma once
/// \file ObjectTrajectory.h
/// \brief One perceived object's pose per frame (camera optical frame,
/// metres, radians, seconds).

#include <string>
#include <vector>

#include "srp/core/Pose.h"

namespace srp::perception {

/// One object's pose in one frame.
struct ObjectPoseSample {
  int frame = 0;
  double t_s = 0.0;
  /// The class's object frame = its mesh file's frame (bottom centre for the
  /// generated catalogue shapes, the CAD file's own frame for a mesh-only class).
  core::Pose3 X_camera_object = core::Pose3::Identity();
  bool detected = false;     ///< false: carried from the nearest detection
  double confidence = 0.0;
};

/// One object's pose trajectory (one sample per frame once it was seen).
struct ObjectTrajectory {
  std::string className;
  int classId = -1;
  bool isStatic = false;
  std::vector<ObjectPoseSample> samples;
  std::string instanceId;  ///< PlanObject::instanceId ("" = the class's one instance)
  int detectedFrames() const;
  /// PlanObject::key(): the instance id, else the class name.
  const std::string& key() const { return instanceId.empty() ? className : instanceId; }
};

}  // namespace srp::perception
