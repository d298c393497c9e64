#include "srp/rawlog/RawlogReader.h"

#include <mrpt/io/CFileGZInputStream.h>
#include <mrpt/obs/CObservation3DRangeScan.h>
#include <mrpt/serialization/CArchive.h>
#include <mrpt/serialization/CSerializable.h>

#include <filesystem>

#include "srp/core/Error.h"
#include "srp/rawlog/ObservationToFrame.h"

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
      // MRPT exceptions start with a banner line; the reason is on "Message:".
      if (const auto m = reason.find("Message:"); m != std::string::npos) reason = reason.substr(m + 8);
      reason.erase(0, reason.find_first_not_of(" \t"));
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
    depthUnit_m_ = static_cast<double>(obs->rangeUnits);
    return frameFromObservation(*obs, framesRead_++);
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
