#include "srp/calib/IntrinsicCalibrator.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <regex>

#include "OpenCvPose.h"
#include "srp/core/Error.h"

namespace srp::calib {

namespace fs = std::filesystem;

int IntrinsicCalibrationResult::viewsUsed() const {
  return static_cast<int>(std::count_if(views.begin(), views.end(), [](const auto& v) { return v.found; }));
}

std::vector<std::string> IntrinsicCalibrationResult::rejectedNames() const {
  std::vector<std::string> names;
  for (const auto& v : views)
    if (!v.found) names.push_back(v.name);
  return names;
}

std::vector<std::string> IntrinsicCalibrationResult::outlierNames() const {
  std::vector<std::string> names;
  for (const auto& v : views)
    if (v.outlier) names.push_back(v.name);
  return names;
}

namespace {

/// Sets medianViewRms_px and flags the views at kOutlierViewFactor x the median or more.
void flagOutlierViews(IntrinsicCalibrationResult& result) {
  std::vector<double> rms;
  for (const auto& v : result.views)
    if (v.found) rms.push_back(v.rms_px);
  if (rms.empty()) return;
  const auto mid = rms.begin() + static_cast<std::ptrdiff_t>(rms.size() / 2);
  std::nth_element(rms.begin(), mid, rms.end());
  double median = *mid;
  if (rms.size() % 2 == 0) median = 0.5 * (median + *std::max_element(rms.begin(), mid));
  result.medianViewRms_px = median;
  for (auto& v : result.views) v.outlier = v.found && median > 0.0 && v.rms_px >= kOutlierViewFactor * median;
}

std::string joinNames(const std::vector<std::string>& names) {
  std::string s;
  for (const auto& n : names) s += (s.empty() ? "" : ", ") + n;
  return s;
}

}  // namespace

IntrinsicCalibrationResult calibrateIntrinsics(const std::vector<cv::Mat>& images,
                                               const std::vector<std::string>& names,
                                               const CalibrationPattern& pattern,
                                               const IntrinsicCalibrationOptions& options) {
  core::require(images.size() == names.size(), "calibrateIntrinsics: one name per image");
  if (images.empty()) throw core::InvalidInputError("calibration: no images given");
  IntrinsicCalibrationResult result;
  const cv::Size size = images.front().size();
  std::vector<std::vector<cv::Point2f>> imagePoints;
  std::vector<std::vector<cv::Point3f>> objectPoints;
  std::vector<size_t> usedIndex;
  if (!options.drawDir.empty()) fs::create_directories(options.drawDir);
  for (size_t i = 0; i < images.size(); ++i) {
    if (options.progress) options.progress(static_cast<int>(i), static_cast<int>(images.size()), names[i]);
    const cv::Mat& img = images[i];
    if (img.empty()) throw core::InvalidInputError("calibration image '" + names[i] + "' is empty");
    if (img.size() != size)
      throw core::InvalidInputError("calibration image '" + names[i] + "' is " + std::to_string(img.cols) + "x" +
                                    std::to_string(img.rows) + " but '" + names.front() + "' is " +
                                    std::to_string(size.width) + "x" + std::to_string(size.height) +
                                    " (all images must come from the same camera mode)");
    cv::Mat grey;
    if (img.channels() == 3) cv::cvtColor(img, grey, cv::COLOR_BGR2GRAY);
    else if (img.channels() == 4) cv::cvtColor(img, grey, cv::COLOR_BGRA2GRAY);
    else grey = img;
    if (grey.depth() != CV_8U) grey.convertTo(grey, CV_8U, grey.depth() == CV_16U ? 1.0 / 256.0 : 1.0);
    CalibrationView view;
    view.name = names[i];
    if (auto obs = pattern.detect(grey)) {
      view.found = true;
      view.points = static_cast<int>(obs->imagePoints_px.size());
      imagePoints.push_back(obs->imagePoints_px);
      objectPoints.push_back(obs->objectPoints_m);
      view.observation = std::move(*obs);
      usedIndex.push_back(i);
    }
    result.views.push_back(std::move(view));
  }
  if (imagePoints.size() < 3)
    throw core::InvalidInputError("calibration: the pattern '" + pattern.spec() + "' was found in only " +
                                  std::to_string(imagePoints.size()) + " of " + std::to_string(images.size()) +
                                  " images (need at least 3); not found in: " + joinNames(result.rejectedNames()));

  // ViSP's model: one radial coefficient (kud = k1), no tangential terms.
  int flags = cv::CALIB_FIX_K2 | cv::CALIB_FIX_K3 | cv::CALIB_ZERO_TANGENT_DIST;
  if (!options.estimateDistortion) flags |= cv::CALIB_FIX_K1;
  cv::Mat K = cv::Mat::eye(3, 3, CV_64F), dist = cv::Mat::zeros(5, 1, CV_64F);
  std::vector<cv::Mat> rvecs, tvecs;
  cv::calibrateCamera(objectPoints, imagePoints, size, K, dist, rvecs, tvecs, flags,
                      cv::TermCriteria(cv::TermCriteria::COUNT + cv::TermCriteria::EPS, 100, 1e-12));

  CameraCalibration& cam = result.camera;
  cam.name = options.cameraName;
  cam.intrinsics = {K.at<double>(0, 0), K.at<double>(1, 1), K.at<double>(0, 2), K.at<double>(1, 2), size.width,
                    size.height};
  cam.kud = options.estimateDistortion ? dist.at<double>(0) : 0.0;
  cam.kdu = CameraCalibration::fitKdu(cam.intrinsics, cam.kud);

  double sumSq = 0.0;
  size_t count = 0;
  for (size_t k = 0; k < usedIndex.size(); ++k) {
    std::vector<cv::Point2f> projected;
    cv::projectPoints(objectPoints[k], rvecs[k], tvecs[k], K, dist, projected);
    double viewSq = 0.0;
    for (size_t p = 0; p < projected.size(); ++p) {
      const cv::Point2f d = projected[p] - imagePoints[k][p];
      viewSq += d.dot(d);
    }
    CalibrationView& view = result.views[usedIndex[k]];
    view.rms_px = std::sqrt(viewSq / projected.size());
    view.X_camera_board = detail::poseFromRvecTvec(rvecs[k], tvecs[k]);
    sumSq += viewSq;
    count += projected.size();
  }
  result.rms_px = std::sqrt(sumSq / count);
  flagOutlierViews(result);

  if (!options.drawDir.empty()) {
    for (size_t i = 0; i < images.size(); ++i) {
      cv::Mat bgr;
      if (images[i].channels() == 1) cv::cvtColor(images[i], bgr, cv::COLOR_GRAY2BGR);
      else if (images[i].channels() == 4) cv::cvtColor(images[i], bgr, cv::COLOR_BGRA2BGR);
      else bgr = images[i].clone();
      if (bgr.depth() != CV_8U) bgr.convertTo(bgr, CV_8U, 1.0 / 256.0);
      const auto& view = result.views[i];
      char text[160];
      if (view.found) {
        pattern.draw(bgr, view.observation);
        std::snprintf(text, sizeof text, "%d points, RMS %.3f px", view.points, view.rms_px);
      } else {
        std::snprintf(text, sizeof text, "pattern not found");
      }
      cv::putText(bgr, text, cv::Point(10, 25), cv::FONT_HERSHEY_SIMPLEX, 0.7,
                  view.found ? cv::Scalar(0, 200, 0) : cv::Scalar(0, 0, 255), 2, cv::LINE_AA);
      const std::string out = (fs::path(options.drawDir) / (fs::path(view.name).stem().string() + ".png")).string();
      if (!cv::imwrite(out, bgr)) throw core::FileError(out, "cannot write the drawn detection");
    }
  }
  return result;
}

IntrinsicCalibrationResult calibrateIntrinsicsFromFiles(const std::vector<std::string>& paths,
                                                        const CalibrationPattern& pattern,
                                                        const IntrinsicCalibrationOptions& options) {
  if (paths.empty()) throw core::InvalidInputError("calibration: no image files given");
  std::vector<cv::Mat> images;
  for (const auto& p : paths) checkImageFile(p, options.maxImagePixels);  // all of them, before any is decoded
  for (const auto& p : paths) {
    cv::Mat img = cv::imread(p, cv::IMREAD_UNCHANGED);
    if (img.empty()) throw core::FileError(p, "cannot read this image (missing, or not an image OpenCV can decode)");
    images.push_back(img);
  }
  return calibrateIntrinsics(images, paths, pattern, options);
}

std::vector<std::string> expandImageGlob(const std::string& pattern) {
  const fs::path p(pattern);
  const std::string name = p.filename().string();
  if (name.find_first_of("*?[") == std::string::npos) {
    if (!fs::is_regular_file(p)) throw core::FileError(pattern, "no such image file");
    return {pattern};
  }
  std::string re;
  bool inClass = false;  // inside [...]: passed through as a regex class ([!..] -> [^..])
  for (size_t i = 0; i < name.size(); ++i) {
    const char c = name[i];
    if (inClass) {
      if (c == ']') inClass = false;
      if (c == '\\') re += '\\';
      re += c;
    } else if (c == '[' && name.find(']', i + 1) != std::string::npos) {
      inClass = true;
      re += '[';
      if (i + 1 < name.size() && name[i + 1] == '!') {
        re += '^';
        ++i;
      }
    } else if (c == '*') {
      re += ".*";
    } else if (c == '?') {
      re += '.';
    } else if (std::string("\\^$.|+()[]{}").find(c) != std::string::npos) {
      re += std::string("\\") + c;
    } else {
      re += c;
    }
  }
  const std::regex fileRe(re);
  const fs::path dir = p.has_parent_path() ? p.parent_path() : fs::path(".");
  std::vector<std::string> files;
  if (fs::is_directory(dir))
    for (const auto& e : fs::directory_iterator(dir))
      if (e.is_regular_file() && std::regex_match(e.path().filename().string(), fileRe))
        files.push_back(e.path().string());
  std::sort(files.begin(), files.end());
  if (files.empty())
    throw core::FileError(pattern, "no image matches this pattern (quote it so the shell does not expand it)");
  return files;
}

}  // namespace srp::calib
