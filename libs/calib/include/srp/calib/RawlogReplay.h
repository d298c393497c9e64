#pragma once
/// \file RawlogReplay.h
/// \brief Replays an RGB-D rawlog (srp::rawlog::RawlogReader): summary
/// (frames, duration, rate, intrinsics), export of colour/depth PNGs that
/// `srp import` reads back bit-exactly, and an MJPG video with optional overlay.

#include <functional>
#include <nlohmann/json_fwd.hpp>
#include <opencv2/core.hpp>
#include <optional>
#include <string>

#include "srp/core/CameraIntrinsics.h"
#include "srp/rawlog/RgbdFrame.h"

namespace srp::calib {

struct ReplayOptions {
  /// When set: colour_NNNN.png (8-bit BGR), depth_NNNN.png (16-bit, depth /
  /// depth scale), depth_color_NNNN.png (the depth colour-mapped for a person
  /// to look at: OpenCV's TURBO map, blue near to red far over one range for the
  /// whole recording, ReplaySummary::depthColourRange_m; black = no depth) and
  /// cam.json (intrinsics + depthScale) are written here.
  std::string exportDir;
  /// Metres per exported depth unit; unset: the rawlog's own unit (lossless).
  std::optional<double> exportDepthScale_m;
  /// When set: an MJPG .avi of the colour frames (with the overlay).
  std::string videoPath;
  double videoFps = 0.0;  ///< 0: the recording's rate (30 when it has one frame)
  /// Draws on a copy of the colour image before it goes into the video (and,
  /// when exportOverlay, into overlay_NNNN.png).
  std::function<void(cv::Mat& bgr8, const srp::rawlog::RgbdFrame& frame)> overlay;
  bool exportOverlay = false;
  std::function<void(int framesDone)> progress;
};

/// What a replay saw. Rates come from the frame timestamps.
struct ReplaySummary {
  std::string path;
  int frames = 0;
  double firstTime_s = 0.0, lastTime_s = 0.0;
  double duration_s = 0.0;         ///< last - first timestamp
  double fps = 0.0;                ///< (frames - 1) / duration; 0 for a single frame
  srp::core::CameraIntrinsics intrinsics;  ///< of the first frame
  bool intrinsicsChange = false;   ///< a later frame has other intrinsics
  double depthUnit_m = 0.0;        ///< depth step stored in the rawlog
  double validDepthFraction = 0.0; ///< mean fraction of pixels with depth
  bool hasColour = true;           ///< every frame has a colour image
  int objectsSkipped = 0;          ///< non-RGB-D objects in the file
  std::optional<std::string> damage;  ///< where a damaged file ended
  int depthClipped = 0;            ///< exported depth pixels beyond 16 bits (written as 0)
  /// Depth range [m] of the exported colour-mapped depth (blue .. red): the 1st
  /// and 99th percentile of the first frame's valid depth; zero without export.
  double depthColourNear_m = 0.0, depthColourFar_m = 0.0;
  /// Frames whose depth the reader re-projected from the depth camera into the
  /// colour camera (rawlog::needsRegistration): 0 for a registered recording,
  /// `frames` for one whose two cameras differ.
  int framesRegisteredOnRead = 0;
  /// "registered" (as recorded), "unregistered" (registered on read) or "mixed".
  std::string depthAlignment() const;

  nlohmann::json toJson() const;
  std::string toText() const;      ///< a few human-readable lines
};

/// Reads the whole rawlog once, doing what the options ask. A damaged
/// (truncated) file is not an error: the frames before the damage are
/// replayed and `damage` says where it ended. Throws FileError naming the
/// file when it is missing or holds no RGB-D frame at all, or naming the
/// output when it cannot be written.
ReplaySummary replayRawlog(const std::string& path, const ReplayOptions& options = {});

}  // namespace srp::calib
