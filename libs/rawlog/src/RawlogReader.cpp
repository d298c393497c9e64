#include "srp/rawlog/RawlogReader.h"

#include <mrpt/io/CFileGZInputStream.h>
#include <mrpt/obs/CObservation3DRangeScan.h>
#include <mrpt/serialization/CArchive.h>
#include <mrpt/serialization/CSerializable.h>

#include <condition_variable>
#include <deque>
#include <exception>
#include <filesystem>
#include <mutex>
#include <thread>

#include "srp/core/Error.h"
#include "srp/rawlog/ObservationToFrame.h"

namespace srp::rawlog {

/// One decoder step: a frame (or the end) with the counters as they were
/// right after reading it, so the consumer reports what a synchronous read would.
struct RawlogReader::Decoded {
  std::optional<RgbdFrame> frame;
  int framesRead = 0;
  int objectsSkipped = 0;
  double depthUnit_m = 0.0;
  std::optional<std::string> damage;
  std::exception_ptr error;
};

struct RawlogReader::Impl {
  mrpt::io::CFileGZInputStream in;
  bool decoderEnded = false;   // the decoder saw the end (or damage)
  bool consumerEnded = false;  // next() returned the end
  Decoded state;               // the decoder's running counters

  // Read-ahead: the worker decodes into `queue` (at most `capacity` waiting).
  std::thread worker;
  std::mutex mutex;
  std::condition_variable changed;
  std::deque<Decoded> queue;
  std::size_t capacity = 0;
  bool stop = false;
};

RawlogReader::RawlogReader(const std::string& path, int readAheadFrames)
    : impl_(std::make_unique<Impl>()), path_(path) {
  if (!std::filesystem::is_regular_file(path))
    throw core::FileError(path, "rawlog not found (record one with 'srp record' or make one with 'srp synth-demo')");
  if (!impl_->in.open(path)) throw core::FileError(path, "cannot open rawlog (permissions?)");
  if (readAheadFrames > 0) startReadAhead(readAheadFrames);
}

RawlogReader::~RawlogReader() {
  if (!impl_->worker.joinable()) return;
  {
    std::lock_guard<std::mutex> lock(impl_->mutex);
    impl_->stop = true;
  }
  impl_->changed.notify_all();
  impl_->worker.join();
}

void RawlogReader::startReadAhead(int frames) {
  impl_->capacity = static_cast<std::size_t>(frames);
  impl_->worker = std::thread([this] {
    Impl& im = *impl_;
    for (;;) {
      {
        std::unique_lock<std::mutex> lock(im.mutex);
        im.changed.wait(lock, [&] { return im.stop || im.queue.size() < im.capacity; });
        if (im.stop) return;
      }
      Decoded d;
      try {
        d = decodeNext();
      } catch (...) {
        d.error = std::current_exception();
      }
      const bool last = !d.frame;
      {
        std::lock_guard<std::mutex> lock(im.mutex);
        im.queue.push_back(std::move(d));
      }
      im.changed.notify_all();
      if (last) return;
    }
  });
}

RawlogReader::Decoded RawlogReader::decodeNext() {
  Decoded& st = impl_->state;
  Decoded out;
  while (!impl_->decoderEnded) {
    mrpt::serialization::CSerializable::Ptr obj;
    try {
      auto arch = mrpt::serialization::archiveFrom(impl_->in);
      arch >> obj;
    } catch (const mrpt::serialization::CExceptionEOF&) {
      impl_->decoderEnded = true;
      break;
    } catch (const std::exception& e) {
      impl_->decoderEnded = true;
      std::string reason = e.what();
      // MRPT exceptions start with a banner line; the reason is on "Message:".
      if (const auto m = reason.find("Message:"); m != std::string::npos) reason = reason.substr(m + 8);
      reason.erase(0, reason.find_first_not_of(" \t"));
      if (const auto nl = reason.find('\n'); nl != std::string::npos) reason = reason.substr(0, nl);
      st.damage = "damaged after frame " + std::to_string(st.framesRead) + " (" + std::to_string(st.framesRead) +
                  " frames readable): " + reason;
      break;
    }
    auto obs = std::dynamic_pointer_cast<mrpt::obs::CObservation3DRangeScan>(obj);
    if (!obs) {
      ++st.objectsSkipped;
      continue;
    }
    obs->load();
    if (!obs->hasRangeImage) {
      ++st.objectsSkipped;
      continue;
    }
    st.depthUnit_m = static_cast<double>(obs->rangeUnits);
    out.frame = frameFromObservation(*obs, st.framesRead++);
    break;
  }
  out.framesRead = st.framesRead;
  out.objectsSkipped = st.objectsSkipped;
  out.depthUnit_m = st.depthUnit_m;
  out.damage = st.damage;
  return out;
}

std::optional<RgbdFrame> RawlogReader::next() {
  if (impl_->consumerEnded) return std::nullopt;
  Decoded d;
  if (impl_->worker.joinable()) {
    {
      std::unique_lock<std::mutex> lock(impl_->mutex);
      impl_->changed.wait(lock, [&] { return !impl_->queue.empty(); });
      d = std::move(impl_->queue.front());
      impl_->queue.pop_front();
    }
    impl_->changed.notify_all();
  } else {
    d = decodeNext();
  }
  if (d.error) {
    impl_->consumerEnded = true;
    std::rethrow_exception(d.error);
  }
  framesRead_ = d.framesRead;
  objectsSkipped_ = d.objectsSkipped;
  depthUnit_m_ = d.depthUnit_m;
  damage_ = d.damage;
  if (!d.frame) impl_->consumerEnded = true;
  return std::move(d.frame);
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
