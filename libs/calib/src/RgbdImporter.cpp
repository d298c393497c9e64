#include "srp/calib/RgbdImporter.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <regex>
#include <sstream>

#include "ImageHeader.h"
#include "srp/calib/CameraFiles.h"
#include "srp/core/Error.h"
#include "srp/core/Json.h"
#include "srp/core/OutputFile.h"
#include "srp/core/Text.h"
#include "srp/rawlog/DepthRegistration.h"
#include "srp/rawlog/RawlogWriter.h"

namespace srp::calib {

namespace fs = std::filesystem;

namespace {

std::string typeName(const cv::Mat& m) {
  const char* depth[] = {"8-bit", "8-bit signed", "16-bit", "16-bit signed", "32-bit int", "32-bit float", "64-bit float", "16-bit float"};
  return std::string(depth[m.depth()]) + " " + std::to_string(m.channels()) + "-channel";
}

std::string sizeName(const cv::Mat& m) { return std::to_string(m.cols) + "x" + std::to_string(m.rows); }

bool xmlHasCamera(const fs::path& xml, const std::string& name) {
  if (!fs::is_regular_file(xml)) return false;
  const auto names = cameraNamesInXml(xml.string());
  return std::find(names.begin(), names.end(), name) != names.end();
}

CameraFile findCamera(const std::string& folder, const ImportOptions& options) {
  if (!options.cameraPath.empty()) return loadCameraFile(options.cameraPath);
  // ViSP's saveRealSenseData writes colour, depth and infrared cameras into one camera.xml.
  const fs::path xml = fs::path(folder) / "camera.xml";
  if (xmlHasCamera(xml, "color_camera")) return CameraFile{loadCameraXml(xml.string(), "color_camera"), std::nullopt};
  for (const char* name : {"camera.xml", "cam.json", "intrinsics.json"}) {
    const fs::path p = fs::path(folder) / name;
    if (fs::is_regular_file(p)) return loadCameraFile(p.string());
  }
  throw core::FileError(folder, "no camera file: put camera.xml, cam.json or intrinsics.json in the folder or pass "
                                "--intrinsics FILE (ViSP XML or JSON)");
}

/// The depth camera of an unregistered recording, nullopt for a registered one.
struct DepthCamera {
  rawlog::DepthRegistration::Camera camera;
  core::Pose3 X_colour_depth = core::Pose3::Identity();
};

rawlog::DepthRegistration::Camera toRegistrationCamera(const std::string& path) {
  const CameraFile file = loadCameraFile(path);
  rawlog::DepthRegistration::Camera out;
  out.K = file.camera.intrinsics;
  out.distortion.k1 = file.camera.kud;  // ViSP's model: kud is OpenCV's k1
  if (fs::path(path).extension() != ".xml") {
    const nlohmann::json root = core::readJsonFile(path);
    const nlohmann::json& j = root.contains("intrinsics") ? root.at("intrinsics") : root;
    if (j.contains("distortion")) out.distortion = j.at("distortion").get<rawlog::LensDistortion>();
  }
  return out;
}

core::Pose3 readDepthMColour(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw core::FileError(path, "cannot open depth_M_color (4 rows of 4 numbers, p_depth = depth_M_color p_colour)");
  Eigen::Matrix4d M;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c)
      if (!(in >> M(r, c)))
        throw core::FileError(path, "expected 16 numbers (a 4x4 homogeneous matrix, rows first, metres)");
  const Eigen::Matrix3d R = M.topLeftCorner<3, 3>();
  if ((R * R.transpose() - Eigen::Matrix3d::Identity()).norm() > 1e-4 || R.determinant() < 0.0 ||
      (M.row(3) - Eigen::RowVector4d(0, 0, 0, 1)).norm() > 1e-9)
    throw core::FileError(path, "not a rigid transform (the rotation must be orthonormal, the last row 0 0 0 1)");
  core::Pose3 X_depth_colour = core::Pose3::Identity();
  X_depth_colour.linear() = R;
  X_depth_colour.translation() = M.topRightCorner<3, 1>();
  return X_depth_colour;
}

std::optional<DepthCamera> findDepthCamera(const std::string& folder, const ImportOptions& options) {
  std::string path = options.depthCameraPath;
  const fs::path xml = fs::path(folder) / "camera.xml";
  std::optional<rawlog::DepthRegistration::Camera> camera;
  if (path.empty())
    for (const char* name : {"depth_camera.xml", "depth_cam.json", "depth_intrinsics.json"})
      if (fs::is_regular_file(fs::path(folder) / name)) {
        path = (fs::path(folder) / name).string();
        break;
      }
  if (!path.empty()) {
    camera = toRegistrationCamera(path);
  } else if (options.cameraPath.empty() && xmlHasCamera(xml, "depth_camera")) {
    const CameraCalibration c = loadCameraXml(xml.string(), "depth_camera");
    camera = rawlog::DepthRegistration::Camera{c.intrinsics, rawlog::LensDistortion{c.kud, 0, 0, 0, 0}};
  }
  if (!camera) return std::nullopt;
  DepthCamera out;
  out.camera = *camera;
  std::string extrinsic = options.depthToColourPath;
  if (extrinsic.empty() && fs::is_regular_file(fs::path(folder) / "depth_M_color.txt"))
    extrinsic = (fs::path(folder) / "depth_M_color.txt").string();
  if (!extrinsic.empty()) out.X_colour_depth = readDepthMColour(extrinsic).inverse();
  return out;
}

// What a depth image of another size than colour needs.
const char* const kOwnDepthCameraHint =
    ": depth registered to colour must have its size; depth from its own camera needs that camera's file "
    "(depth_cam.json or --depth-intrinsics) and depth_M_color.txt";

// The size the file declares, checked against its camera before any decoding.
void checkDeclaredSize(const std::string& path, const core::CameraIntrinsics& K, const std::string& camera,
                       const std::string& hint = "") {
  const auto size = detail::imageSizeFromHeader(path);
  if (!size) throw core::FileError(path, "not a PNG or JPEG image (its header cannot be read)");
  if (size->width != K.width_px || size->height != K.height_px)
    throw core::FileError(path, "image is " + std::to_string(size->width) + "x" + std::to_string(size->height) +
                                    " (by its header) but the " + camera + " file says " + std::to_string(K.width_px) +
                                    "x" + std::to_string(K.height_px) + "; nothing was decoded" + hint);
}

cv::Mat readColour(const std::string& path) {
  cv::Mat img = cv::imread(path, cv::IMREAD_UNCHANGED);
  if (img.empty()) throw core::FileError(path, "cannot read this colour image (missing, truncated or not PNG/JPG)");
  if (img.depth() != CV_8U)
    throw core::FileError(path, "colour image is " + typeName(img) + "; expected 8-bit colour or grey");
  if (img.channels() == 1) cv::cvtColor(img, img, cv::COLOR_GRAY2BGR);
  else if (img.channels() == 4) cv::cvtColor(img, img, cv::COLOR_BGRA2BGR);
  return img;
}

cv::Mat readDepth(const std::string& path, double scale_m) {
  cv::Mat raw = cv::imread(path, cv::IMREAD_UNCHANGED);
  if (raw.empty()) throw core::FileError(path, "cannot read this depth image (missing, truncated or not PNG)");
  if (raw.type() != CV_16UC1)
    throw core::FileError(path, "depth image is " + typeName(raw) +
                                    "; expected a 16-bit single-channel PNG (depth units x depth scale = metres)");
  cv::Mat depth(raw.size(), CV_32FC1);
  const float scale = static_cast<float>(scale_m);  // the rawlog stores float units: same product on both sides
  for (int r = 0; r < raw.rows; ++r) {
    const uint16_t* s = raw.ptr<uint16_t>(r);
    float* d = depth.ptr<float>(r);
    for (int c = 0; c < raw.cols; ++c) d[c] = static_cast<float>(s[c]) * scale;
  }
  return depth;
}

/// The median frame period's rate of increasing times, to 1e-6 Hz (0 for fewer than two).
double rateOf(const std::vector<double>& times_s) {
  std::vector<double> dt;
  for (std::size_t i = 1; i < times_s.size(); ++i) dt.push_back(times_s[i] - times_s[i - 1]);
  if (dt.empty()) return 0.0;
  std::nth_element(dt.begin(), dt.begin() + static_cast<std::ptrdiff_t>(dt.size() / 2), dt.end());
  if (!(dt[dt.size() / 2] > 0.0)) return 0.0;
  constexpr double kDigits = 1e6;  // 10 Hz, not 9.999999999999991 from times i / 10
  return std::round(kDigits / dt[dt.size() / 2]) / kDigits;
}

/// "3, 7, 12" (at most `shown`, then "and N more").
std::string listOf(const std::vector<int>& v, std::size_t shown = 10) {
  std::string out;
  for (std::size_t i = 0; i < v.size() && i < shown; ++i) out += (i ? ", " : "") + std::to_string(v[i]);
  if (v.size() > shown) out += " and " + std::to_string(v.size() - shown) + " more";
  return out;
}

/// Reads, checks and writes all pairs, into a temporary file renamed over the
/// rawlog at the end (a failure leaves the previous rawlog as it was).
ImportSummary writePairs(ImportSummary summary, const std::vector<double>& times_s, const CameraFile& camera,
                         const std::optional<DepthCamera>& depthCamera, const std::string& rawlogPath,
                         const ImportOptions& options) {
  const auto& K = camera.camera.intrinsics;
  summary.intrinsics = K;
  summary.depthIntrinsics = depthCamera ? depthCamera->camera.K : K;
  std::unique_ptr<rawlog::DepthRegistration> registration;
  if (depthCamera) {
    registration = std::make_unique<rawlog::DepthRegistration>(depthCamera->camera,
                                                               rawlog::DepthRegistration::Camera{K, {}},
                                                               depthCamera->X_colour_depth);
    summary.depthRegistered = true;
    summary.depthToColourBaseline_m = depthCamera->X_colour_depth.translation().norm();
  }
  if (camera.camera.hasDistortion())
    throw core::InvalidInputError("camera '" + camera.camera.name +
                                  "' has lens distortion; import expects undistorted (rectified) images and "
                                  "intrinsics without distortion");
  if (!(summary.depthScale_m > 0.0)) throw core::InvalidInputError("depth scale must be positive (metres per unit)");
  summary.fps = rateOf(times_s);
  core::AtomicOutputFile out(rawlogPath);
  rawlog::RawlogWriter writer(out.temporaryPath().string(), summary.depthScale_m);
  const int n = static_cast<int>(summary.colourFiles.size());
  for (int i = 0; i < n; ++i) {
    if (options.progress) options.progress(i, n);
    rawlog::RgbdFrame f;
    f.index = i;
    f.t_s = times_s[i];
    f.intrinsics = K;
    checkDeclaredSize(summary.colourFiles[i], K, "camera");
    checkDeclaredSize(summary.depthFiles[i], summary.depthIntrinsics, registration ? "depth camera" : "camera",
                      registration ? "" : kOwnDepthCameraHint);
    f.colour_bgr8 = readColour(summary.colourFiles[i]);
    f.depth_m = readDepth(summary.depthFiles[i], summary.depthScale_m);
    if (f.colour_bgr8.cols != K.width_px || f.colour_bgr8.rows != K.height_px)
      throw core::FileError(summary.colourFiles[i], "colour image is " + sizeName(f.colour_bgr8) +
                                                        " but the camera file says " + std::to_string(K.width_px) +
                                                        "x" + std::to_string(K.height_px));
    if (registration) {
      const auto& Kd = registration->depthCamera().K;
      if (f.depth_m.cols != Kd.width_px || f.depth_m.rows != Kd.height_px)
        throw core::FileError(summary.depthFiles[i], "depth image is " + sizeName(f.depth_m) +
                                                         " but the depth camera file says " +
                                                         std::to_string(Kd.width_px) + "x" + std::to_string(Kd.height_px));
      f.depth_m = registration->registerDepth(f.depth_m);
    } else if (f.depth_m.size() != f.colour_bgr8.size()) {
      throw core::FileError(summary.depthFiles[i], "depth image is " + sizeName(f.depth_m) + " but its colour image '" +
                                                       summary.colourFiles[i] + "' is " + sizeName(f.colour_bgr8) +
                                                       kOwnDepthCameraHint);
    }
    if (cv::countNonZero(f.depth_m > 0.0f) == 0) summary.framesWithoutDepth.push_back(i);
    writer.write(f);
  }
  writer.close();
  out.commit();
  summary.frames = n;
  if (!summary.framesWithoutDepth.empty())
    summary.warnings.push_back(std::to_string(summary.framesWithoutDepth.size()) + " of " + std::to_string(n) +
                               " frames have no valid depth (depth image all zero): frames " +
                               listOf(summary.framesWithoutDepth) + "; perception finds nothing in them");
  if (options.progress) options.progress(n, n);
  return summary;
}

bool isImage(const fs::path& p, bool depth) {
  const std::string ext = core::toLowerAscii(p.extension().string());
  return ext == ".png" || (!depth && (ext == ".jpg" || ext == ".jpeg"));
}

/// number -> file for files named <prefix>N in `dir` (prefix from `prefixes`,
/// optional '_' or '-'), or any N in the subfolders named like the prefixes.
std::map<long, std::string> numberedFiles(const fs::path& dir, const std::vector<std::string>& prefixes, bool depth) {
  std::map<long, std::string> files;
  std::string alternatives;
  for (const auto& p : prefixes) alternatives += (alternatives.empty() ? "" : "|") + p;
  const std::regex inFolder("^(?:" + alternatives + ")[_-]?(\\d+)$", std::regex::icase);
  const std::regex inSub("^(?:\\D*?)(\\d+)$");
  const auto add = [&](const fs::path& file, const std::regex& re) {
    std::smatch m;
    const std::string stem = file.stem().string();
    if (isImage(file, depth) && std::regex_match(stem, m, re)) {
      const long number = std::stol(m[1]);
      if (files.count(number))
        throw core::FileError(file.string(), "two images with number " + std::to_string(number) + " (also '" +
                                                 files[number] + "'); keep one");
      files[number] = file.string();
    }
  };
  for (const auto& e : fs::directory_iterator(dir))
    if (e.is_regular_file()) add(e.path(), inFolder);
  for (const auto& prefix : prefixes) {
    const fs::path sub = dir / prefix;
    if (fs::is_directory(sub))
      for (const auto& e : fs::directory_iterator(sub))
        if (e.is_regular_file()) add(e.path(), inSub);
  }
  return files;
}

struct TumEntry {
  double t_s;
  std::string path;
};

// Calls fn(line number, line) for every line of a text list that is neither blank nor a '#' comment.
template <typename Fn>
void forEachListLine(std::istream& in, Fn fn) {
  std::string line;
  int lineNo = 0;
  while (std::getline(in, line)) {
    ++lineNo;
    if (line.empty() || line[0] == '#' || line.find_first_not_of(" \t\r") == std::string::npos) continue;
    fn(lineNo, line);
  }
}

std::vector<TumEntry> readTumList(const fs::path& folder, const std::string& name) {
  const fs::path list = folder / name;
  std::ifstream in(list);
  if (!in) throw core::FileError(list.string(), "cannot open (a TUM RGB-D folder has rgb.txt and depth.txt)");
  std::vector<TumEntry> entries;
  forEachListLine(in, [&](int lineNo, const std::string& line) {
    std::istringstream ss(line);
    TumEntry e;
    if (!(ss >> e.t_s >> e.path))
      throw core::FileError(list.string(), "line " + std::to_string(lineNo) + " is not 'timestamp path': " + line);
    e.path = (folder / e.path).string();
    entries.push_back(e);
  });
  return entries;
}

}  // namespace

namespace {

// The rawlog must not be an input: the folder itself, any image or camera
// file the import reads (in the folder or given from elsewhere). A new file in
// the folder is fine; an existing rawlog is replaced.
void checkRawlogPath(const std::string& folder, const std::string& rawlogPath, const ImportOptions& o,
                     const std::vector<std::string>& images) {
  if (core::isSameFile(rawlogPath, folder))
    throw core::FileError(rawlogPath, "is the recording folder itself; give the rawlog a file name (e.g. demo.rawlog)");
  std::vector<core::PathRole> inputs;
  for (const auto& f : images) inputs.push_back({"an image of the recording", f});
  for (const char* name : {"camera.xml", "cam.json", "intrinsics.json", "depth_camera.xml", "depth_cam.json",
                           "depth_intrinsics.json", "depth_M_color.txt", "timestamps.txt", "rgb.txt", "depth.txt"})
    if (fs::exists(fs::path(folder) / name)) inputs.push_back({"the recording's " + std::string(name), fs::path(folder) / name});
  if (!o.cameraPath.empty()) inputs.push_back({"--intrinsics", o.cameraPath});
  if (!o.depthCameraPath.empty()) inputs.push_back({"--depth-intrinsics", o.depthCameraPath});
  if (!o.depthToColourPath.empty()) inputs.push_back({"--depth-M-color", o.depthToColourPath});
  core::checkOutputPaths({{"the rawlog to write", rawlogPath}}, inputs, /*overwrite=*/true);
}

/// timestamps.txt of an image folder: frame number -> time [s]; empty when absent.
std::map<long, double> folderTimestamps(const fs::path& folder) {
  std::map<long, double> times;
  const fs::path list = folder / "timestamps.txt";
  if (!fs::is_regular_file(list)) return times;
  std::ifstream in(list);
  forEachListLine(in, [&](int lineNo, const std::string& line) {
    std::istringstream ss(line);
    long number = 0;
    double t = 0.0;
    if (!(ss >> number >> t) || !std::isfinite(t))
      throw core::FileError(list.string(), "line " + std::to_string(lineNo) +
                                               " is not 'frame-number seconds' (e.g. '12 0.400'): " + line);
    times[number] = t;
  });
  return times;
}

}  // namespace

ImportSummary importImageFolder(const std::string& folder, const std::string& rawlogPath,
                                const ImportOptions& options) {
  if (!fs::is_directory(folder)) throw core::FileError(folder, "not a folder");
  const auto colour = numberedFiles(folder, {"color", "colour", "rgb"}, false);
  const auto depth = numberedFiles(folder, {"depth"}, true);
  if (colour.empty())
    throw core::FileError(folder, "no colour images (expected color_0000.png ... or rgb/0000.png with depth_0000.png)");
  const CameraFile camera = findCamera(folder, options);
  ImportSummary s;
  s.layout = "folder";
  s.depthScale_m = options.depthScale_m.value_or(camera.depthScale_m.value_or(0.001));
  const std::map<long, double> stamps = folderTimestamps(folder);
  const fs::path stampFile = fs::path(folder) / "timestamps.txt";
  const long first = colour.begin()->first;
  const double fps = options.fps.value_or(kAssumedFps);
  s.fpsSource = !stamps.empty() ? "timestamps" : options.fps ? "--fps" : "assumed";
  std::vector<double> times;
  long previous = first - 1;
  std::vector<std::string> gaps;
  for (const auto& [number, path] : colour) {
    const auto d = depth.find(number);
    if (d == depth.end())
      throw core::FileError(path, "no depth image with number " + std::to_string(number) +
                                      " (expected depth_" + std::to_string(number) + ".png, any zero padding)");
    if (number > previous + 1) {
      s.missingFrames += static_cast<int>(number - previous - 1);
      gaps.push_back(std::to_string(previous + 1) + (number - 1 > previous + 1 ? "-" + std::to_string(number - 1) : ""));
    }
    previous = number;
    s.colourFiles.push_back(path);
    s.depthFiles.push_back(d->second);
    if (stamps.empty()) {
      times.push_back(static_cast<double>(number - first) / fps);
    } else {
      const auto t = stamps.find(number);
      if (t == stamps.end())
        throw core::FileError(stampFile.string(), "has no time for frame " + std::to_string(number) + " ('" + path + "')");
      if (!times.empty() && !(t->second > times.back()))
        throw core::FileError(stampFile.string(), "the time of frame " + std::to_string(number) +
                                                      " is not after the previous frame's; times must increase");
      times.push_back(t->second);
    }
  }
  for (const auto& entry : depth)
    if (!colour.count(entry.first)) ++s.unpairedDepth;
  std::vector<std::string> images = s.colourFiles;
  images.insert(images.end(), s.depthFiles.begin(), s.depthFiles.end());
  checkRawlogPath(folder, rawlogPath, options, images);
  ImportSummary out = writePairs(s, times, camera, findDepthCamera(folder, options), rawlogPath, options);
  if (out.fpsSource == "assumed")
    out.warnings.insert(out.warnings.begin(),
                        "no timestamps in the folder and no --fps: ASSUMED " + std::to_string(kAssumedFps).substr(0, 4) +
                            " frames/s. If the camera ran at another rate, import again with --fps (grasp/release "
                            "times and learned speeds scale with it)");
  if (out.fpsSource == "timestamps" && options.fps && std::abs(*options.fps - out.fps) > 0.05 * out.fps)
    out.warnings.push_back("the folder's timestamps give " + std::to_string(out.fps) + " frames/s; --fps " +
                           std::to_string(*options.fps) + " was not used");
  if (!gaps.empty()) {
    std::string list;
    for (std::size_t i = 0; i < gaps.size() && i < 10; ++i) list += (i ? ", " : "") + gaps[i];
    if (gaps.size() > 10) list += " and " + std::to_string(gaps.size() - 10) + " more";
    out.warnings.push_back(std::to_string(out.missingFrames) + " frame numbers are missing (" + list +
                           "): the frames after each gap keep their time (t = number / fps or the folder's timestamps)");
  }
  return out;
}

ImportSummary importTum(const std::string& folder, const std::string& rawlogPath, const ImportOptions& options) {
  if (!fs::is_directory(folder)) throw core::FileError(folder, "not a folder");
  const auto rgb = readTumList(folder, "rgb.txt");
  const auto depth = readTumList(folder, "depth.txt");
  if (rgb.empty()) throw core::FileError((fs::path(folder) / "rgb.txt").string(), "lists no images");
  // associate.py: all pairs within the window, closest first, each image once.
  struct Candidate {
    double diff;
    size_t rgb, depth;
  };
  std::vector<Candidate> candidates;
  for (size_t i = 0; i < rgb.size(); ++i)
    for (size_t j = 0; j < depth.size(); ++j) {
      const double diff = std::abs(rgb[i].t_s - depth[j].t_s);
      if (diff < options.maxTimeDifference_s) candidates.push_back({diff, i, j});
    }
  std::sort(candidates.begin(), candidates.end(), [](const auto& a, const auto& b) {
    return a.diff < b.diff || (a.diff == b.diff && a.rgb < b.rgb);
  });
  std::vector<long> depthOf(rgb.size(), -1);
  std::vector<bool> depthUsed(depth.size(), false);
  for (const auto& c : candidates)
    if (depthOf[c.rgb] < 0 && !depthUsed[c.depth]) {
      depthOf[c.rgb] = static_cast<long>(c.depth);
      depthUsed[c.depth] = true;
    }
  ImportSummary s;
  s.layout = "tum";
  const CameraFile camera = findCamera(folder, options);
  s.depthScale_m = options.depthScale_m.value_or(camera.depthScale_m.value_or(1.0 / 5000.0));
  std::vector<double> times;
  for (size_t i = 0; i < rgb.size(); ++i)
    if (depthOf[i] >= 0) {
      s.colourFiles.push_back(rgb[i].path);
      s.depthFiles.push_back(depth[depthOf[i]].path);
      times.push_back(rgb[i].t_s);
    }
  if (s.colourFiles.empty())
    throw core::FileError(folder, "no colour/depth pair within " + std::to_string(options.maxTimeDifference_s) +
                                      " s of each other in rgb.txt and depth.txt");
  s.unpairedDepth = static_cast<int>(depth.size() - s.depthFiles.size());
  s.fpsSource = "timestamps";
  std::vector<std::string> images = s.colourFiles;
  images.insert(images.end(), s.depthFiles.begin(), s.depthFiles.end());
  checkRawlogPath(folder, rawlogPath, options, images);
  return writePairs(s, times, camera, findDepthCamera(folder, options), rawlogPath, options);
}

ImportSummary importRecording(const std::string& folder, const std::string& rawlogPath, const ImportOptions& options) {
  if (fs::is_regular_file(fs::path(folder) / "rgb.txt")) return importTum(folder, rawlogPath, options);
  return importImageFolder(folder, rawlogPath, options);
}

}  // namespace srp::calib
