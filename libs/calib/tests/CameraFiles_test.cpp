#include "srp/calib/CameraFiles.h"
#include "srp/calib/CameraYaml.h"

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <opencv2/core/persistence.hpp>
#include <fstream>

#include "ExpectError.h"
#include "srp/core/Error.h"
#include "srp/core/Scene.h"

using namespace srp::calib;
namespace fs = std::filesystem;

namespace {
std::string tempPath(const std::string& name) { return (fs::temp_directory_path() / ("srp_calib_" + name)).string(); }
}  // namespace

TEST(CameraFiles, XmlRoundTripsExactlyWithAndWithoutDistortion) {
  CameraCalibration c;
  c.name = "test_cam";
  c.intrinsics = {536.98412345678901, 537.42123456789, 344.11134567, 235.17412345, 640, 480};
  c.kud = -0.267281234567891;
  c.kdu = 0.30812123456789;
  const std::string path = tempPath("roundtrip.xml");
  saveCameraXml(path, c, "unit test");
  EXPECT_EQ(loadCameraXml(path), c);
  EXPECT_EQ(loadCameraXml(path, "test_cam"), c);
  saveCameraXml(path, c);  // replaces, does not append a second camera
  EXPECT_EQ(cameraNamesInXml(path).size(), 1u);

  c.kud = c.kdu = 0.0;
  saveCameraXml(path, c);
  const auto back = loadCameraXml(path);
  EXPECT_EQ(back, c);
  EXPECT_FALSE(back.hasDistortion());
}

TEST(CameraFiles, ReadsVispRgbdRecordingFiles) {
  const std::string folder = std::string(SRP_DATASETS_DIR) + "/real/visp-rbt-cube/";
  constexpr double kPx = 607.178466796875, kPy = 607.2342529296875, kU0 = 321.39129638671875, kV0 = 241.91822814941406;
  const auto xmlNames = cameraNamesInXml(folder + "camera.xml");
  ASSERT_EQ(xmlNames.size(), 3u);
  const auto colour = loadCameraXml(folder + "camera.xml");
  EXPECT_EQ(colour.name, "color_camera");
  EXPECT_EQ(colour.intrinsics, (srp::core::CameraIntrinsics{kPx, kPy, kU0, kV0, 640, 480}));
  EXPECT_NE(loadCameraXml(folder + "camera.xml", "infrared_camera").intrinsics.fx_px, kPx);
  const auto json = loadCameraFile(folder + "cam.json");
  EXPECT_EQ(json.camera.intrinsics, colour.intrinsics);
  ASSERT_TRUE(json.depthScale_m.has_value());
  EXPECT_DOUBLE_EQ(*json.depthScale_m, 0.001);
}

TEST(CameraFiles, DefaultCalibrationMatchesTheDefaultSyntheticScene) {
  // calib/camera.xml is the calibration of the synthetic camera of
  // sim/scenes/default.json; keep the two in step.
  const auto scene = srp::core::Scene::load(std::string(SRP_SIM_DIR) + "/scenes/default.json");
  const auto cam = loadCameraXml(std::string(SRP_SOURCE_DIR) + "/calib/camera.xml");
  EXPECT_EQ(cam.intrinsics, scene.intrinsics);
  EXPECT_FALSE(cam.hasDistortion());
}

TEST(CameraFiles, BadFilesAreNamed) {
  const std::string missing = tempPath("missing.xml");
  fs::remove(missing);
  test::expectErrorNaming<srp::core::FileError>([&] { loadCameraXml(missing); }, missing);
  const std::string folder = std::string(SRP_DATASETS_DIR) + "/real/visp-rbt-cube/";
  // The error lists the cameras the file has.
  test::expectErrorNaming<srp::core::FileError>([&] { loadCameraXml(folder + "camera.xml", "no_such_camera"); },
                                                "color_camera");
  const std::string bad = tempPath("bad.json");
  { std::ofstream(bad) << R"({"px": 500, "py": 500, "u0": 320})"; }
  test::expectErrorNaming<srp::core::InvalidInputError>([&] { loadCameraFile(bad); }, "v0");
}

// ROS camera_info and OpenCV YAML hold the same camera as the ViSP XML: K and kud
// read back exactly (kdu is refitted to kud, as the calibrator makes it), and each
// file reads as its own ecosystem reads it (yaml-cpp for ROS, cv::FileStorage for OpenCV).
TEST(CameraFiles, RosAndOpenCvYamlRoundTripExactly) {
  CameraCalibration c;
  c.name = "test_cam";
  c.intrinsics = {536.98412345678901, 537.42123456789, 344.11134567, 235.17412345, 640, 480};
  c.kud = -0.267281234567891;
  c.kdu = CameraCalibration::fitKdu(c.intrinsics, c.kud);
  for (const auto format : {CameraFileFormat::Ros, CameraFileFormat::OpenCv}) {
    const std::string path = tempPath(format == CameraFileFormat::Ros ? "roundtrip_ros.yaml" : "roundtrip_cv.yaml");
    saveCameraFile(path, c, format, "unit test", 0.42);
    EXPECT_EQ(loadCameraFile(path).camera, c) << path;
  }

  const YAML::Node ros = YAML::LoadFile(tempPath("roundtrip_ros.yaml"));
  EXPECT_EQ(ros["image_width"].as<int>(), 640);
  EXPECT_EQ(ros["camera_name"].as<std::string>(), "test_cam");
  EXPECT_EQ(ros["distortion_model"].as<std::string>(), "plumb_bob");
  EXPECT_EQ(ros["camera_matrix"]["data"].as<std::vector<double>>(),
            (std::vector<double>{c.intrinsics.fx_px, 0, c.intrinsics.cx_px, 0, c.intrinsics.fy_px, c.intrinsics.cy_px, 0, 0, 1}));
  EXPECT_EQ(ros["distortion_coefficients"]["data"].as<std::vector<double>>(), (std::vector<double>{c.kud, 0, 0, 0, 0}));
  const auto P = ros["projection_matrix"]["data"].as<std::vector<double>>();
  ASSERT_EQ(P.size(), 12u);
  EXPECT_EQ(P[3], 0.0);
  EXPECT_EQ(P[7], 0.0);
  EXPECT_EQ(P[11], 0.0);
  EXPECT_EQ(P[10], 1.0);

  cv::FileStorage fs(tempPath("roundtrip_cv.yaml"), cv::FileStorage::READ);
  cv::Mat K, D;
  fs["camera_matrix"] >> K;
  fs["distortion_coefficients"] >> D;
  EXPECT_EQ(K.at<double>(0, 0), c.intrinsics.fx_px);
  EXPECT_EQ(K.at<double>(1, 2), c.intrinsics.cy_px);
  EXPECT_EQ(D.at<double>(0), c.kud);
  EXPECT_EQ(static_cast<double>(fs["avg_reprojection_error"]), 0.42);
}

// Without distortion the rectified projection is the camera matrix itself.
TEST(CameraFiles, RosProjectionOfAnUndistortedCameraIsK) {
  CameraCalibration c;
  c.intrinsics = {600.0, 605.0, 322.5, 236.0, 640, 480};
  const YAML::Node ros = YAML::Load(cameraInfoYaml(c));
  const auto P = ros["projection_matrix"]["data"].as<std::vector<double>>();
  constexpr double kProjectionTol_px = 1e-9;
  const std::vector<double> expected{600.0, 0, 322.5, 0, 0, 605.0, 236.0, 0, 0, 0, 1, 0};
  for (std::size_t i = 0; i < expected.size(); ++i) EXPECT_NEAR(P[i], expected[i], kProjectionTol_px) << i;
}

// Distortion srp does not model (k2, tangential) is refused, naming the coefficient.
TEST(CameraFiles, YamlWithUnmodelledDistortionIsRefused) {
  const std::string path = tempPath("k2.yaml");
  std::ofstream(path) << "image_width: 640\nimage_height: 480\ncamera_name: c\n"
                         "camera_matrix: {rows: 3, cols: 3, data: [500, 0, 320, 0, 500, 240, 0, 0, 1]}\n"
                         "distortion_model: plumb_bob\n"
                         "distortion_coefficients: {rows: 1, cols: 5, data: [-0.2, 0.05, 0, 0, 0]}\n";
  test::expectErrorNaming<srp::core::FileError>([&] { loadCameraFile(path); }, "distortion coefficient 1 is 0.05");
  std::ofstream(path) << "image_width: 640\nimage_height: 480\n";
  test::expectErrorNaming<srp::core::FileError>([&] { loadCameraFile(path); }, "missing field 'camera_matrix'");
}
