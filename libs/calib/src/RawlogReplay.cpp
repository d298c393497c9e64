#include "srp/calib/RawlogReplay.h"

#include <algorithm>
#include <cmath>
#include <tuple>
#include <vector>
#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>
#include <sstream>

#include "srp/core/Error.h"
#include "srp/core/Json.h"
#include "srp/rawlog/RawlogReader.h"

namespace srp::calib {

namespace fs = std::filesystem;

nlohmann::json ReplaySummary::toJson() const {
  nlohmann::json j{{"path", path},
                   {"frames", frames},
                   {"first_time_s", firstTime_s},
                   {"duration_s", duration_s},
                   {"fps", fps},
                   {"intrinsics", intrinsics},
                   {"intrinsics_change", intrinsicsChange},
                   {"depth_unit_m", depthUnit_m},
                   {"valid_depth_fraction", validDepthFraction},
                   {"has_colour", hasColour},
                   {"objects_skipped", objectsSkipped},
                   {"depth_clipped", depthClipped},
                   {"depth_alignment", depthAlignment()},
                   {"frames_registered_on_read", framesRegisteredOnRead}};
  j["damage"] = damage ? nlohmann::json(*damage) : nlohmann::json(nullptr);
  if (depthColourFar_m > 0.0) j["depth_color_range_m"] = {depthColourNear_m, depthColourFar_m};
  return j;
}

std::string ReplaySummary::depthAlignment() const {
  if (framesRegisteredOnRead == 0) return "registered";
  return framesRegisteredOnRead == frames ? "unregistered" : "mixed";
}

std::string ReplaySummary::toText() const {
  std::ostringstream s;
  s.precision(6);
  s << path << "\n  frames:     " << frames << "\n  duration:   " << duration_s << " s\n  rate:       " << fps
    << " fps\n  intrinsics: " << intrinsics.width_px << "x" << intrinsics.height_px << " fx " << intrinsics.fx_px
    << " fy " << intrinsics.fy_px << " cx " << intrinsics.cx_px << " cy " << intrinsics.cy_px
    << (intrinsicsChange ? " (changes during the recording)" : "") << "\n  depth:      unit " << depthUnit_m * 1000.0
    << " mm, " << std::round(validDepthFraction * 1000.0) / 10.0 << " % of pixels valid\n";
  if (framesRegisteredOnRead == 0)
    s << "  alignment:  registered as recorded (depth pixel = colour pixel)\n";
  else
    s << "  alignment:  unregistered: depth re-projected into the colour camera on reading (" << framesRegisteredOnRead
      << " of " << frames << " frames; intrinsics above are the colour camera's)\n";
  if (!hasColour) s << "  colour:     missing in some frames\n";
  if (objectsSkipped > 0) s << "  skipped:    " << objectsSkipped << " non-RGB-D objects\n";
  if (damage) s << "  DAMAGED:    " << *damage << "\n";
  if (depthColourFar_m > 0.0)
    s << "  depth_color_NNNN.png: blue " << depthColourNear_m << " m .. red " << depthColourFar_m
      << " m, black = no depth\n";
  return s.str();
}

namespace {

/// The float unit stored in the rawlog as the shortest decimal that reads back
/// as the same float (0.001f -> 0.001, not 0.0010000000474974513).
double shortestDecimal(double unit) {
  const float f = static_cast<float>(unit);
  for (int digits = 1; digits <= 9; ++digits) {
    char text[40];
    std::snprintf(text, sizeof text, "%.*g", digits, static_cast<double>(f));
    const double d = std::strtod(text, nullptr);
    if (static_cast<float>(d) == f) return d;
  }
  return unit;
}

std::string numbered(const std::string& dir, const char* prefix, int index) {
  char name[64];
  std::snprintf(name, sizeof name, "%s_%04d.png", prefix, index);
  return (fs::path(dir) / name).string();
}

// The 1st and 99th percentile of the valid depth (0.3 .. 3 m when there is none).
std::pair<double, double> depthColourRange(const cv::Mat& depth_m) {
  std::vector<float> valid;
  for (int r = 0; r < depth_m.rows; ++r) {
    const float* d = depth_m.ptr<float>(r);
    for (int c = 0; c < depth_m.cols; ++c)
      if (std::isfinite(d[c]) && d[c] > 0.0f) valid.push_back(d[c]);
  }
  if (valid.size() < 2) return {0.3, 3.0};
  const auto at = [&](double q) {
    auto it = valid.begin() + static_cast<std::ptrdiff_t>(q * static_cast<double>(valid.size() - 1));
    std::nth_element(valid.begin(), it, valid.end());
    return static_cast<double>(*it);
  };
  const double near = at(0.01), far = at(0.99);
  return {near, std::max(far, near + 0.01)};
}

// Depth as a picture: TURBO from blue (near_m) to red (far_m), black where there is no depth.
cv::Mat colourMappedDepth(const cv::Mat& depth_m, double near_m, double far_m) {
  cv::Mat grey(depth_m.size(), CV_8UC1);
  cv::Mat invalid(depth_m.size(), CV_8UC1, cv::Scalar(0));
  for (int r = 0; r < depth_m.rows; ++r) {
    const float* d = depth_m.ptr<float>(r);
    uint8_t* g = grey.ptr<uint8_t>(r);
    uint8_t* bad = invalid.ptr<uint8_t>(r);
    for (int c = 0; c < depth_m.cols; ++c) {
      const bool ok = std::isfinite(d[c]) && d[c] > 0.0f;
      g[c] = ok ? cv::saturate_cast<uint8_t>(255.0 * (d[c] - near_m) / (far_m - near_m)) : 0;
      bad[c] = ok ? 0 : 255;
    }
  }
  cv::Mat colour;
  cv::applyColorMap(grey, colour, cv::COLORMAP_TURBO);
  colour.setTo(cv::Scalar(0, 0, 0), invalid);
  return colour;
}

/// Frame `s.frames` as PNGs in the export folder: depth in 16-bit steps of `exportScale_m` (counting the
/// pixels beyond 16 bits in `s.depthClipped`), depth colour-mapped (its range from the first frame),
/// and colour when the frame has it.
void exportFrame(const rawlog::RgbdFrame& f, const ReplayOptions& options, double exportScale_m, bool colour,
                 ReplaySummary& s) {
  cv::Mat depth16(f.depth_m.size(), CV_16UC1);
  const double inv = 1.0 / static_cast<double>(static_cast<float>(exportScale_m));
  for (int r = 0; r < depth16.rows; ++r) {
    const float* d = f.depth_m.ptr<float>(r);
    uint16_t* o = depth16.ptr<uint16_t>(r);
    for (int c = 0; c < depth16.cols; ++c) {
      const double steps = std::round(static_cast<double>(d[c]) * inv);
      const bool ok = std::isfinite(d[c]) && d[c] > 0.0f;
      if (ok && steps > 65535.0) ++s.depthClipped;
      o[c] = (ok && steps <= 65535.0) ? static_cast<uint16_t>(steps) : uint16_t(0);
    }
  }
  const std::string depthPath = numbered(options.exportDir, "depth", s.frames);
  if (!cv::imwrite(depthPath, depth16)) throw core::FileError(depthPath, "cannot write depth PNG");
  if (s.frames == 0) std::tie(s.depthColourNear_m, s.depthColourFar_m) = depthColourRange(f.depth_m);
  const std::string colourDepthPath = numbered(options.exportDir, "depth_color", s.frames);
  if (!cv::imwrite(colourDepthPath, colourMappedDepth(f.depth_m, s.depthColourNear_m, s.depthColourFar_m)))
    throw core::FileError(colourDepthPath, "cannot write the colour-mapped depth PNG");
  if (colour) {
    const std::string colourPath = numbered(options.exportDir, "color", s.frames);
    if (!cv::imwrite(colourPath, f.colour_bgr8)) throw core::FileError(colourPath, "cannot write colour PNG");
  }
}

/// cam.json in the export folder: the intrinsics and depth scale of the exported PNGs (ViSP's names).
void writeExportCamera(const ReplaySummary& s, const ReplayOptions& options, double exportScale_m,
                       const std::string& rawlogPath) {
  const auto& K = s.intrinsics;
  core::writeJsonFile((fs::path(options.exportDir) / "cam.json").string(),
                      {{"w", K.width_px},
                       {"h", K.height_px},
                       {"px", K.fx_px},
                       {"py", K.fy_px},
                       {"u0", K.cx_px},
                       {"v0", K.cy_px},
                       {"depthScale", exportScale_m},
                       {"model", "perspectiveProjWithoutDistortion"},
                       {"source", rawlogPath}});
}

}  // namespace

ReplaySummary replayRawlog(const std::string& path, const ReplayOptions& options) {
  rawlog::RawlogReader reader(path);
  ReplaySummary s;
  s.path = path;
  double exportScale_m = 0.0;
  cv::VideoWriter video;
  cv::Mat pendingVideoFrame;
  const auto openVideo = [&](double fps, cv::Size size) {
    video.open(options.videoPath, cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), fps, size, true);
    if (!video.isOpened())
      throw core::FileError(options.videoPath, "cannot open an MJPG video writer (use a .avi path in a writable folder)");
  };
  double validSum = 0.0;
  if (!options.exportDir.empty()) {
    std::error_code ec;
    fs::create_directories(options.exportDir, ec);
    if (!fs::is_directory(options.exportDir))
      throw core::FileError(options.exportDir, "cannot create the export folder");
  }
  while (auto frame = reader.next()) {
    const auto& f = *frame;
    if (s.frames == 0) {
      s.intrinsics = f.intrinsics;
      s.firstTime_s = f.t_s;
      s.depthUnit_m = shortestDecimal(reader.depthUnit_m());
      exportScale_m = options.exportDepthScale_m.value_or(s.depthUnit_m);
      if (!(exportScale_m > 0.0)) throw core::InvalidInputError("export depth scale must be positive");
    } else if (f.intrinsics != s.intrinsics) {
      s.intrinsicsChange = true;
    }
    s.lastTime_s = f.t_s;
    validSum += static_cast<double>(cv::countNonZero(f.depth_m > 0.0f)) / static_cast<double>(f.depth_m.total());
    const bool colour = !f.colour_bgr8.empty();
    s.hasColour = s.hasColour && colour;
    if (f.depthRegisteredOnRead) ++s.framesRegisteredOnRead;

    if (!options.exportDir.empty()) exportFrame(f, options, exportScale_m, colour, s);
    if (colour && (!options.videoPath.empty() || (options.exportOverlay && !options.exportDir.empty()))) {
      cv::Mat drawn = f.colour_bgr8.clone();
      if (options.overlay) options.overlay(drawn, f);
      if (!options.videoPath.empty()) {
        // The writer needs the rate up front: take it from the first two
        // timestamps (unless given), holding the first frame back until then.
        if (!video.isOpened() && pendingVideoFrame.empty() && options.videoFps <= 0.0) {
          pendingVideoFrame = drawn;
        } else {
          if (!video.isOpened()) {
            const double dt = f.t_s - s.firstTime_s;
            openVideo(options.videoFps > 0.0 ? options.videoFps : (dt > 1.0 / 240.0 && dt < 1.0 ? 1.0 / dt : 30.0),
                      drawn.size());
          }
          if (!pendingVideoFrame.empty()) video.write(pendingVideoFrame);
          pendingVideoFrame.release();
          video.write(drawn);
        }
      }
      if (options.exportOverlay && !options.exportDir.empty()) {
        const std::string p = numbered(options.exportDir, "overlay", s.frames);
        if (!cv::imwrite(p, drawn)) throw core::FileError(p, "cannot write overlay PNG");
      }
    }
    ++s.frames;
    if (options.progress) options.progress(s.frames);
  }
  if (!pendingVideoFrame.empty()) {  // a one-frame recording
    openVideo(30.0, pendingVideoFrame.size());
    video.write(pendingVideoFrame);
  }
  video.release();
  s.damage = reader.damage();
  s.objectsSkipped = reader.objectsSkipped();
  if (s.frames == 0) {
    if (s.damage) throw core::FileError(path, "no readable RGB-D frame: " + *s.damage);
    throw core::FileError(path, "no RGB-D frames (CObservation3DRangeScan with depth) in this rawlog (" +
                                    std::to_string(s.objectsSkipped) + " other objects)");
  }
  s.duration_s = s.lastTime_s - s.firstTime_s;
  s.fps = (s.frames > 1 && s.duration_s > 0.0) ? (s.frames - 1) / s.duration_s : 0.0;
  s.validDepthFraction = validSum / s.frames;
  if (!options.exportDir.empty()) writeExportCamera(s, options, exportScale_m, path);
  return s;
}

}  // namespace srp::calib
