// srp record: an OpenNI2 RGB-D camera to a rawlog.
#include <cstdio>
#include <iostream>

#include "CommandRegistry.h"
#include "ProgressLine.h"
#include "srp/calib/RgbdRecorder.h"
#include "srp/core/OutputFile.h"

namespace {

struct Args {
  std::string out;
  srp::calib::RecordOptions options;
  bool overwrite = false;
};

void setupRecord(CLI::App& cmd) {
  auto a = std::make_shared<Args>();
  cmd.add_option("out", a->out, "rawlog to write")->required();
  cmd.add_option("--frames", a->options.maxFrames, "stop after this many frames (0: no limit)")->capture_default_str();
  cmd.add_option("--duration", a->options.duration_s, "stop after this many seconds (0: no limit)")
      ->capture_default_str();
  cmd.add_option("--device", a->options.deviceIndex, "OpenNI2 device number")->capture_default_str();
  cmd.add_option("--depth-unit", a->options.depthUnit_m, "depth step stored in the rawlog [m]")->capture_default_str();
  srp::app::addOverwriteFlag(cmd, a->overwrite);
  cmd.footer("Example: srp record demo.rawlog --duration 20\nNo camera? Convert recorded images: srp import FOLDER OUT.rawlog");
  cmd.callback([a] {
    srp::core::checkOutputPaths({{"out", a->out}}, {}, a->overwrite);
    srp::app::ProgressLine line;
    a->options.progress = [&line](int frames, double elapsed_s) {
      line.show("recording:", static_cast<std::size_t>(frames), 0, "frames, " + std::to_string(static_cast<int>(elapsed_s)) + " s");
    };
    const auto s = srp::calib::recordOpenNI2(a->out, a->options);
    line.finish();
    std::printf("%s: %d frames, %.2f s, %dx%d fx %.2f\n", a->out.c_str(), s.frames, s.duration_s, s.intrinsics.width_px,
                s.intrinsics.height_px, s.intrinsics.fx_px);
  });
}

const srp::app::CommandRegistrar kReg{"record", "Record an RGB-D camera (OpenNI2) to a rawlog", 20, setupRecord};

}  // namespace
