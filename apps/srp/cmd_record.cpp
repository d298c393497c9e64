// srp record: an OpenNI2 RGB-D camera to a rawlog.
#include <cstdio>
#include <iostream>

#include <nlohmann/json.hpp>
#include "CommandRegistry.h"
#include "CommonOptions.h"
#include "ProgressLine.h"

#include "srp/calib/RgbdRecorder.h"
#include "srp/core/OutputFile.h"

namespace {

struct Args {
  std::string out;
  srp::calib::RecordOptions options;
  bool overwrite = false, json = false;
};

void setupRecord(CLI::App& cmd) {
  auto a = std::make_shared<Args>();
  cmd.add_option("-o,--out", a->out, "rawlog to write");
  srp::app::addDeprecatedPositional(cmd, "out", a->out, "--out");
  cmd.add_flag("--json", a->json, "print the summary as JSON");
  cmd.add_option("--frames", a->options.maxFrames, "stop after this many frames (0: no limit)")->capture_default_str();
  cmd.add_option("--duration", a->options.duration_s, "stop after this many seconds (0: no limit)")
      ->capture_default_str();
  cmd.add_option("--device", a->options.deviceIndex, "OpenNI2 device number")->capture_default_str();
  cmd.add_option("--depth-unit", a->options.depthUnit_m, "depth step stored in the rawlog [m]")->capture_default_str();
  srp::app::addOverwriteFlag(cmd, a->overwrite);
  cmd.footer(
      "Example: srp record -o demo.rawlog --duration 20\nNo camera? Convert recorded images: srp import FOLDER -o "
      "OUT.rawlog");
  cmd.callback([a, &cmd] {
    srp::app::requireOneOf(cmd, "--out", "out");
    srp::core::checkOutputPaths({{"--out", a->out}}, {}, a->overwrite);
    srp::app::ProgressLine line(srp::app::progressWanted(a->json));
    a->options.progress = [&line](int frames, double elapsed_s) {
      line.show("recording:", static_cast<std::size_t>(frames), 0, "frames, " + std::to_string(static_cast<int>(elapsed_s)) + " s");
    };
    const auto s = srp::calib::recordOpenNI2(a->out, a->options);
    line.finish();
    if (a->json) {
      std::cout << nlohmann::json{{"rawlog", a->out},
                                  {"frames", s.frames},
                                  {"duration_s", s.duration_s},
                                  {"width_px", s.intrinsics.width_px},
                                  {"height_px", s.intrinsics.height_px},
                                  {"fx_px", s.intrinsics.fx_px}}
                       .dump(2)
                << "\n";
      return;
    }
    std::printf("%s: %d frames, %.2f s, %dx%d fx %.2f\n", a->out.c_str(), s.frames, s.duration_s, s.intrinsics.width_px,
                s.intrinsics.height_px, s.intrinsics.fx_px);
  });
}

const srp::app::CommandRegistrar kReg{"record", "Record an RGB-D camera (OpenNI2) to a rawlog", 20, setupRecord};

}  // namespace
