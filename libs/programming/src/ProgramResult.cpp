#include "srp/programming/ProgramResult.h"

#include <nlohmann/json.hpp>

namespace srp::programming {

std::string toJsonText(const ProgramResult& r) {
  nlohmann::json j;
  j["task_model_id"] = r.taskModelId;
  j["name"] = r.name;
  j["version"] = r.version;
  j["plan"] = r.planLines;
  j["frames"] = r.frames;
  j["hand_detected_frames"] = r.handDetectedFrames;
  j["skills"] = r.skillCount;
  j["objects"] = nlohmann::json::array();
  for (const auto& o : r.objects)
    j["objects"].push_back({{"name", o.name},
                            {"instance", o.instanceId},
                            {"class_id", o.classId},
                            {"moved", o.moved},
                            {"grasp_frame", o.graspFrame},
                            {"release_frame", o.releaseFrame},
                            {"detected_frames", o.detectedFrames},
                            {"reach_lambda", o.reachLambda},
                            {"move_lambda", o.moveLambda},
                            {"note", o.note}});
  j["timings_s"] = nlohmann::json::object();
  for (const auto& t : r.timings) j["timings_s"][t.stage] = t.wall_s;
  j["peak_memory_MB"] = r.peakResidentMemory_MB;
  j["warnings"] = r.warnings;
  j["problems"] = r.problems;
  j["perceived_scene_stored"] = r.sceneStored;
  if (!r.robotBase.empty()) j["robot_base"] = r.robotBase;
  j["hand_detector"] = r.handDetector;
  j["camera_moved"] = r.cameraMoved;
  if (!r.observedClasses.empty()) {
    j["observed_classes"] = nlohmann::json::array();
    for (const auto& c : r.observedClasses) {
      nlohmann::json footprint = nlohmann::json::array();
      for (const auto& p : c.footprint_object) footprint.push_back({p.x(), p.y()});
      j["observed_classes"].push_back({{"name", c.name},
                                       {"class_id", c.classId},
                                       {"kind", core::toString(c.kind)},
                                       {"shape", c.shape},
                                       {"color_name", c.colourName},
                                       {"dimensions_m", {c.dimensions_m.x(), c.dimensions_m.y(), c.dimensions_m.z()}},
                                       {"footprint_m", footprint}});
    }
    j["discovery"] = r.discoveryNotes;
  }
  j["report_files"] = r.reportFiles;
  return j.dump(2);
}

}  // namespace srp::programming
