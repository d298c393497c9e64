#include "srp/calib/CameraFiles.h"

#include <gtest/gtest.h>

#include <filesystem>
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
