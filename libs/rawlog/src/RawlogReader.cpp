#include "srp/rawlog/RawlogReader.h"

#include <mrpt/obs/CObservation3DRangeScan.h>
#include <mrpt/obs/CObservationComment.h>
#include <mrpt/serialization/CArchive.h>
#include <mrpt/serialization/CSerializable.h>

#include <cmath>
#include <condition_variable>
#include <cstring>
#include <deque>
#include <exception>
#include <filesystem>
#include <mutex>
#include <thread>

#include "srp/core/Error.h"
#include "RawlogSource.h"
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

namespace {

// Decode a whole gzip member (a frame, for srp's rawlogs) before parsing it:
// its CRC is checked and its length known before MRPT allocates anything.
constexpr std::size_t kPrefetchBytes = std::size_t(64) << 20;

// MRPT exceptions start with a banner line; the reason is on "Message:".
std::string reasonOf(const std::string& what) {
  std::string reason = what;
  if (const auto m = reason.find("Message:"); m != std::string::npos) reason = reason.substr(m + 8);
  reason.erase(0, reason.find_first_not_of(" \t"));
  if (const auto nl = reason.find('\n'); nl != std::string::npos) reason = reason.substr(0, nl);
  return detail::printable(reason);
}

// What srp needs of a scan, checked after MRPT read it and before converting it.
std::optional<std::string> checkScan(const mrpt::obs::CObservation3DRangeScan& obs) {
  const auto rows = obs.rangeImage.rows(), cols = obs.rangeImage.cols();
  if (rows < 1 || cols < 1 || rows > static_cast<int>(detail::kMaxImageSide_px) ||
      cols > static_cast<int>(detail::kMaxImageSide_px))
    return "depth image of " + std::to_string(cols) + " x " + std::to_string(rows) + " px";
  if (!std::isfinite(obs.rangeUnits) || obs.rangeUnits <= 0.0f) return "depth unit " + std::to_string(obs.rangeUnits);
  const auto& cam = obs.cameraParams;
  for (const double v : {cam.fx(), cam.fy(), cam.cx(), cam.cy()})
    if (!std::isfinite(v)) return std::string("camera intrinsics are not finite");
  if (obs.hasIntensityImage && !obs.intensityImage.isEmpty()) {
    const auto w = obs.intensityImage.getWidth(), h = obs.intensityImage.getHeight();
    if (w < 1 || h < 1 || w > detail::kMaxImageSide_px || h > detail::kMaxImageSide_px)
      return "colour image of " + std::to_string(w) + " x " + std::to_string(h) + " px";
  }
  return std::nullopt;
}

}  // namespace

struct RawlogReader::Impl {
  std::unique_ptr<detail::RawlogSource> in;
  bool srpFormat = false;      // the file starts with srp's start marker: it must end with the end marker
  bool endMarkerSeen = false;
  int objects = 0;
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
  impl_->in = std::make_unique<detail::RawlogSource>(path);
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
  Impl& im = *impl_;
  detail::RawlogSource& src = *im.in;
  const auto fail = [&](const std::string& reason, std::uint64_t fileOffset, std::uint64_t dataOffset) {
    im.decoderEnded = true;
    std::string where = "at byte " + std::to_string(fileOffset) + " of the file";
    if (src.gzip()) where += " (the gzip member holding it; byte " + std::to_string(dataOffset) + " of the decompressed data)";
    st.damage = "damaged after frame " + std::to_string(st.framesRead) + " (" + std::to_string(st.framesRead) +
                " frames readable): frame " + std::to_string(st.framesRead) + " " + where + ": " + reason;
  };
  while (!im.decoderEnded) {
    src.prefetch(kPrefetchBytes);
    const std::uint64_t fileOffset = src.fileOffset(), dataOffset = src.getPosition();
    if (src.error()) {
      // The member did not decode (corrupt data, CRC mismatch, cut short):
      // none of its bytes are trusted, even those zlib produced before.
      fail(*src.error(), fileOffset, dataOffset);
      break;
    }
    if (src.available() == 0) {
      if (im.srpFormat && !im.endMarkerSeen) {
        fail("the file ends without srp's end marker (truncated; it was not closed by its writer)", fileOffset,
             dataOffset);
      } else {
        im.decoderEnded = true;  // a clean end: nothing was left to read
      }
      break;
    }
    if (im.endMarkerSeen) {
      fail("data after srp's end marker", fileOffset, dataOffset);
      break;
    }
    if (auto problem = detail::prescanObject(src.peek(), src.available(), src.bounded())) {
      fail(*problem, fileOffset, dataOffset);
      break;
    }
    mrpt::serialization::CSerializable::Ptr obj;
    try {
      auto arch = mrpt::serialization::archiveFrom(src);
      arch >> obj;
    } catch (const std::bad_alloc&) {
      fail("the object declares more memory than this machine has (a damaged size field)", fileOffset, dataOffset);
      break;
    } catch (const std::exception& e) {
      // MRPT reports any failure inside an object as "EOF"; an object had
      // started here, so it is damage (a gzip error says what it was).
      fail(src.error() ? *src.error() : reasonOf(e.what()), fileOffset, dataOffset);
      break;
    }
    const bool first = im.objects++ == 0;
    if (auto comment = std::dynamic_pointer_cast<mrpt::obs::CObservationComment>(obj)) {
      const std::string& text = comment->text;
      if (first && text == detail::kStartMarker) {
        im.srpFormat = true;
        continue;
      }
      if (text.rfind(detail::kEndMarker, 0) == 0) {
        const std::string count = text.substr(std::strlen(detail::kEndMarker));
        if (count != std::to_string(st.framesRead)) {
          fail("the end marker counts " + detail::printable(count, 20) + " frames but " +
                   std::to_string(st.framesRead) + " were read (frames lost)",
               fileOffset, dataOffset);
          break;
        }
        im.endMarkerSeen = true;
        continue;
      }
    }
    auto obs = std::dynamic_pointer_cast<mrpt::obs::CObservation3DRangeScan>(obj);
    if (!obs) {
      ++st.objectsSkipped;
      continue;
    }
    try {
      obs->load();
    } catch (const std::exception& e) {
      fail("external image: " + reasonOf(e.what()), fileOffset, dataOffset);
      break;
    }
    if (!obs->hasRangeImage) {
      ++st.objectsSkipped;
      continue;
    }
    if (auto problem = checkScan(*obs)) {
      fail(*problem + " (a damaged field)", fileOffset, dataOffset);
      break;
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
