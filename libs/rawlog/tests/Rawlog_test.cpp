#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include <mrpt/io/CFileGZInputStream.h>
#include <mrpt/obs/CObservationComment.h>
#include <mrpt/io/CFileGZOutputStream.h>
#include <mrpt/obs/CObservation3DRangeScan.h>
#include <mrpt/serialization/CArchive.h>

#include "srp/core/Error.h"
#include "srp/rawlog/RawlogReader.h"
#include "srp/rawlog/RawlogWriter.h"
#include "TestFrames.h"

using namespace srp::rawlog;

namespace {
constexpr double kDepthUnit_m = 1e-4;
constexpr double kDepthTol_m = kDepthUnit_m / 2 + 1e-7;  // quantisation to the stored unit
const srp::core::CameraIntrinsics kK{525.0, 526.0, 159.5, 119.5, 320, 240};

RgbdFrame makeFrame(int i) {
  return srp::rawlog::testing::testFrame(i, kK, 1234 + i, [i](int r, int c) {
    return (c % 17 == 0) ? 0.0f : 0.4f + 0.001f * r + 0.0003f * c + 0.01f * i;
  });
}

std::string tempPath(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("srp_rawlog_test_" + name)).string();
}
}  // namespace

TEST(Rawlog, RoundTripKeepsIntrinsicsColourAndDepth) {
  const std::string path = tempPath("roundtrip.rawlog");
  {
    RawlogWriter writer(path, kDepthUnit_m);
    for (int i = 0; i < 3; ++i) writer.write(makeFrame(i));
    EXPECT_EQ(writer.framesWritten(), 3);
  }
  const auto frames = RawlogReader::readAll(path);
  ASSERT_EQ(frames.size(), 3u);
  for (int i = 0; i < 3; ++i) {
    const RgbdFrame expected = makeFrame(i);
    const RgbdFrame& got = frames[i];
    EXPECT_EQ(got.index, i);
    EXPECT_EQ(got.intrinsics, kK);
    EXPECT_NEAR(got.t_s, expected.t_s, 1e-6);
    EXPECT_EQ(cv::norm(got.colour_bgr8, expected.colour_bgr8, cv::NORM_INF), 0.0) << "colour is lossless";
    double maxErr = 0.0;
    for (int r = 0; r < got.depth_m.rows; ++r)
      for (int c = 0; c < got.depth_m.cols; ++c) {
        const float e = expected.depth_m.at<float>(r, c), g = got.depth_m.at<float>(r, c);
        if (e == 0.0f) ASSERT_EQ(g, 0.0f) << "invalid depth stays invalid";
        maxErr = std::max(maxErr, static_cast<double>(std::abs(e - g)));
      }
    EXPECT_LT(maxErr, kDepthTol_m);
  }
  std::filesystem::remove(path);
}

TEST(Rawlog, TruncatedFileKeepsFramesBeforeTheDamage) {
  const std::string path = tempPath("truncated.rawlog");
  {
    RawlogWriter writer(path, kDepthUnit_m, 0);
    for (int i = 0; i < 4; ++i) writer.write(makeFrame(i));
  }
  const auto size = std::filesystem::file_size(path);
  std::filesystem::resize_file(path, size * 5 / 8);  // inside the third frame
  RawlogReader reader(path);
  int n = 0;
  while (reader.next()) ++n;
  EXPECT_EQ(n, 2);
  ASSERT_TRUE(reader.damage().has_value());
  EXPECT_NE(reader.damage()->find("after frame 2"), std::string::npos) << *reader.damage();
  EXPECT_THROW(RawlogReader::readAll(path), srp::core::FileError);
  std::filesystem::remove(path);
}

TEST(Rawlog, BadInputGivesClearErrors) {
  EXPECT_THROW(RawlogReader("/nonexistent/demo.rawlog"), srp::core::FileError);
  const std::string junk = tempPath("junk.rawlog");
  std::ofstream(junk) << "this is not a rawlog";
  EXPECT_THROW(RawlogReader::readAll(junk), srp::core::FileError);
  std::filesystem::remove(junk);
  RgbdFrame f = makeFrame(0);
  f.depth_m = cv::Mat(100, 100, CV_32FC1, cv::Scalar(1.0f));
  const std::string path = tempPath("bad.rawlog");
  RawlogWriter writer(path);
  try {
    writer.write(f);
    ADD_FAILURE() << "mismatched depth size accepted";
  } catch (const srp::core::InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("100x100"), std::string::npos) << e.what();
  }
  std::filesystem::remove(path);
}

TEST(Rawlog, ReadsMrptSampleDataset) {
  const std::string path = "/usr/share/mrpt/datasets/tests_rgbd.rawlog";
  if (!std::filesystem::exists(path)) FAIL() << path << " missing: install Debian's mrpt-common (scripts/install-deps.sh does)";
  RawlogReader reader(path);
  auto f = reader.next();
  ASSERT_TRUE(f.has_value());
  EXPECT_EQ(f->depth_m.cols, 640);
  EXPECT_NEAR(f->intrinsics.fx_px, 572.883, 0.01);  // depth camera, per the dataset README
  const int valid = cv::countNonZero(f->depth_m > 0.0f);
  EXPECT_EQ(valid, 273225);
}

// Frames handed to encoder threads come back complete and in write() order,
// also when the caller reuses its buffers right after write().
TEST(Rawlog, ThreadedWriterKeepsOrderAndPixels) {
  const std::string path = tempPath("threaded.rawlog");
  constexpr int kFrames = 12;
  {
    RawlogWriter writer(path, kDepthUnit_m, 1, 3);
    RgbdFrame reused = makeFrame(0);
    for (int i = 0; i < kFrames; ++i) {
      makeFrame(i).colour_bgr8.copyTo(reused.colour_bgr8);  // same buffers every frame
      makeFrame(i).depth_m.copyTo(reused.depth_m);
      reused.index = i;
      reused.t_s = makeFrame(i).t_s;
      writer.write(reused);
    }
    EXPECT_EQ(writer.framesWritten(), kFrames);
    writer.close();
    EXPECT_EQ(writer.bytesWritten(), std::filesystem::file_size(path));
    EXPECT_GT(writer.encodeCpuTime_s(), 0.0);
  }
  const auto frames = RawlogReader::readAll(path);
  ASSERT_EQ(static_cast<int>(frames.size()), kFrames);
  for (int i = 0; i < kFrames; ++i) {
    const RgbdFrame expected = makeFrame(i);
    EXPECT_NEAR(frames[i].t_s, expected.t_s, 1e-6) << "frame " << i;
    EXPECT_EQ(cv::norm(frames[i].colour_bgr8, expected.colour_bgr8, cv::NORM_INF), 0.0) << "frame " << i;
    cv::Mat err;
    cv::absdiff(frames[i].depth_m, expected.depth_m, err);
    double maxErr = 0.0;
    cv::minMaxLoc(err, nullptr, &maxErr);
    EXPECT_LT(maxErr, kDepthTol_m) << "frame " << i;
  }
  std::filesystem::remove(path);
}

// 640x480 frames of noise: each gzip member (~1.2 MB) is larger than the
// reader's first input chunk and output guess, so members are decoded
// whole after more input and more room, up to the file's last byte.
TEST(Rawlog, ReadsMembersLargerThanItsInputChunkToTheLastByte) {
  const std::string path = tempPath("large.rawlog");
  const srp::core::CameraIntrinsics K{525.0, 525.0, 319.5, 239.5, 640, 480};
  auto frame = [&](int i) {
    return srp::rawlog::testing::testFrame(i, K, 77 + i, [i](int r, int c) {
      return 0.5f + 0.0001f * static_cast<float>((r * 7919 + c * 104729 + i * 31) % 5000);
    });
  };
  constexpr int kFrames = 7;
  {
    RawlogWriter writer(path, kDepthUnit_m);
    for (int i = 0; i < kFrames; ++i) writer.write(frame(i));
  }
  for (const int readAhead : {0, RawlogReader::kDefaultReadAheadFrames}) {
    RawlogReader reader(path, readAhead);
    int n = 0;
    while (auto f = reader.next()) {
      const RgbdFrame expected = frame(n);
      EXPECT_EQ(cv::norm(f->colour_bgr8, expected.colour_bgr8, cv::NORM_INF), 0.0) << "frame " << n;
      cv::Mat err;
      cv::absdiff(f->depth_m, expected.depth_m, err);
      double maxErr = 0.0;
      cv::minMaxLoc(err, nullptr, &maxErr);
      EXPECT_LT(maxErr, kDepthTol_m) << "frame " << n;
      ++n;
    }
    EXPECT_FALSE(reader.damage()) << *reader.damage();
    EXPECT_EQ(n, kFrames) << "read-ahead " << readAhead;
  }
  std::filesystem::remove(path);
}

// One gzip member per frame: the file is still one valid gzip stream for zlib
// (MRPT's own gzip reader, as RawLogViewer uses it, reads every observation).
TEST(Rawlog, MrptReadsTheConcatenatedGzipMembers) {
  const std::string path = tempPath("members.rawlog");
  {
    RawlogWriter writer(path, kDepthUnit_m);
    for (int i = 0; i < 3; ++i) writer.write(makeFrame(i));
  }
  mrpt::io::CFileGZInputStream in(path);
  auto arch = mrpt::serialization::archiveFrom(in);
  int observations = 0;
  std::vector<std::string> comments;
  for (;;) {
    mrpt::serialization::CSerializable::Ptr obj;
    try {
      arch >> obj;
    } catch (const mrpt::serialization::CExceptionEOF&) {
      break;
    }
    // srp's start and end markers are MRPT comments, readable by MRPT's tools.
    if (const auto c = std::dynamic_pointer_cast<mrpt::obs::CObservationComment>(obj)) {
      comments.push_back(c->text);
      continue;
    }
    const auto obs = std::dynamic_pointer_cast<mrpt::obs::CObservation3DRangeScan>(obj);
    ASSERT_TRUE(obs) << "object " << observations << " is not a CObservation3DRangeScan";
    EXPECT_EQ(obs->rangeImage.cols(), kK.width_px);
    EXPECT_EQ(obs->intensityImage.getWidth(), static_cast<size_t>(kK.width_px));
    ++observations;
  }
  ASSERT_EQ(comments.size(), 2u);
  EXPECT_EQ(comments.back(), "srp-rawlog end: frames=3");
  EXPECT_EQ(observations, 3);
  std::filesystem::remove(path);
}

// Rawlogs written before the per-frame members (one gzip stream by MRPT's
// CFileGZOutputStream, as MRPT's grabbers write them) still read.
TEST(Rawlog, ReadsSingleStreamRawlogs) {
  const std::string path = tempPath("single_stream.rawlog");
  {
    mrpt::io::CFileGZOutputStream out(path);
    auto arch = mrpt::serialization::archiveFrom(out);
    const RgbdFrame f = makeFrame(0);
    auto obs = mrpt::obs::CObservation3DRangeScan::Create();
    obs->timestamp = mrpt::Clock::fromDouble(f.t_s);
    obs->cameraParams.ncols = kK.width_px;
    obs->cameraParams.nrows = kK.height_px;
    obs->cameraParams.setIntrinsicParamsFromValues(kK.fx_px, kK.fy_px, kK.cx_px, kK.cy_px);
    obs->range_is_depth = true;
    obs->rangeUnits = static_cast<float>(kDepthUnit_m);
    obs->hasRangeImage = true;
    obs->rangeImage_setSize(kK.height_px, kK.width_px);
    obs->rangeImage.fill(8500);
    for (int i = 0; i < 2; ++i) arch << *obs;
  }
  const auto frames = RawlogReader::readAll(path);
  ASSERT_EQ(frames.size(), 2u);
  EXPECT_EQ(frames[1].intrinsics, kK);
  EXPECT_NEAR(frames[1].depth_m.at<float>(100, 100), 0.85, kDepthTol_m);
  std::filesystem::remove(path);
}

TEST(Rawlog, ThreadedWriterRejectsBadFramesAtWrite) {
  const std::string path = tempPath("threaded_bad.rawlog");
  RawlogWriter writer(path, kDepthUnit_m, 1, 2);
  RgbdFrame f = makeFrame(0);
  f.colour_bgr8 = cv::Mat(10, 10, CV_8UC3);
  EXPECT_THROW(writer.write(f), srp::core::InvalidInputError);
  EXPECT_THROW(RawlogWriter(path, kDepthUnit_m, 13), srp::core::InvalidInputError);
  EXPECT_THROW(RawlogWriter("/nonexistent/dir/x.rawlog", kDepthUnit_m, 1, 2), srp::core::FileError);
  writer.close();
  std::filesystem::remove(path);
}

TEST(Rawlog, ReadAheadGivesWhatASynchronousReadGives) {
  const std::string path = tempPath("readahead.rawlog");
  constexpr int kFrames = 9;
  {
    RawlogWriter writer(path, kDepthUnit_m, 0);
    for (int i = 0; i < kFrames; ++i) writer.write(makeFrame(i));
  }
  // Whole file, then cut inside frame 7: frames, counters and damage agree after every next().
  for (const bool truncate : {false, true}) {
    if (truncate) std::filesystem::resize_file(path, std::filesystem::file_size(path) * 7 / 9 - 100);
    RawlogReader sync(path, 0), ahead(path, 2);
    int n = 0;
    for (;;) {
      const auto a = sync.next();
      const auto b = ahead.next();
      ASSERT_EQ(a.has_value(), b.has_value()) << "frame " << n << (truncate ? " (truncated file)" : "");
      EXPECT_EQ(sync.framesRead(), ahead.framesRead());
      EXPECT_EQ(sync.objectsSkipped(), ahead.objectsSkipped());
      EXPECT_EQ(sync.depthUnit_m(), ahead.depthUnit_m());
      EXPECT_EQ(sync.damage(), ahead.damage());
      if (!a) break;
      EXPECT_EQ(b->index, n);
      EXPECT_EQ(cv::norm(a->colour_bgr8, b->colour_bgr8, cv::NORM_INF), 0.0);
      EXPECT_EQ(cv::norm(a->depth_m, b->depth_m, cv::NORM_INF), 0.0);
      ++n;
    }
    EXPECT_EQ(n, truncate ? 6 : kFrames);
    EXPECT_EQ(ahead.damage().has_value(), truncate);
    EXPECT_FALSE(ahead.next().has_value()) << "the end stays the end";
  }
  std::filesystem::remove(path);
}

TEST(Rawlog, ReaderLeftMidStreamStopsItsReadAhead) {
  const std::string path = tempPath("midstream.rawlog");
  {
    RawlogWriter writer(path, kDepthUnit_m, 0);
    for (int i = 0; i < 6; ++i) writer.write(makeFrame(i));
  }
  {
    RawlogReader reader(path, 1);
    const auto f = reader.next();
    ASSERT_TRUE(f.has_value());
    EXPECT_EQ(f->index, 0);
  }  // the destructor must stop the worker blocked on a full queue (a hang fails by CTest's timeout)
  std::filesystem::remove(path);
}
