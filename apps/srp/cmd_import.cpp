// srp import: an image folder or a TUM RGB-D sequence to a rawlog.
#include <unistd.h>

#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>

#include "CommandRegistry.h"
#include "CommonOptions.h"
#include "ProgressLine.h"
#include "srp/calib/RgbdImporter.h"
#include "srp/core/OutputFile.h"

namespace {

struct Args {
  std::string folder, out, layout = "auto";
  std::string intrinsics, depthIntrinsics, depthMColor;
  double depthScale_m = 0.0;
  double fps = 0.0;  // 0: the folder's timestamps, else assumed (warned)
  double maxDt_s = 0.02;
  bool json = false, overwrite = false;
};

void setupImport(CLI::App& cmd) {
  auto a = std::make_shared<Args>();
  cmd.add_option("folder", a->folder, "image folder (color_N + depth_N images) or TUM RGB-D sequence")->required();
  cmd.add_option("-o,--out", a->out, "rawlog to write");
  srp::app::addDeprecatedPositional(cmd, "out", a->out, "--out");
  cmd.add_option("--layout", a->layout, "auto (TUM when rgb.txt is there), folder or tum")
      ->check(CLI::IsMember({"auto", "folder", "tum"}))
      ->capture_default_str();
  cmd.add_option("--intrinsics", a->intrinsics,
                 "camera file: ViSP XML or JSON (default: the folder's camera.xml, cam.json or intrinsics.json)");
  cmd.add_option("--depth-intrinsics", a->depthIntrinsics,
                 "depth camera file (ViSP XML or JSON) when depth is not registered to colour (default: the "
                 "folder's depth_camera.xml, depth_cam.json, depth_intrinsics.json or camera 'depth_camera' in "
                 "camera.xml); depth is then re-projected into the colour camera");
  cmd.add_option("--depth-M-color", a->depthMColor,
                 "ViSP depth_M_color.txt: 4x4 pose of the colour camera in the depth camera (default: the folder's "
                 "depth_M_color.txt, else identity)");
  cmd.add_option("--depth-scale", a->depthScale_m,
                 "metres per depth PNG unit (default: the camera JSON's depthScale, else 0.001; TUM 0.0002)")
      ->check(CLI::Range(1e-6, 1.0));
  cmd.add_option("--fps", a->fps,
                 "frame rate of an image folder without timestamps (frame N at t = N / fps; default: the folder's "
                 "timestamps.txt, else 30 with a warning)")
      ->check(CLI::Range(0.1, 1000.0));
  cmd.add_option("--max-dt", a->maxDt_s, "TUM: max colour/depth timestamp difference [s]")
      ->check(CLI::Range(0.0, 10.0))
      ->capture_default_str();
  cmd.add_flag("--json", a->json, "print the summary as JSON");
  cmd.footer("Example: srp import datasets/real/visp-rbt-cube -o cube.rawlog");
  srp::app::addOverwriteFlag(cmd, a->overwrite);
  cmd.callback([a, &cmd] {
    srp::app::requireOneOf(cmd, "--out", "out");
    srp::core::checkOutputPaths({{"--out", a->out}},
                                {{"folder", a->folder},
                                 {"--intrinsics", a->intrinsics},
                                 {"--depth-intrinsics", a->depthIntrinsics},
                                 {"--depth-M-color", a->depthMColor}},
                                a->overwrite);
    srp::calib::ImportOptions o;
    o.cameraPath = a->intrinsics;
    o.depthCameraPath = a->depthIntrinsics;
    o.depthToColourPath = a->depthMColor;
    if (a->depthScale_m > 0.0) o.depthScale_m = a->depthScale_m;
    if (a->fps > 0.0) o.fps = a->fps;
    o.maxTimeDifference_s = a->maxDt_s;
    srp::app::ProgressLine line(srp::app::progressWanted(a->json));
    o.progress = [&line](int done, int total) {
      line.show("importing", static_cast<std::size_t>(done), static_cast<std::size_t>(total));
      if (done == total) line.finish();
    };
    const auto s = a->layout == "tum"      ? srp::calib::importTum(a->folder, a->out, o)
                   : a->layout == "folder" ? srp::calib::importImageFolder(a->folder, a->out, o)
                                           : srp::calib::importRecording(a->folder, a->out, o);
    const auto& K = s.intrinsics;
    if (a->json) {
      std::cout << nlohmann::json{{"rawlog", a->out},         {"layout", s.layout},
                                  {"frames", s.frames},       {"depth_scale_m", s.depthScale_m},
                                  {"intrinsics", K},          {"unpaired_depth", s.unpairedDepth},
                                  {"depth_registered", s.depthRegistered},
                                  {"depth_intrinsics", s.depthIntrinsics},
                                  {"depth_to_colour_baseline_m", s.depthToColourBaseline_m},
                                  {"fps", s.fps},
                                  {"fps_source", s.fpsSource},
                                  {"missing_frames", s.missingFrames},
                                  {"frames_without_depth", s.framesWithoutDepth},
                                  {"warnings", s.warnings}}
                       .dump(2)
                << "\n";
      for (const auto& w : s.warnings) std::cerr << "srp import: WARNING: " << w << "\n";
      return;
    }
    std::printf("%s -> %s: %d frames (%s layout), depth scale %g m/unit, %dx%d fx %.3f fy %.3f cx %.3f cy %.3f\n",
                a->folder.c_str(), a->out.c_str(), s.frames, s.layout.c_str(), s.depthScale_m, K.width_px, K.height_px,
                K.fx_px, K.fy_px, K.cx_px, K.cy_px);
    if (s.depthRegistered)
      std::printf("  depth %dx%d from its own camera (%.1f mm from the colour camera) registered to colour\n",
                  s.depthIntrinsics.width_px, s.depthIntrinsics.height_px, 1e3 * s.depthToColourBaseline_m);
    else
      std::printf("  depth registered to colour as recorded\n");
    if (s.unpairedDepth > 0) std::printf("  %d depth images without a colour partner were left out\n", s.unpairedDepth);
    std::printf("  frame rate %.3g frames/s (%s)\n", s.fps,
                s.fpsSource == "assumed" ? "ASSUMED: no timestamps and no --fps" : ("from " + s.fpsSource).c_str());
    for (const auto& w : s.warnings) std::cerr << "srp import: WARNING: " << w << "\n";
  });
}

const srp::app::CommandRegistrar kReg{"import", "Convert an image folder or TUM RGB-D sequence to a rawlog", 21,
                                      setupImport};

}  // namespace
