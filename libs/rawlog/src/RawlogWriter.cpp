#include "srp/rawlog/RawlogWriter.h"

#include <mrpt/io/CFileGZOutputStream.h>
#include <mrpt/obs/CObservation3DRangeScan.h>
#include <mrpt/serialization/CArchive.h>

#include <cmath>

#include "srp/core/Error.h"

namespace srp::rawlog {

struct RawlogWriter::Impl {
  mrpt::io::CFileGZOutputStream out;
};

RawlogWriter::RawlogWriter(const std::string& path, double depthUnit_m, int compressionLevel)
    : impl_(std::make_unique<Impl>()), path_(path), depthUnit_m_(depthUnit_m) {
  if (!(depthUnit_m > 0.0)) throw core::InvalidInputError("rawlog depth unit must be positive");
  if (!impl_->out.open(path, compressionLevel))
    throw core::FileError(path, "cannot create rawlog (is the folder there and writable?)");
}

RawlogWriter::~RawlogWriter() {
  try {
    close();
  } catch (...) {
  }
}

void RawlogWriter::write(const RgbdFrame& frame) {
  if (!impl_->out.is_open()) throw core::FileError(path_, "rawlog already closed");
  frame.validate(path_);
  auto obs = mrpt::obs::CObservation3DRangeScan::Create();
  obs->sensorLabel = "RGBD";
  obs->timestamp = mrpt::Clock::fromDouble(frame.t_s);
  const auto& K = frame.intrinsics;
  obs->cameraParams.ncols = K.width_px;
  obs->cameraParams.nrows = K.height_px;
  obs->cameraParams.setIntrinsicParamsFromValues(K.fx_px, K.fy_px, K.cx_px, K.cy_px);
  obs->cameraParamsIntensity = obs->cameraParams;
  obs->range_is_depth = true;
  obs->rangeUnits = static_cast<float>(depthUnit_m_);
  obs->hasRangeImage = true;
  obs->rangeImage_setSize(K.height_px, K.width_px);
  const double scale = 1.0 / static_cast<double>(obs->rangeUnits);
  for (int r = 0; r < K.height_px; ++r) {
    const float* d = frame.depth_m.ptr<float>(r);
    for (int c = 0; c < K.width_px; ++c) {
      const double steps = std::round(static_cast<double>(d[c]) * scale);
      obs->rangeImage(r, c) = (std::isfinite(d[c]) && d[c] > 0.0f && steps <= 65535.0)
                                  ? static_cast<uint16_t>(steps)
                                  : uint16_t(0);
    }
  }
  // Colour must round-trip bit-exactly: raw, not JPEG (MRPT's global switch).
  mrpt::img::CImage::DISABLE_JPEG_COMPRESSION(true);
  obs->hasIntensityImage = true;
  obs->intensityImage = mrpt::img::CImage(frame.colour_bgr8, mrpt::img::DEEP_COPY);
  obs->intensityImageChannel = mrpt::obs::CObservation3DRangeScan::CH_VISIBLE;
  auto arch = mrpt::serialization::archiveFrom(impl_->out);
  arch << *obs;
  ++framesWritten_;
}

void RawlogWriter::close() {
  if (impl_ && impl_->out.is_open()) impl_->out.close();
}

}  // namespace srp::rawlog
