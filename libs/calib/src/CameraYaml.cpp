// The YAML camera files (CameraYaml.h): ROS camera_info (yaml-cpp) and OpenCV FileStorage YAML.
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <fstream>
#include <opencv2/calib3d.hpp>
#include <opencv2/core/persistence.hpp>

#include "srp/calib/CameraYaml.h"
#include "srp/core/Error.h"
#include "srp/core/OutputFile.h"

namespace srp::calib {
namespace {

/// Distortion coefficients beyond k1 that srp's one-coefficient model treats as zero.
constexpr double kUnmodelledDistortionTol = 1e-12;

cv::Mat cameraMatrix(const core::CameraIntrinsics& K) {
  return (cv::Mat_<double>(3, 3) << K.fx_px, 0.0, K.cx_px, 0.0, K.fy_px, K.cy_px, 0.0, 0.0, 1.0);
}

cv::Mat plumbBob(double kud) { return (cv::Mat_<double>(1, 5) << kud, 0.0, 0.0, 0.0, 0.0); }

/// A camera from K (3x3, row-major), D (plumb_bob order) and the image size; refuses
/// distortion srp cannot model.
CameraCalibration fromMatrices(const std::vector<double>& K, const std::vector<double>& D, int width, int height,
                               const std::string& name, const std::string& path) {
  if (K.size() != 9) throw core::FileError(path, "camera_matrix must hold 9 numbers (3x3, row-major)");
  for (std::size_t i = 1; i < D.size(); ++i)
    if (std::abs(D[i]) > kUnmodelledDistortionTol)
      throw core::FileError(path, "distortion coefficient " + std::to_string(i) + " is " + std::to_string(D[i]) +
                                      ": srp models one radial coefficient (k1, ViSP's kud); calibrate with "
                                      "'srp calibrate' or give a rectified camera");
  CameraCalibration c;
  c.name = name.empty() ? c.name : name;
  c.intrinsics = {K[0], K[4], K[2], K[5], width, height};
  c.intrinsics.validate("camera file '" + path + "'");
  c.kud = D.empty() ? 0.0 : D[0];
  c.kdu = CameraCalibration::fitKdu(c.intrinsics, c.kud);
  return c;
}

void emitMatrix(YAML::Emitter& out, const char* key, int rows, int cols, const std::vector<double>& data) {
  out << YAML::Key << key << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "rows" << YAML::Value << rows << YAML::Key << "cols" << YAML::Value << cols;
  out << YAML::Key << "data" << YAML::Value << YAML::Flow << data << YAML::EndMap;
}

std::vector<double> values(const cv::Mat& m) {
  cv::Mat d;
  m.convertTo(d, CV_64F);
  return std::vector<double>(d.begin<double>(), d.end<double>());
}

}  // namespace

std::string openCvYaml(const CameraCalibration& camera, const std::string& comment, double rms_px) {
  cv::FileStorage fs(".yaml", cv::FileStorage::WRITE | cv::FileStorage::MEMORY);
  if (!comment.empty()) fs.writeComment(comment);
  fs << "image_width" << camera.intrinsics.width_px << "image_height" << camera.intrinsics.height_px;
  fs << "camera_name" << camera.name;
  fs << "camera_matrix" << cameraMatrix(camera.intrinsics);
  fs << "distortion_coefficients" << plumbBob(camera.kud);
  if (rms_px > 0.0) fs << "avg_reprojection_error" << rms_px;
  return fs.releaseAndGetString();
}

std::string cameraInfoYaml(const CameraCalibration& camera) {
  const auto& K = camera.intrinsics;
  const cv::Mat k = cameraMatrix(K), d = plumbBob(camera.kud);
  // Without distortion the image is its own rectification (getOptimalNewCameraMatrix would
  // shrink K by about a pixel, from its sampled image border).
  const cv::Mat rectified =
      camera.kud == 0.0 ? k : cv::getOptimalNewCameraMatrix(k, d, cv::Size(K.width_px, K.height_px), 0.0);
  std::vector<double> P = values(rectified);
  P.insert(P.begin() + 3, 0.0);
  P.insert(P.begin() + 7, 0.0);
  P.push_back(0.0);
  YAML::Emitter out;
  out.SetDoublePrecision(17);
  out << YAML::BeginMap;
  out << YAML::Key << "image_width" << YAML::Value << K.width_px;
  out << YAML::Key << "image_height" << YAML::Value << K.height_px;
  out << YAML::Key << "camera_name" << YAML::Value << camera.name;
  emitMatrix(out, "camera_matrix", 3, 3, values(k));
  out << YAML::Key << "distortion_model" << YAML::Value << "plumb_bob";
  emitMatrix(out, "distortion_coefficients", 1, 5, values(d));
  emitMatrix(out, "rectification_matrix", 3, 3, {1, 0, 0, 0, 1, 0, 0, 0, 1});
  emitMatrix(out, "projection_matrix", 3, 4, P);
  out << YAML::EndMap;
  return std::string(out.c_str()) + "\n";
}

CameraCalibration loadCameraYaml(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw core::FileError(path, "cannot open camera YAML (does it exist? make one with 'srp calibrate')");
  std::string first;
  std::getline(in, first);
  if (first.rfind("%YAML:", 0) == 0) {  // OpenCV FileStorage
    cv::FileStorage fs;
    try {
      fs.open(path, cv::FileStorage::READ);
    } catch (const cv::Exception& e) {
      throw core::FileError(path, "not an OpenCV YAML file: " + e.msg);
    }
    cv::Mat K, D;
    fs["camera_matrix"] >> K;
    fs["distortion_coefficients"] >> D;
    if (K.empty()) throw core::FileError(path, "no camera_matrix (is it an OpenCV camera calibration file?)");
    std::string name;
    fs["camera_name"] >> name;
    return fromMatrices(values(K), D.empty() ? std::vector<double>{} : values(D), static_cast<int>(fs["image_width"]),
                        static_cast<int>(fs["image_height"]), name, path);
  }
  try {
    const YAML::Node root = YAML::LoadFile(path);
    const auto field = [&](const YAML::Node& node, const char* key) {
      if (!node[key]) throw core::FileError(path, std::string("missing field '") + key + "' (ROS camera_info YAML)");
      return node[key];
    };
    const std::string model = root["distortion_model"] ? root["distortion_model"].as<std::string>() : "plumb_bob";
    if (model != "plumb_bob")
      throw core::FileError(path, "distortion_model '" + model + "' is not supported (srp reads plumb_bob)");
    const auto K = field(field(root, "camera_matrix"), "data").as<std::vector<double>>();
    const auto D = root["distortion_coefficients"] ? field(root["distortion_coefficients"], "data").as<std::vector<double>>()
                                                   : std::vector<double>{};
    return fromMatrices(K, D, field(root, "image_width").as<int>(), field(root, "image_height").as<int>(),
                        root["camera_name"] ? root["camera_name"].as<std::string>() : "", path);
  } catch (const YAML::Exception& e) {
    throw core::FileError(path, std::string("bad camera_info YAML: ") + e.what());
  }
}

}  // namespace srp::calib
