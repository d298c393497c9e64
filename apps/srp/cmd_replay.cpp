// srp replay: summary of an RGB-D rawlog, PNG export and video.
#include <filesystem>
#include <iostream>
#include <optional>
#include <nlohmann/json.hpp>

#include "CommandRegistry.h"
#include "CommonOptions.h"
#include "ProgressLine.h"
#include "srp/calib/RawlogReplay.h"
#include "srp/calib/TaskModelOverlay.h"
#include "srp/core/Error.h"
#include "srp/core/ExitCode.h"
#include "srp/core/OutputFile.h"
#include "srp/taskdb/TaskDatabase.h"
#include "srp/taskdb/TaskModelStore.h"

namespace {

struct Args {
  std::string rawlog, exportDir, video, overlayDb;
  int taskId = 0;  // 0: the newest task model
  int firstTimeId = 0;
  double depthScale_m = 0.0;
  double fps = 0.0;
  bool json = false, overwrite = false;
};

void setupReplay(CLI::App& cmd) {
  auto a = std::make_shared<Args>();
  cmd.add_option("rawlog", a->rawlog, "rawlog to replay")->required();
  cmd.add_option("-o,--out", a->exportDir,
                 "write color_NNNN.png, 16-bit depth_NNNN.png and cam.json here (importable again)");
  srp::app::addDeprecatedOption(cmd, "--export", a->exportDir, "--out");
  cmd.add_option("--depth-scale", a->depthScale_m,
                 "metres per exported depth unit (default: the rawlog's own unit, lossless)")
      ->check(CLI::Range(1e-6, 1.0));
  cmd.add_option("--video", a->video, "write an MJPG video of the colour frames (.avi)");
  cmd.add_option("--fps", a->fps, "video frame rate (default: the recording's)")->check(CLI::Range(0.1, 1000.0));
  cmd.add_option("--overlay", a->overlayDb,
                 "task database: draw a task model's trajectories, detections and skills on the video and as "
                 "overlay_NNNN.png in --out");
  cmd.add_option("--task", a->taskId, "task model to draw (default: the newest)")->check(srp::app::kDecimalId);
  srp::app::addDeprecatedOption(cmd, "--task-id", a->taskId, "--task")->check(srp::app::kDecimalId);
  cmd.add_option("--first-time-id", a->firstTimeId, "TimeId of the rawlog's first frame")->capture_default_str();
  cmd.add_flag("--json", a->json, "print the summary as JSON");
  srp::app::addOverwriteFlag(cmd, a->overwrite);
  cmd.footer("Example: srp replay demo.rawlog -o frames/ --video demo.avi --overlay task.db");
  cmd.callback([a] {
    using srp::core::PathRole;
    srp::core::checkOutputPaths({{"--out", a->exportDir}, {"--video", a->video}},
                                {{"rawlog", a->rawlog}, {"--overlay", a->overlayDb}}, a->overwrite);
    // Outputs are made beside their targets and put in place when the replay is done.
    std::optional<srp::core::AtomicOutputFolder> exportFolder;
    std::optional<srp::core::AtomicOutputFile> videoFile;
    if (!a->exportDir.empty()) {
      srp::core::checkFolderHoldsOnly(a->exportDir, {"color_*", "depth_*", "overlay_*", "cam.json"}, "--out");
      exportFolder.emplace(std::filesystem::path(a->exportDir).lexically_normal());
    }
    if (!a->video.empty()) videoFile.emplace(a->video);
    srp::calib::ReplayOptions o;
    if (exportFolder) o.exportDir = exportFolder->temporaryPath().string();
    if (a->depthScale_m > 0.0) o.exportDepthScale_m = a->depthScale_m;
    if (videoFile) o.videoPath = videoFile->temporaryPath().string();
    o.videoFps = a->fps;
    std::shared_ptr<srp::calib::TaskModelOverlay> overlay;
    if (!a->overlayDb.empty()) {
      if (a->exportDir.empty() && a->video.empty())
        throw srp::core::InvalidInputError("--overlay draws into --video and/or --out: give one of them");
      auto db = srp::taskdb::TaskDatabase::open(a->overlayDb, srp::taskdb::TaskDatabase::Mode::ReadOnly);
      srp::taskdb::TaskModelStore store(db);
      int id = a->taskId;
      if (id == 0) {
        const auto models = store.list();
        if (models.empty()) throw srp::core::FileError(a->overlayDb, "holds no task model to draw");
        id = models.back().id;
      }
      overlay = std::make_shared<srp::calib::TaskModelOverlay>(store.read(id), a->firstTimeId);
      o.overlay = [overlay](cv::Mat& img, const srp::rawlog::RgbdFrame& f) { overlay->draw(img, f); };
      o.exportOverlay = true;
    }
    const bool slow = !o.exportDir.empty() || !o.videoPath.empty();
    srp::app::ProgressLine line(slow && srp::app::progressWanted(a->json));
    o.progress = [&line](int frames) {
      if (frames % 10 == 0) line.show("replayed", static_cast<std::size_t>(frames), 0, "frames");
    };
    const auto s = srp::calib::replayRawlog(a->rawlog, o);
    line.finish("replayed " + std::to_string(s.frames) + " frames");
    if (videoFile) videoFile->commit();
    if (exportFolder) exportFolder->commit();
    if (a->json) std::cout << s.toJson().dump(2) << "\n";
    else std::cout << s.toText();
    if (!a->exportDir.empty() && !a->json) std::cout << "  exported to " << a->exportDir << "\n";
    if (!a->video.empty() && !a->json) std::cout << "  video " << a->video << "\n";
    if (s.damage)  // frames replayed, but the file is damaged
      srp::app::commandExitCode() = srp::core::toInt(srp::core::ExitCode::Partial);
  });
}

const srp::app::CommandRegistrar kReg{"replay", "Summarise a rawlog; export PNGs or a video", 80, setupReplay};

}  // namespace
