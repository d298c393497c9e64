#include "srp/calib/RawlogReplay.h"

#include <gtest/gtest.h>

#include <mrpt/io/CFileGZOutputStream.h>
#include <mrpt/obs/CObservation3DRangeScan.h>
#include <mrpt/serialization/CArchive.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

#include "ExpectError.h"
#include "srp/core/Error.h"
#include "srp/rawlog/RawlogWriter.h"

using namespace srp::calib;
namespace fs = std::filesystem;

namespace {

const srp::core::CameraIntrinsics kK{300.0, 300.0, 79.5, 59.5, 160, 120};
constexpr double kFps = 30.0;

/// A small synthetic recording with noisy (poorly compressible) colour.
std::string writeRecording(const std::string& name, int frames) {
  const std::string path = (fs::temp_directory_path() / ("srp_calib_replay_" + name)).string();
  srp::rawlog::RawlogWriter writer(path, 1e-3);
  for (int i = 0; i < frames; ++i) {
    srp::rawlog::RgbdFrame f;
    f.index = i;
    f.t_s = 1700000000.0 + i / kFps;
    f.intrinsics = kK;
    f.colour_bgr8 = cv::Mat(kK.height_px, kK.width_px, CV_8UC3);
    cv::RNG rng(i);
    rng.fill(f.colour_bgr8, cv::RNG::UNIFORM, cv::Scalar::all(0), cv::Scalar::all(256));
    f.depth_m = cv::Mat(kK.height_px, kK.width_px, CV_32FC1, cv::Scalar(0.5 + 0.01 * i));
    writer.write(f);
  }
  return path;
}

}  // namespace

TEST(RawlogReplay, SummaryExportAndVideo) {
  const auto path = writeRecording("ten.rawlog", 10);
  const fs::path dir = fs::temp_directory_path() / "srp_calib_replay_export";
  fs::remove_all(dir);
  ReplayOptions options;
  options.exportDir = dir.string();
  options.videoPath = (dir / "out.avi").string();
  int overlays = 0;
  options.overlay = [&](cv::Mat& img, const srp::rawlog::RgbdFrame&) {
    cv::circle(img, {10, 10}, 3, cv::Scalar(0, 0, 255), -1);
    ++overlays;
  };
  const auto s = replayRawlog(path, options);
  constexpr double kRateTol_fps = 1e-3;
  EXPECT_EQ(s.frames, 10);
  EXPECT_NEAR(s.duration_s, 9.0 / kFps, 1e-5);
  EXPECT_NEAR(s.fps, kFps, kRateTol_fps);
  EXPECT_EQ(s.intrinsics, kK);
  EXPECT_FALSE(s.damage.has_value());
  EXPECT_DOUBLE_EQ(s.validDepthFraction, 1.0);
  EXPECT_EQ(overlays, 10);
  const cv::Mat depth = cv::imread((dir / "depth_0009.png").string(), cv::IMREAD_UNCHANGED);
  ASSERT_EQ(depth.type(), CV_16UC1);
  EXPECT_EQ(depth.at<uint16_t>(0, 0), 590) << "0.59 m in millimetres (the rawlog's unit)";
  EXPECT_TRUE(fs::exists(dir / "color_0009.png"));
  EXPECT_TRUE(fs::exists(dir / "cam.json"));
  cv::VideoCapture video(options.videoPath);
  ASSERT_TRUE(video.isOpened());
  EXPECT_EQ(static_cast<int>(video.get(cv::CAP_PROP_FRAME_COUNT)), 10);
  EXPECT_NEAR(video.get(cv::CAP_PROP_FPS), kFps, 0.01);
  cv::Mat first;
  ASSERT_TRUE(video.read(first));
  EXPECT_EQ(first.size(), cv::Size(kK.width_px, kK.height_px));
  const auto j = s.toJson();
  EXPECT_EQ(j.at("frames").get<int>(), 10);
  EXPECT_TRUE(j.at("damage").is_null());
}

TEST(RawlogReplay, TruncatedRawlogReplaysTheFramesBeforeTheDamage) {
  const auto path = writeRecording("truncated.rawlog", 8);
  fs::resize_file(path, fs::file_size(path) * 6 / 10);
  const auto s = replayRawlog(path);
  EXPECT_GT(s.frames, 0);
  EXPECT_LT(s.frames, 8);
  ASSERT_TRUE(s.damage.has_value());
  EXPECT_NE(s.damage->find("after frame " + std::to_string(s.frames)), std::string::npos) << *s.damage;
  EXPECT_NE(s.toText().find("DAMAGED"), std::string::npos);
  std::cout << "  truncated at 60 %: " << s.frames << " frames, " << *s.damage << "\n";
}

TEST(RawlogReplay, MrptSampleRgbdRawlogReplaysAndExports) {
  const std::string sample = "/usr/share/mrpt/datasets/tests_rgbd.rawlog";
  if (!fs::exists(sample)) FAIL() << sample << " missing: install Debian's mrpt-common (scripts/install-deps.sh does)";
  const fs::path dir = fs::temp_directory_path() / "srp_calib_replay_mrpt";
  fs::remove_all(dir);
  ReplayOptions options;
  options.exportDir = dir.string();
  const auto s = replayRawlog(sample, options);
  EXPECT_EQ(s.frames, 1);
  EXPECT_EQ(s.intrinsics.width_px, 640);
  EXPECT_EQ(s.intrinsics.height_px, 480);
  // Its cameras sit 1.6 mm apart (MRPT's own flag says they differ): kept as recorded (rawlog README).
  EXPECT_EQ(s.depthAlignment(), "registered");
  EXPECT_NE(s.toText().find("registered as recorded"), std::string::npos);
  constexpr double kFocalTol_px = 0.01;
  EXPECT_NEAR(s.intrinsics.fx_px, 572.883, kFocalTol_px) << "the depth camera's focal length (datasets README)";
  EXPECT_GT(s.validDepthFraction, 0.5);
  const cv::Mat depth = cv::imread((dir / "depth_0000.png").string(), cv::IMREAD_UNCHANGED);
  const cv::Mat colour = cv::imread((dir / "color_0000.png").string(), cv::IMREAD_UNCHANGED);
  ASSERT_EQ(depth.type(), CV_16UC1);
  ASSERT_EQ(colour.type(), CV_8UC3);
  EXPECT_GT(cv::countNonZero(depth), 200000) << "most of the 273 225 valid points survive the export";
  std::cout << "  tests_rgbd.rawlog: " << s.toText();
}

TEST(RawlogReplay, MissingOrEmptyFilesAreNamed) {
  const std::string missing = (fs::temp_directory_path() / "srp_calib_no_such.rawlog").string();
  fs::remove(missing);
  test::expectErrorNaming<srp::core::FileError>([&] { replayRawlog(missing); }, missing);
  const auto path = writeRecording("cut.rawlog", 2);
  fs::resize_file(path, 40);  // not even one frame left
  test::expectErrorNaming<srp::core::FileError>([&] { replayRawlog(path); }, path);
}

// An MRPT rawlog whose depth camera (320x240) is not the colour camera
// (640x360, 25 mm away), as MRPT's grabbers write one: replay says so and
// reports the colour camera's intrinsics.
TEST(RawlogReplay, UnregisteredMrptRawlogIsReportedAsSuch) {
  const fs::path path = fs::temp_directory_path() / "srp_calib_replay_unregistered.rawlog";
  {
    mrpt::obs::CObservation3DRangeScan obs;
    obs.hasRangeImage = true;
    obs.range_is_depth = true;
    obs.rangeUnits = 0.001f;
    obs.rangeImage_setSize(240, 320);
    obs.rangeImage.fill(800);
    obs.cameraParams.ncols = 320, obs.cameraParams.nrows = 240;
    obs.cameraParams.setIntrinsicParamsFromValues(285.0, 285.0, 159.5, 119.5);
    obs.cameraParamsIntensity.ncols = 640, obs.cameraParamsIntensity.nrows = 360;
    obs.cameraParamsIntensity.setIntrinsicParamsFromValues(460.0, 461.0, 321.0, 178.0);
    // The colour camera 25 mm along the depth camera's x (MRPT's sensor frame: -y).
    obs.relativePoseIntensityWRTDepth = mrpt::poses::CPose3D(0.0, -0.025, 0.0, -M_PI / 2, 0.0, -M_PI / 2);
    obs.hasIntensityImage = true;
    obs.intensityImage = mrpt::img::CImage(cv::Mat(360, 640, CV_8UC3, cv::Scalar(40, 90, 160)), mrpt::img::DEEP_COPY);
    mrpt::io::CFileGZOutputStream out(path.string());
    auto arch = mrpt::serialization::archiveFrom(out);
    arch << obs << obs;
  }
  const auto s = replayRawlog(path.string());
  EXPECT_EQ(s.frames, 2);
  EXPECT_EQ(s.framesRegisteredOnRead, 2);
  EXPECT_EQ(s.depthAlignment(), "unregistered");
  EXPECT_NE(s.toText().find("unregistered"), std::string::npos);
  EXPECT_EQ(s.intrinsics, (srp::core::CameraIntrinsics{460.0, 461.0, 321.0, 178.0, 640, 360}));
  EXPECT_EQ(s.toJson().at("depth_alignment"), "unregistered");
}
