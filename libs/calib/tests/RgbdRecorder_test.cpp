#include "srp/calib/RgbdRecorder.h"

#include <gtest/gtest.h>

#include <filesystem>

using namespace srp::calib;
namespace fs = std::filesystem;

TEST(RgbdRecorder, WithoutACameraSaysSoClearlyAndWritesNothing) {
  if (countOpenNI2Devices() > 0) GTEST_SKIP() << "an OpenNI2 camera is connected; this test is for machines without";
  const std::string out = (fs::temp_directory_path() / "srp_calib_record.rawlog").string();
  fs::remove(out);
  RecordOptions options;
  options.maxFrames = 3;
  try {
    recordOpenNI2(out, options);
    FAIL() << "expected NoCameraError";
  } catch (const NoCameraError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("no RGB-D camera"), std::string::npos) << msg;
    EXPECT_NE(msg.find("srp import"), std::string::npos) << "suggests the alternative: " << msg;
  }
  EXPECT_FALSE(fs::exists(out)) << "no empty rawlog left behind";
}

TEST(RgbdRecorder, RejectsOptionsWithoutALimit) {
  RecordOptions options;
  options.maxFrames = 0;
  options.duration_s = 0.0;
  EXPECT_THROW(recordOpenNI2("unused.rawlog", options), srp::core::InvalidInputError);
}
