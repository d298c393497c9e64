#include "srp/rawlog/RawlogReader.h"

#include <mrpt/io/CFileGZInputStream.h>
#include <mrpt/obs/CObservation3DRangeScan.h>
#include <mrpt/serialization/CArchive.h>
#include <mrpt/serialization/CSerializable.h>

#include <filesystem>
#include <opencv2/imgproc.hpp>

#include "srp/core/Error.h"

namespace srp::rawlog {

struct RawlogReader::Impl {
  mrpt::io::CFileGZInputStream in;
  bool ended = false;
};

RawlogReader::RawlogReader(const std::string& path) : impl_(std::make_unique<Impl>()), path_(path) {
  if (!std::filesystem::is_regular_file(path))
    throw core::FileError(path, "rawlog not found (record one with 'srp record' or make one with 'srp synth-demo')");
  if (!impl_->in.open(path)) throw core::FileError(path, "cannot open rawlog (permissions?)");
}

RawlogReader::~RawlogReader() = default;

namespace {

RgbdFrame toFrame(const mrpt::obs::CObservation3DRangeScan& obs, int index) {
  RgbdFrame f;
  f.index = index;
  f.t_s = mrpt::Clock::toDouble(obs.timestamp);
  const auto& cam = obs.cameraParams;
  f.intrinsics = {cam.fx(), cam.fy(), cam.cx(), cam.cy(), static_cast<int>(cam.ncols), static_cast<int>(cam.nrows)};
  const int rows = static_cast<int>(obs.rangeImage.rows());
  const int cols = static_cast<int>(obs.rangeImage.cols());
  if (f.intrinsics.width_px != cols || f.intrinsics.height_px != rows) {
    // Some grabbers leave ncols/nrows unset: trust the image size.
    f.intrinsics.width_px = cols;
    f.intrinsics.height_px = rows;
  }
  f.depth_m = cv::Mat(rows, cols, CV_32FC1);
  const float units = obs.rangeUnits;
  for (int r = 0; r < rows; ++r) {
    float* d = f.depth_m.ptr<float>(r);
    for (int c = 0; c < cols; ++c) d[c] = static_cast<float>(obs.rangeImage(r, c)) * units;
  }
  if (obs.hasIntensityImage && !obs.intensityImage.isEmpty()) {
    cv::Mat img = obs.intensityImage.asCvMat<cv::Mat>(mrpt::img::SHALLOW_COPY);
    cv::Mat bgr;
    if (img.channels() == 1) cv::cvtColor(img, bgr, cv::COLOR_GRAY2BGR);
    else bgr = img.clone();
    if (bgr.cols != cols || bgr.rows != rows) cv::resize(bgr, bgr, cv::Size(cols, rows), 0, 0, cv::INTER_LINEAR);
    f.colour_bgr8 = bgr;
  }
  return f;
}

}  // namespace

std::optional<RgbdFrame> RawlogReader::next() {
  while (!impl_->ended) {
    mrpt::serialization::CSerializable::Ptr obj;
    try {
      auto arch = mrpt::serialization::archiveFrom(impl_->in);
      arch >> obj;
    } catch (const mrpt::serialization::CExceptionEOF&) {
      impl_->ended = true;
      break;
    } catch (const std::exception& e) {
      impl_->ended = true;
      std::string reason = e.what();
      if (const auto nl = reason.find('\n'); nl != std::string::npos) reason = reason.substr(0, nl);
      damage_ = "damaged after frame " + std::to_string(framesRead_) + " (" + std::to_string(framesRead_) +
                " frames readable): " + reason;
      break;
    }
    auto obs = std::dynamic_pointer_cast<mrpt::obs::CObservation3DRangeScan>(obj);
    if (!obs) {
      ++objectsSkipped_;
      continue;
    }
    obs->load();
    if (!obs->hasRangeImage) {
      ++objectsSkipped_;
      continue;
    }
    return toFrame(*obs, framesRead_++);
  }
  return std::nullopt;
}

std::vector<RgbdFrame> RawlogReader::readAll(const std::string& path) {
  RawlogReader reader(path);
  std::vector<RgbdFrame> frames;
  while (auto f = reader.next()) frames.push_back(std::move(*f));
  if (reader.damage()) throw core::FileError(path, *reader.damage());
  if (frames.empty())
    throw core::FileError(path, "no RGB-D frames (CObservation3DRangeScan with depth) in this rawlog (" +
                                    std::to_string(reader.objectsSkipped()) + " other objects)");
  return frames;
}

}  // namespace srp::rawlog
