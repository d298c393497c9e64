#pragma once
/// \file RgbdImporter.h
/// \brief Imports RGB-D recordings stored as image files into an MRPT rawlog
/// (through srp::rawlog::RawlogWriter): an image folder (colour PNG/JPG +
/// 16-bit depth PNG) or the TUM RGB-D benchmark layout.

#include <functional>
#include <optional>
#include <vector>
#include <string>

#include "srp/core/CameraIntrinsics.h"

namespace srp::calib {

struct ImportOptions {
  /// Camera file (ViSP XML, or JSON: cam.json / srp intrinsics). Empty: the
  /// folder's camera.xml, cam.json or intrinsics.json, in that order.
  std::string cameraPath;
  /// Metres per depth PNG unit. Unset: the camera JSON's depthScale, else
  /// 0.001 for a folder (millimetres) and 1/5000 for TUM. The rawlog stores
  /// depth in this same unit, so depth round-trips bit-exactly.
  std::optional<double> depthScale_m;
  /// Image folders without timestamps: frame number N at t = (N - first N) / fps
  /// [s] (a gap in the numbers stays a gap in time). Unset: the folder's
  /// timestamps (timestamps.txt), else kAssumedFps with a warning in the
  /// summary. A folder with timestamps keeps them (an --fps that disagrees by
  /// more than 5 % is warned about).
  std::optional<double> fps;
  double maxTimeDifference_s = 0.02;   ///< TUM: colour/depth association window
  /// Depth camera file (ViSP XML, or JSON as above, optionally with a
  /// "distortion" object {k1, k2, p1, p2, k3}) of a recording whose depth is
  /// not registered to colour. Empty: the folder's depth_camera.xml,
  /// depth_cam.json or depth_intrinsics.json, else the camera named
  /// "depth_camera" in its camera.xml (ViSP's saveRealSenseData layout, whose
  /// colour camera is then "color_camera"). No depth camera: depth must be
  /// registered to colour (same size), as before.
  std::string depthCameraPath;
  /// ViSP's depth_M_color.txt (vpHomogeneousMatrix::save: 4 rows of 4 numbers,
  /// p_depth = depth_M_color * p_colour, metres). Empty: the folder's
  /// depth_M_color.txt; none: identity (the cameras share their optical centre).
  std::string depthToColourPath;
  std::function<void(int done, int total)> progress;
};

/// The frame rate an image folder is given when it has no timestamps and no
/// ImportOptions::fps (said loudly in the summary's warnings).
inline constexpr double kAssumedFps = 30.0;

/// What an import produced.
struct ImportSummary {
  std::string layout;                  ///< "folder" or "tum"
  int frames = 0;
  double depthScale_m = 0.0;
  srp::core::CameraIntrinsics intrinsics;
  std::vector<std::string> colourFiles;  ///< in frame order
  std::vector<std::string> depthFiles;   ///< paired with colourFiles
  int unpairedDepth = 0;               ///< depth images without a colour partner (ignored)
  /// Depth re-projected into the colour camera on import (rawlog::DepthRegistration):
  /// the recording had a depth camera of its own.
  bool depthRegistered = false;
  srp::core::CameraIntrinsics depthIntrinsics;  ///< of the depth images (== intrinsics when not registered)
  double depthToColourBaseline_m = 0.0;         ///< distance of the two optical centres
  double fps = 0.0;          ///< frame rate of the rawlog's timestamps (median frame period)
  /// Where the rate came from: "timestamps" (TUM lists, a folder's
  /// timestamps.txt), "--fps" (ImportOptions::fps) or "assumed" (neither: kAssumedFps).
  std::string fpsSource;
  int missingFrames = 0;     ///< numbers missing between the first and last frame (gaps, kept in time)
  std::vector<int> framesWithoutDepth;  ///< rawlog frames whose depth image has no valid pixel
  /// Everything a user should know before trusting the rawlog: an assumed rate,
  /// gaps in the frame numbers, frames without depth; one line each.
  std::vector<std::string> warnings;
};

/// Common to both layouts: the rawlog is written atomically (a failed import
/// leaves the previous file, if any, as it was); it must not be one of the
/// inputs (the folder itself, an image or camera file it reads; FileError
/// otherwise; a new file in the folder is fine); every image's size is read from its header and checked against
/// its camera file before it is decoded (a small file claiming a huge image is
/// refused, nothing is allocated for it).
///
/// Image folder: colour files `color_N`, `colour_N` or `rgb_N` (.png/.jpg,
/// any zero padding, optional separator) or any `N.png/.jpg` inside a `color/`,
/// `colour/` or `rgb/` subfolder; depth files `depth_N.png` or `depth/N.png`,
/// 16-bit single channel, paired by the number N. Depth is either registered
/// to colour (same size, one camera file) or seen by its own depth camera
/// (any size; a depth camera file and depth_M_color.txt, see ImportOptions):
/// then each depth image is re-projected into the colour camera
/// (rawlog::DepthRegistration) and the rawlog holds colour-sized depth with
/// the colour camera's intrinsics. Colour images are never resized, and must
/// be undistorted (the depth camera may have lens distortion).
/// Times: from `timestamps.txt` in the folder when it is there (lines "N t"
/// pairing a frame number with its time in seconds; '#' comments), else
/// (N - first N) / fps. Errors (FileError naming the file): no colour images, a
/// colour image without depth, an unreadable image, a depth image that is not
/// 16-bit single-channel, sizes that differ from each other or from the
/// intrinsics, a frame without a timestamp or timestamps not increasing.
ImportSummary importImageFolder(const std::string& folder, const std::string& rawlogPath,
                                const ImportOptions& options = {});

/// TUM RGB-D layout: `rgb.txt` and `depth.txt` ("timestamp path" lines, '#'
/// comments) with the images they name; colour and depth associated by
/// nearest timestamp within maxTimeDifference_s (each image used once, as the
/// benchmark's associate.py does). Frame times are the colour timestamps.
ImportSummary importTum(const std::string& folder, const std::string& rawlogPath, const ImportOptions& options = {});

/// importTum when the folder has rgb.txt, importImageFolder otherwise.
ImportSummary importRecording(const std::string& folder, const std::string& rawlogPath,
                              const ImportOptions& options = {});

}  // namespace srp::calib
