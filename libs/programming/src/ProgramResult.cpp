#include "srp/programming/ProgramResult.h"

#include <nlohmann/json.hpp>

#include "srp/core/ObjectClassJson.h"

namespace srp::programming {
namespace {

nlohmann::json toJson(const ObjectOutcome& o) {
  return {{"name", o.name},
          {"instance", o.instanceId},
          {"class_id", o.classId},
          {"moved", o.moved},
          {"grasp_frame", o.graspFrame},
          {"release_frame", o.releaseFrame},
          {"detected_frames", o.detectedFrames},
          {"reach_lambda", o.reachLambda},
          {"move_lambda", o.moveLambda},
          {"note", o.note}};
}

// A class seen without a CAD file, as the scene file and the task database write it.
nlohmann::json toJson(const core::ObjectClass& c) { return core::objectClassToJson(c); }

/// [toJson(x) for x in items] (an empty array for none).
template <typename T>
nlohmann::json arrayOf(const std::vector<T>& items) {
  nlohmann::json a = nlohmann::json::array();
  for (const auto& x : items) a.push_back(toJson(x));
  return a;
}

}  // namespace

std::string toJsonText(const ProgramResult& r) {
  // nlohmann::json keeps an object's keys sorted: the text does not depend on the order below.
  nlohmann::json timings = nlohmann::json::object();
  for (const auto& t : r.timings) timings[t.stage] = t.wall_s;
  nlohmann::json j = {{"task_model_id", r.taskModelId},
                      {"name", r.name},
                      {"version", r.version},
                      {"plan", r.planLines},
                      {"frames", r.frames},
                      {"hand_detected_frames", r.handDetectedFrames},
                      {"skills", r.skillCount},
                      {"objects", arrayOf(r.objects)},
                      {"timings_s", timings},
                      {"peak_memory_MB", r.peakResidentMemory_MB},
                      {"warnings", r.warnings},
                      {"problems", r.problems},
                      {"perceived_scene_stored", r.sceneStored},
                      {"hand_detector", r.handDetector},
                      {"camera_moved", r.cameraMoved},
                      {"report_files", r.reportFiles}};
  if (!r.robotBase.empty()) j["robot_base"] = r.robotBase;
  if (!r.observedClasses.empty()) {
    j["observed_classes"] = arrayOf(r.observedClasses);
    j["discovery"] = r.discoveryNotes;
  }
  return j.dump(2);
}

}  // namespace srp::programming
