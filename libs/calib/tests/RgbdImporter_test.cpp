#include "srp/calib/RgbdImporter.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>

#include "ExpectError.h"
#include "srp/calib/CameraFiles.h"
#include "srp/calib/RawlogReplay.h"
#include "srp/core/Error.h"
#include "srp/rawlog/LensDistortion.h"
#include "srp/rawlog/RawlogReader.h"

using namespace srp::calib;
namespace fs = std::filesystem;

namespace {

const std::string kCubeFolder = std::string(SRP_DATASETS_DIR) + "/real/visp-rbt-cube";

fs::path freshDir(const std::string& name) {
  const fs::path p = fs::temp_directory_path() / ("srp_calib_import_" + name);
  fs::remove_all(p);
  fs::create_directories(p);
  return p;
}

/// Expects `fn` to throw FileError whose message names `needle`.
template <typename Fn>
void expectFileErrorNaming(Fn fn, const std::string& needle) {
  test::expectErrorNaming<srp::core::FileError>(fn, needle);
}

void writeIntrinsicsJson(const fs::path& dir, int w, int h) {
  std::ofstream(dir / "intrinsics.json") << R"({"fx": 300, "fy": 301, "cx": )" << (w - 1) / 2.0 << R"(, "cy": )"
                                         << (h - 1) / 2.0 << R"(, "width": )" << w << R"(, "height": )" << h << "}";
}

}  // namespace

TEST(RgbdImporter, VispRbtCubeFolderImportsWithItsIntrinsicsAndDepthScale) {
  const std::string out = (fs::temp_directory_path() / "srp_calib_cube.rawlog").string();
  const auto s = importRecording(kCubeFolder, out);
  EXPECT_EQ(s.layout, "folder");
  EXPECT_EQ(s.frames, 50);
  EXPECT_DOUBLE_EQ(s.depthScale_m, 0.001) << "from cam.json's depthScale";
  const auto cam = loadCameraFile(kCubeFolder + "/cam.json").camera.intrinsics;
  const auto frames = srp::rawlog::RawlogReader::readAll(out);
  ASSERT_EQ(frames.size(), 50u);
  EXPECT_EQ(frames[3].intrinsics, cam);
  EXPECT_NEAR(frames[9].t_s - frames[0].t_s, 9.0 / 30.0, 1e-6);
  // Depth checked against the PNG: millimetres x 0.001 = metres, every pixel.
  const cv::Mat raw = cv::imread(kCubeFolder + "/depth_0004.png", cv::IMREAD_UNCHANGED);
  ASSERT_EQ(raw.type(), CV_16UC1);
  cv::Mat expected_m;
  raw.convertTo(expected_m, CV_32FC1, 0.001f);
  EXPECT_EQ(cv::norm(frames[4].depth_m, expected_m, cv::NORM_INF), 0.0);
  EXPECT_GT(cv::countNonZero(raw), raw.total() / 2) << "a real depth image, mostly valid";
  const auto replay = replayRawlog(out);
  EXPECT_EQ(replay.frames, 50);
  EXPECT_EQ(replay.intrinsics, cam);
  EXPECT_DOUBLE_EQ(static_cast<float>(replay.depthUnit_m), 0.001f);
  EXPECT_NEAR(replay.fps, 30.0, 1e-3);
}

TEST(RgbdImporter, ImportReplayExportRoundTripsPixelsAndDepthBitExactly) {
  const std::string out = (fs::temp_directory_path() / "srp_calib_roundtrip.rawlog").string();
  importImageFolder(kCubeFolder, out);
  const fs::path exported = freshDir("export");
  ReplayOptions options;
  options.exportDir = exported.string();
  const auto s = replayRawlog(out, options);
  ASSERT_EQ(s.frames, 50);
  EXPECT_EQ(s.depthClipped, 0);
  for (int i = 0; i < 50; ++i) {
    char name[32];
    std::snprintf(name, sizeof name, "_%04d.png", i);
    for (const char* kind : {"color", "depth"}) {
      const cv::Mat a = cv::imread(kCubeFolder + "/" + kind + name, cv::IMREAD_UNCHANGED);
      const cv::Mat b = cv::imread((exported / (std::string(kind) + name)).string(), cv::IMREAD_UNCHANGED);
      ASSERT_EQ(a.type(), b.type()) << kind << name;
      ASSERT_EQ(a.size(), b.size()) << kind << name;
      EXPECT_EQ(cv::norm(a, b, cv::NORM_INF), 0.0) << kind << name << " differs";
    }
  }
  // The export folder (with its cam.json) imports again to the same frames.
  const std::string again = (fs::temp_directory_path() / "srp_calib_roundtrip2.rawlog").string();
  const auto s2 = importImageFolder(exported.string(), again);
  EXPECT_EQ(s2.intrinsics, s.intrinsics);
  EXPECT_DOUBLE_EQ(s2.depthScale_m, 0.001);
  const auto f1 = srp::rawlog::RawlogReader::readAll(out), f2 = srp::rawlog::RawlogReader::readAll(again);
  ASSERT_EQ(f1.size(), f2.size());
  for (size_t i = 0; i < f1.size(); ++i) {
    EXPECT_EQ(cv::norm(f1[i].depth_m, f2[i].depth_m, cv::NORM_INF), 0.0);
    EXPECT_EQ(cv::norm(f1[i].colour_bgr8, f2[i].colour_bgr8, cv::NORM_INF), 0.0);
  }
}

TEST(RgbdImporter, TumLayoutAssociatesByTimestamp) {
  const fs::path dir = freshDir("tum");
  fs::create_directories(dir / "rgb");
  fs::create_directories(dir / "depth");
  constexpr int kW = 64, kH = 48;
  writeIntrinsicsJson(dir, kW, kH);
  std::ofstream rgbTxt(dir / "rgb.txt"), depthTxt(dir / "depth.txt");
  rgbTxt << "# color images\n# file: 'test'\n# timestamp filename\n";
  depthTxt << "# depth maps\n# timestamp filename\n";
  const double t0 = 1305031102.175304;
  for (int i = 0; i < 5; ++i) {
    const double tRgb = t0 + i / 30.0, tDepth = tRgb + 0.004 * (i % 2 ? 1 : -1);  // jitter, within 20 ms
    char rgbName[64], depthName[64];
    std::snprintf(rgbName, sizeof rgbName, "rgb/%.6f.png", tRgb);
    std::snprintf(depthName, sizeof depthName, "depth/%.6f.png", tDepth);
    cv::imwrite((dir / rgbName).string(), cv::Mat(kH, kW, CV_8UC3, cv::Scalar(10 * i, 20, 30)));
    cv::imwrite((dir / depthName).string(), cv::Mat(kH, kW, CV_16UC1, cv::Scalar(5000 + 100 * i)));  // (1 + 0.02 i) m
    rgbTxt << std::fixed << tRgb << " " << rgbName << "\n";
    depthTxt << std::fixed << tDepth << " " << depthName << "\n";
  }
  depthTxt << std::fixed << t0 + 10.0 << " depth/orphan.png\n";  // no colour near it: ignored
  rgbTxt.close();
  depthTxt.close();
  const std::string out = (dir / "tum.rawlog").string();
  const auto s = importRecording(dir.string(), out);
  EXPECT_EQ(s.layout, "tum");
  EXPECT_EQ(s.frames, 5);
  EXPECT_EQ(s.unpairedDepth, 1);
  EXPECT_DOUBLE_EQ(s.depthScale_m, 1.0 / 5000.0) << "TUM's factor 5000";
  const auto frames = srp::rawlog::RawlogReader::readAll(out);
  ASSERT_EQ(frames.size(), 5u);
  constexpr double kTimeTol_s = 1e-5;
  constexpr double kDepthTol_m = 1e-6;
  for (int i = 0; i < 5; ++i) {
    EXPECT_NEAR(frames[i].t_s, t0 + i / 30.0, kTimeTol_s) << "colour timestamp";
    EXPECT_NEAR(frames[i].depth_m.at<float>(10, 10), 1.0 + 0.02 * i, kDepthTol_m) << "paired with its own depth";
    EXPECT_EQ(frames[i].colour_bgr8.at<cv::Vec3b>(5, 5)[0], 10 * i);
  }
}

TEST(RgbdImporter, BadInputNamesTheFile) {
  constexpr int kW = 32, kH = 24;
  const std::string out = (fs::temp_directory_path() / "srp_calib_bad.rawlog").string();
  {  // no images at all
    const fs::path dir = freshDir("empty");
    writeIntrinsicsJson(dir, kW, kH);
    expectFileErrorNaming([&] { importImageFolder(dir.string(), out); }, dir.string());
  }
  {  // colour without depth
    const fs::path dir = freshDir("nodepth");
    writeIntrinsicsJson(dir, kW, kH);
    cv::imwrite((dir / "color_0000.png").string(), cv::Mat(kH, kW, CV_8UC3, cv::Scalar::all(0)));
    expectFileErrorNaming([&] { importImageFolder(dir.string(), out); }, "color_0000.png");
  }
  {  // depth of the wrong type (8-bit)
    const fs::path dir = freshDir("depth8");
    writeIntrinsicsJson(dir, kW, kH);
    cv::imwrite((dir / "color_0.png").string(), cv::Mat(kH, kW, CV_8UC3, cv::Scalar::all(0)));
    cv::imwrite((dir / "depth_0.png").string(), cv::Mat(kH, kW, CV_8UC1, cv::Scalar::all(9)));
    expectFileErrorNaming([&] { importImageFolder(dir.string(), out); }, "depth_0.png");
  }
  {  // mismatched sizes: depth smaller than colour
    const fs::path dir = freshDir("size");
    writeIntrinsicsJson(dir, kW, kH);
    cv::imwrite((dir / "color_1.png").string(), cv::Mat(kH, kW, CV_8UC3, cv::Scalar::all(0)));
    cv::imwrite((dir / "depth_1.png").string(), cv::Mat(kH / 2, kW / 2, CV_16UC1, cv::Scalar::all(9)));
    expectFileErrorNaming([&] { importImageFolder(dir.string(), out); }, "depth_1.png");
  }
  {  // colour size differs from the intrinsics
    const fs::path dir = freshDir("intr");
    writeIntrinsicsJson(dir, kW * 2, kH * 2);
    cv::imwrite((dir / "color_1.png").string(), cv::Mat(kH, kW, CV_8UC3, cv::Scalar::all(0)));
    cv::imwrite((dir / "depth_1.png").string(), cv::Mat(kH, kW, CV_16UC1, cv::Scalar::all(9)));
    expectFileErrorNaming([&] { importImageFolder(dir.string(), out); }, "color_1.png");
  }
  {  // unreadable colour image
    const fs::path dir = freshDir("junk");
    writeIntrinsicsJson(dir, kW, kH);
    std::ofstream(dir / "color_2.png") << "this is not a PNG";
    cv::imwrite((dir / "depth_2.png").string(), cv::Mat(kH, kW, CV_16UC1, cv::Scalar::all(9)));
    expectFileErrorNaming([&] { importImageFolder(dir.string(), out); }, "color_2.png");
  }
  {  // no camera file
    const fs::path dir = freshDir("nocam");
    cv::imwrite((dir / "color_0.png").string(), cv::Mat(kH, kW, CV_8UC3, cv::Scalar::all(0)));
    expectFileErrorNaming([&] { importImageFolder(dir.string(), out); }, "--intrinsics");
  }
}

// A recording as a RealSense stores it: 320x240 depth of its own camera (with
// lens distortion), 640x360 colour, ViSP's depth_M_color.txt. The import
// re-projects depth into the colour camera: colour-sized depth on the plane
// the depth camera saw, colour images unchanged, the colour intrinsics.
TEST(RgbdImporter, UnregisteredFolderIsRegisteredToColour) {
  constexpr double kDepthTol_m = 1.5e-3;  // millimetre PNGs, re-projected
  const fs::path dir = freshDir("unregistered");
  const srp::core::CameraIntrinsics Kd{285.0, 286.0, 160.2, 119.1, 320, 240}, Kc{460.0, 461.0, 321.0, 178.0, 640, 360};
  const srp::rawlog::LensDistortion distortion{0.03, -0.01, 0.0, 0.0, 0.0};
  std::ofstream(dir / "cam.json") << R"({"px": 460, "py": 461, "u0": 321, "v0": 178, "w": 640, "h": 360, "depthScale": 0.001})";
  std::ofstream(dir / "depth_cam.json")
      << R"({"fx": 285, "fy": 286, "cx": 160.2, "cy": 119.1, "width": 320, "height": 240, "distortion": {"k1": 0.03, "k2": -0.01}})";
  // The colour camera 20 mm to the right of the depth camera: p_depth = depth_M_color p_colour.
  std::ofstream(dir / "depth_M_color.txt") << "1 0 0 0.02\n0 1 0 0\n0 0 1 0\n0 0 0 1\n";
  // A plane Z = 0.6 + 0.3 y in the depth frame, seen through the distorted depth lens.
  const auto planeDepth = [](const Eigen::Vector2d& xy) { return 0.6 / (1.0 - 0.3 * xy.y()); };
  for (int i = 0; i < 2; ++i) {
    cv::Mat depth(240, 320, CV_16UC1);
    for (int r = 0; r < 240; ++r)
      for (int c = 0; c < 320; ++c) {
        const Eigen::Vector2d xy = distortion.undistort({(c - Kd.cx_px) / Kd.fx_px, (r - Kd.cy_px) / Kd.fy_px});
        depth.at<uint16_t>(r, c) = static_cast<uint16_t>(std::lround(1000.0 * planeDepth(xy)));
      }
    cv::imwrite((dir / ("depth_" + std::to_string(i) + ".png")).string(), depth);
    cv::imwrite((dir / ("color_" + std::to_string(i) + ".png")).string(),
                cv::Mat(360, 640, CV_8UC3, cv::Scalar(20 * i, 100, 200)));
  }
  const std::string rawlog = (dir / "out.rawlog").string();
  const ImportSummary s = importRecording(dir.string(), rawlog);
  EXPECT_TRUE(s.depthRegistered);
  EXPECT_EQ(s.intrinsics, Kc);
  EXPECT_EQ(s.depthIntrinsics, Kd);
  EXPECT_NEAR(s.depthToColourBaseline_m, 0.02, 1e-12);
  const auto frames = srp::rawlog::RawlogReader::readAll(rawlog);
  ASSERT_EQ(frames.size(), 2u);
  const auto& f = frames[1];
  EXPECT_EQ(f.intrinsics, Kc);
  EXPECT_EQ(cv::norm(f.colour_bgr8, cv::Mat(360, 640, CV_8UC3, cv::Scalar(20, 100, 200)), cv::NORM_INF), 0.0);
  int checked = 0;
  for (int v = 10; v < 350; v += 7)
    for (int u = 80; u < 560; u += 11) {  // the depth camera sees u in about [60, 590]
      const float z = f.depth_m.at<float>(v, u);
      ASSERT_GT(z, 0.f) << u << "," << v;
      const Eigen::Vector3d p_depth = Kc.backProject(u, v, z) + Eigen::Vector3d(0.02, 0.0, 0.0);
      EXPECT_NEAR(p_depth.z(), planeDepth(p_depth.head<2>() / p_depth.z()), kDepthTol_m) << u << "," << v;
      ++checked;
    }
  EXPECT_GT(checked, 1000);
  // Without the depth camera file the sizes disagree: the error says what to add.
  fs::remove(dir / "depth_cam.json");
  expectFileErrorNaming([&] { importRecording(dir.string(), rawlog); }, "depth_M_color.txt");
}

namespace {
// A small registered folder: frames with the given numbers, depth 1 m (0 for `noDepth`).
fs::path smallFolder(const std::string& name, const std::vector<int>& numbers, const std::vector<int>& noDepth = {}) {
  constexpr int kW = 32, kH = 24;
  const fs::path dir = freshDir(name);
  writeIntrinsicsJson(dir, kW, kH);
  for (int n : numbers) {
    char c[32], d[32];
    std::snprintf(c, sizeof c, "color_%04d.png", n);
    std::snprintf(d, sizeof d, "depth_%04d.png", n);
    const bool none = std::find(noDepth.begin(), noDepth.end(), n) != noDepth.end();
    cv::imwrite((dir / c).string(), cv::Mat(kH, kW, CV_8UC3, cv::Scalar(n, 20, 30)));
    cv::imwrite((dir / d).string(), cv::Mat(kH, kW, CV_16UC1, cv::Scalar(none ? 0 : 1000)));
  }
  return dir;
}
constexpr double kTimeTol_s = 1e-6;
}  // namespace

// The frame rate: from the folder's timestamps, else --fps, else assumed and said so.
TEST(RgbdImporter, FrameRateComesFromTimestampsOrFpsOrIsAssumedLoudly) {
  const fs::path dir = smallFolder("rate", {0, 1, 2, 3});
  const std::string out = (dir.parent_path() / "srp_calib_rate.rawlog").string();
  auto s = importImageFolder(dir.string(), out);
  EXPECT_EQ(s.fpsSource, "assumed");
  EXPECT_NEAR(s.fps, kAssumedFps, 1e-9);
  ASSERT_FALSE(s.warnings.empty());
  EXPECT_NE(s.warnings[0].find("ASSUMED 30"), std::string::npos) << s.warnings[0];
  ImportOptions tenHz;
  tenHz.fps = 10.0;
  s = importImageFolder(dir.string(), out, tenHz);
  EXPECT_EQ(s.fpsSource, "--fps");
  EXPECT_NEAR(s.fps, 10.0, 1e-9);
  EXPECT_TRUE(s.warnings.empty());
  std::ofstream(dir / "timestamps.txt") << "# frame seconds\n0 100.00\n1 100.08\n2 100.16\n3 100.24\n";
  s = importImageFolder(dir.string(), out);
  EXPECT_EQ(s.fpsSource, "timestamps");
  EXPECT_NEAR(s.fps, 12.5, 1e-6);
  const auto frames = srp::rawlog::RawlogReader::readAll(out);
  ASSERT_EQ(frames.size(), 4u);
  EXPECT_NEAR(frames[3].t_s - frames[0].t_s, 0.24, kTimeTol_s);
  std::ofstream(dir / "timestamps.txt") << "0 100.00\n1 100.08\n3 100.24\n";  // frame 2 has none
  expectFileErrorNaming([&] { importImageFolder(dir.string(), out); }, "timestamps.txt");
}

// Gaps in the frame numbers keep their time; frames without any depth are named.
TEST(RgbdImporter, GapsKeepTheirTimeAndFramesWithoutDepthAreWarnedAbout) {
  const fs::path dir = smallFolder("gaps", {10, 11, 14, 15, 20}, {15});
  const std::string out = (dir.parent_path() / "srp_calib_gaps.rawlog").string();
  ImportOptions o;
  o.fps = 10.0;
  const auto s = importImageFolder(dir.string(), out, o);
  EXPECT_EQ(s.frames, 5);
  EXPECT_EQ(s.missingFrames, 6);  // 12-13, 16-19
  EXPECT_EQ(s.framesWithoutDepth, std::vector<int>{3});
  const auto frames = srp::rawlog::RawlogReader::readAll(out);
  ASSERT_EQ(frames.size(), 5u);
  EXPECT_NEAR(frames[2].t_s - frames[0].t_s, 0.4, kTimeTol_s) << "number 14 is 0.4 s after number 10";
  EXPECT_NEAR(frames[4].t_s - frames[0].t_s, 1.0, kTimeTol_s);
  std::string all;
  for (const auto& w : s.warnings) all += w + "\n";
  EXPECT_NE(all.find("6 frame numbers are missing (12-13, 16-19)"), std::string::npos) << all;
  EXPECT_NE(all.find("1 of 5 frames have no valid depth"), std::string::npos) << all;
}

// A 2 kB PNG whose header claims 60000 x 60000 pixels (a 10 GB image) is
// refused by its header, before anything is decoded.
TEST(RgbdImporter, ImageSizeIsCheckedAgainstTheCameraBeforeDecoding) {
  const fs::path dir = smallFolder("bomb", {0, 1});
  std::vector<unsigned char> png;
  cv::imencode(".png", cv::Mat(24, 32, CV_8UC3, cv::Scalar::all(7)), png);
  const unsigned char huge[8] = {0x00, 0x00, 0xEA, 0x60, 0x00, 0x00, 0xEA, 0x60};  // IHDR width, height 60000
  std::copy(huge, huge + 8, png.begin() + 16);
  std::ofstream(dir / "color_0001.png", std::ios::binary).write(reinterpret_cast<const char*>(png.data()),
                                                                static_cast<std::streamsize>(png.size()));
  const std::string out = (dir.parent_path() / "srp_calib_bomb.rawlog").string();
  expectFileErrorNaming([&] { importImageFolder(dir.string(), out); }, "60000x60000 (by its header)");
}

// The rawlog is never an input, and a failed import leaves the previous rawlog as it was.
TEST(RgbdImporter, OutputIsNeverAnInputAndAFailedImportKeepsTheOldRawlog) {
  const fs::path dir = smallFolder("inputs", {0, 1, 2});
  const auto refused = [](auto fn, const std::string& needle) { test::expectErrorNaming<srp::core::Error>(fn, needle); };
  refused([&] { importImageFolder(dir.string(), (dir / "intrinsics.json").string()); }, "would destroy the input");
  refused([&] { importImageFolder(dir.string(), (dir / "color_0001.png").string()); }, "color_0001.png");
  refused([&] { importImageFolder(dir.string(), dir.string()); }, "is the recording folder itself");
  EXPECT_GT(fs::file_size(dir / "color_0001.png"), 0u);
  const std::string out = (dir.parent_path() / "srp_calib_keep.rawlog").string();
  importImageFolder(dir.string(), out);
  const auto before = fs::file_size(out);
  std::ofstream(dir / "color_0002.png") << "truncated";  // the last frame is damaged
  EXPECT_THROW(importImageFolder(dir.string(), out), srp::core::FileError);
  EXPECT_EQ(fs::file_size(out), before);
  EXPECT_EQ(srp::rawlog::RawlogReader::readAll(out).size(), 3u) << "the good rawlog is still whole";
}

// srp replay --export: a colour-mapped depth PNG beside the 16-bit one, black where there is no depth.
TEST(RawlogReplay, ExportWritesAColourMappedDepthBesideTheSixteenBitOne) {
  const fs::path dir = smallFolder("colourdepth", {0, 1}, {1});
  const std::string out = (dir.parent_path() / "srp_calib_colourdepth.rawlog").string();
  importImageFolder(dir.string(), out);
  const fs::path exported = freshDir("colourdepth_export");
  ReplayOptions options;
  options.exportDir = exported.string();
  const auto s = replayRawlog(out, options);
  EXPECT_NEAR(s.depthColourNear_m, 1.0, 1e-6);
  const cv::Mat viz = cv::imread((exported / "depth_color_0000.png").string(), cv::IMREAD_UNCHANGED);
  ASSERT_EQ(viz.type(), CV_8UC3);
  EXPECT_GT(cv::norm(viz.at<cv::Vec3b>(5, 5)), 0.0) << "depth: coloured";
  const cv::Mat none = cv::imread((exported / "depth_color_0001.png").string(), cv::IMREAD_UNCHANGED);
  ASSERT_EQ(none.type(), CV_8UC3);
  EXPECT_EQ(cv::countNonZero(none.reshape(1)), 0) << "no depth: black";
  EXPECT_EQ(cv::imread((exported / "depth_0000.png").string(), cv::IMREAD_UNCHANGED).type(), CV_16UC1);
  // The export still imports back: the colour-mapped images are not taken for depth.
  const auto again = importImageFolder(exported.string(), (dir.parent_path() / "srp_calib_again.rawlog").string());
  EXPECT_EQ(again.frames, 2);
}
