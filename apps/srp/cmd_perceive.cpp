// srp perceive: the Environment module on a demo rawlog (libs/perception):
// per-frame hand (palm centre) and object poses, camera frame.
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <iostream>
#include <sstream>

#include "CommandRegistry.h"
#include "CommonOptions.h"
#include "ProgressLine.h"
#include "srp/core/Json.h"
#include "srp/core/OutputFile.h"
#include "srp/kb/KnowledgeBase.h"
#include "srp/perception/DemoPerception.h"
#include "srp/perception/PerceptionDrawing.h"
#include "srp/perception/RawlogPerception.h"

namespace {

using namespace srp::perception;

std::vector<std::string> splitList(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  std::string item;
  while (std::getline(ss, item, ','))
    if (!item.empty()) out.push_back(item);
  return out;
}

struct PerceiveOptions {
  std::string demo, kb, csv, hand = "auto", draw;  // kb empty: the shipped catalogue
  int drawEvery = 1;
  std::string objects, staticObjects, scene;
  double tagSize_m = 0.05;
  int tagId = 0;
  bool json = false;
  bool movingCamera = false, fixedCamera = false;
  bool overwrite = false;
  std::string tracker = "auto";
};

void run(const PerceiveOptions& o) {
  srp::core::checkOutputPaths({{"--out", o.csv}, {"--draw", o.draw}},
                              {{"--demo", o.demo}, {"--kb", o.kb}, {"--scene", o.scene}}, o.overwrite);
  if (!o.draw.empty()) srp::core::checkFolderHoldsOnly(o.draw, {"frame_*", "contact_sheet.png"}, "--draw");
  const auto catalogue = srp::kb::loadCatalogue(o.kb.empty() ? srp::core::ObjectCatalogue::defaultPath() : o.kb);
  PerceptionOptions p;
  p.hand = o.hand == "marker-free" ? PerceptionOptions::HandMethod::MarkerFree
           : o.hand == "none"      ? PerceptionOptions::HandMethod::None
           : o.hand == "marker"    ? PerceptionOptions::HandMethod::Marker
                                   : PerceptionOptions::HandMethod::Auto;
  p.movingCamera = o.movingCamera;
  p.detectCameraMotion = !o.fixedCamera;
  p.objectTracking = o.tracker == "mbt"      ? PerceptionOptions::ObjectTracking::Mbt
                     : o.tracker == "fitter" ? PerceptionOptions::ObjectTracking::Fitter
                                             : PerceptionOptions::ObjectTracking::Auto;
  p.marker.tagSize_m = o.tagSize_m;
  p.marker.tagId = o.tagId;
  const auto statics = splitList(o.staticObjects);
  for (const auto& n : splitList(o.objects)) p.plan.push_back({n, false, "", std::nullopt});
  for (const auto& n : statics) p.plan.push_back({n, true, "", std::nullopt});
  if (!o.scene.empty()) p.plan = withSceneInstances(p.plan, srp::core::Scene::load(o.scene), catalogue);
  srp::app::ProgressLine line(srp::app::progressWanted(o.json));
  const PerceptionResult r = perceiveRawlog(o.demo, catalogue, p, [&line](int i, int) {
    if ((i + 1) % 30 == 0) line.show("perceive: frame", static_cast<std::size_t>(i + 1));
  });
  line.finish("perceive: " + std::to_string(r.frames) + " frames done");
  if (!o.csv.empty()) writeSegmentCsv(r, o.csv);
  if (!o.draw.empty()) {
    const auto files = writeDrawnFrames(o.demo, r, catalogue, o.draw, o.drawEvery);
    if (!srp::app::quietFlag())
      std::fprintf(stderr, "drew %zu frames and a contact sheet in %s\n", files.size() - 1, o.draw.c_str());
  }

  if (o.json) {
    nlohmann::json j;
    j["frames"] = r.frames;
    j["frame"] = "camera";
    j["hand_detector"] = r.handMethod == PerceptionOptions::HandMethod::MarkerFree ? "marker-free"
                         : r.handMethod == PerceptionOptions::HandMethod::None     ? "none"
                                                                                  : "marker";
    j["camera_moved"] = r.cameraMoved;
    if (r.cameraMoved) {
      j["camera_moved_at_frame"] = r.cameraMovedAtFrame;
      j["camera_travel_m"] = r.cameraTravel_m;
      j["camera_turn_deg"] = r.cameraTurn_rad * 180.0 / M_PI;
      j["X_camera0_camera"] = nlohmann::json::array();
      for (const auto& X : r.X_camera0_camera) j["X_camera0_camera"].push_back(srp::core::poseToJson(X));
    }
    j["hand_detected_frames"] = r.handDetected;
    j["hand_depth_carried_frames"] = r.handDepthCarried;
    for (const auto& s : r.hand.samples())
      j["hand"].push_back({{"frame", s.frame}, {"t_s", s.t_s}, {"detected", s.valid},
                           {"p_m", s.valid ? std::vector<double>{s.p_m.x(), s.p_m.y(), s.p_m.z()} : std::vector<double>{}}});
    j["objects"] = nlohmann::json::array();
    for (const auto& obj : r.objects) {
      nlohmann::json jo{{"name", obj.className}, {"instance", obj.instanceId}, {"class_id", obj.classId}, {"static", obj.isStatic},
                        {"detected_frames", obj.detectedFrames()}, {"samples", nlohmann::json::array()}};
      for (const auto& s : obj.samples) {
        nlohmann::json js = srp::core::poseToJson(s.X_camera_object);
        js["frame"] = s.frame;
        js["detected"] = s.detected;
        js["confidence"] = s.confidence;
        js["rz_rad"] = cameraYaw(s.X_camera_object);
        jo["samples"].push_back(js);
      }
      j["objects"].push_back(jo);
    }
    std::cout << j.dump(2) << "\n";
    return;
  }
  std::printf("%d frames, hand detected in %d (%d with carried depth); camera frame, metres\n", r.frames,
              r.handDetected, r.handDepthCarried);
  if (r.cameraMoved)
    std::printf("the camera moved (from frame %d on; up to %.1f cm and %.1f deg from frame 0): each frame's poses are in "
                "its own camera (--json gives each camera's pose in frame 0's)\n",
                r.cameraMovedAtFrame, 100.0 * r.cameraTravel_m, r.cameraTurn_rad * 180.0 / M_PI);
  else
    std::printf("the camera stayed still\n");
  for (const auto& obj : r.objects)
    std::printf("  %-14s %-7s detected in %d frames\n", obj.key().c_str(), obj.isStatic ? "static" : "moving",
                obj.detectedFrames());
  for (std::size_t i = 0; i < r.hand.size(); ++i) {
    const auto& h = r.hand[i];
    if (h.valid) std::printf("%5d hand %+.3f %+.3f %.3f", h.frame, h.p_m.x(), h.p_m.y(), h.p_m.z());
    else std::printf("%5d hand       -      -     -", h.frame);
    for (const auto& obj : r.objects) {
      if (i >= obj.samples.size()) continue;
      const auto& s = obj.samples[i];
      const Eigen::Vector3d t = s.X_camera_object.translation();
      std::printf(" | %s%s %+.3f %+.3f %.3f rz %+.2f", obj.key().c_str(), s.detected ? "" : "*", t.x(), t.y(), t.z(),
                  cameraYaw(s.X_camera_object));
    }
    std::printf("\n");
  }
  if (!o.csv.empty()) std::printf("wrote %s\n", o.csv.c_str());
}

void setupPerceive(CLI::App& app) {
  auto o = std::make_shared<PerceiveOptions>();
  app.add_option("--demo", o->demo, "Demo RGB-D rawlog (srp record / srp synth-demo)")->required();
  app.add_option("--kb", o->kb, "Knowledge-base catalogue JSON (classes may be given by a CAD file alone; default: the shipped "
                 "datasets/kb/catalogue.json of srp's data folder)");
  app.add_option("--hand", o->hand,
                 "Hand detector: auto (the glove's AprilTag when the recording shows it, else the bare hand), marker, "
                 "marker-free, or none (objects only, a recording without a demonstrator)")
      ->check(CLI::IsMember({"auto", "marker", "marker-free", "none"}))
      ->capture_default_str();
  auto* moving = app.add_flag("--moving-camera", o->movingCamera,
                              "Treat the camera as moving from the first frame (by default srp notices a moving camera "
                              "itself, by depth odometry against the first frame): support plane fitted and objects "
                              "detected in every frame on its own");
  app.add_flag("--fixed-camera", o->fixedCamera, "Treat the camera as fixed whatever the frames show (no odometry)")
      ->excludes(moving);
  app.add_option("--tracker", o->tracker,
                 "How a detected part is followed: mbt (ViSP model-based tracker on KLT points of the colour image; "
                 "back to detection when too few points remain or the depth does not confirm the part), fitter "
                 "(detected in every frame), auto (mbt once the camera moves, else fitter)")
      ->check(CLI::IsMember({"auto", "mbt", "fitter"}))
      ->capture_default_str();
  app.add_option("--tag-size", o->tagSize_m, "Glove tag (tag36h11) black square side [m]")->capture_default_str();
  app.add_option("--tag-id", o->tagId, "Glove tag id (-1: any)")->capture_default_str();
  app.add_option("--objects", o->objects, "Moving objects of interest, comma-separated class names (default: all classes)");
  app.add_option("--static", o->staticObjects, "Static objects (containers, landmarks), comma-separated class names");
  app.add_option("--scene", o->scene,
                 "Scene JSON of the demo (srp synth-demo --scene): a listed class the scene holds several times is "
                 "tracked per instance (its id and colour; JSON 'instance', CSV columns named by the instance id)");
  app.add_flag("--json", o->json, "Print JSON");
  app.add_option("-o,--out", o->csv,
                 "Write the per-frame CSV in the 'srp segment' format (a sample not detected in its frame, "
                 "e.g. a part in the hand, is written as 0,0,0,0)");
  srp::app::addDeprecatedOption(app, "--csv", o->csv, "--out");
  srp::app::addOverwriteFlag(app, o->overwrite);
  app.add_option("--draw", o->draw,
                 "Write what perception saw, drawn on the recording, to this folder: frame_NNNNN.png (palm, each "
                 "part and container with its outline, name and confidence, the table frame) and contact_sheet.png "
                 "(replaced as a whole)");
  app.add_option("--draw-every", o->drawEvery, "With --draw: draw every n-th frame (the contact sheet spans them all)")
      ->check(CLI::Range(1, 1000000))
      ->capture_default_str();
  app.footer(
      "Object poses are those of each class's mesh frame (a CAD file's own frame), camera optical frame.\n"
      "Example (a real hand-held recording, objects only):\n"
      "  srp import datasets/real/visp-rbt-cube -o cube.rawlog\n"
      "  srp perceive --demo cube.rawlog --kb my_parts.json --objects cube --hand none --json");
  app.callback([o] { run(*o); });
}

const srp::app::CommandRegistrar kReg{"perceive", "Hand and object trajectories from an RGB-D demo (Environment module)", 40,
                                      setupPerceive};

}  // namespace
