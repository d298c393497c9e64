#include "srp/rawlog/RawlogWriter.h"

#include <libdeflate.h>
#include <mrpt/io/CStream.h>
#include <mrpt/obs/CObservation3DRangeScan.h>
#include <mrpt/obs/CObservationComment.h>
#include <mrpt/serialization/CArchive.h>

#include <atomic>
#include <cerrno>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <deque>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

#include "RawlogSource.h"
#include "srp/core/Error.h"

namespace srp::rawlog {
namespace {

double threadCpuTime_s() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// An MRPT output stream into a reusable byte vector: serialising an observation
// into memory costs a copy, and reusing the buffer saves the page faults of a
// fresh 1.5 MB allocation per frame.
class VectorOutStream : public mrpt::io::CStream {
 public:
  explicit VectorOutStream(std::vector<std::uint8_t>& bytes) : bytes_(bytes) { bytes_.clear(); }
  size_t Read(void*, size_t) override { throw core::Error("VectorOutStream is write-only"); }
  size_t Write(const void* buffer, size_t count) override {
    const auto* p = static_cast<const std::uint8_t*>(buffer);
    bytes_.insert(bytes_.end(), p, p + count);
    return count;
  }
  uint64_t Seek(int64_t, CStream::TSeekOrigin) override { throw core::Error("VectorOutStream cannot seek"); }
  uint64_t getTotalBytesCount() const override { return bytes_.size(); }
  uint64_t getPosition() const override { return bytes_.size(); }

 private:
  std::vector<std::uint8_t>& bytes_;
};

// Per-thread encoder: frame -> observation -> serialised bytes -> one gzip member.
class FrameEncoder {
 public:
  FrameEncoder(double depthUnit_m, int level) : depthUnit_m_(depthUnit_m), compressor_(libdeflate_alloc_compressor(level)) {
    if (!compressor_)
      throw core::InvalidInputError("rawlog compression level " + std::to_string(level) + " is not in 0..12");
  }
  ~FrameEncoder() { libdeflate_free_compressor(compressor_); }
  FrameEncoder(const FrameEncoder&) = delete;
  FrameEncoder& operator=(const FrameEncoder&) = delete;

  /// The gzip member of `frame` (valid until the next call).
  const std::vector<std::uint8_t>& encode(const RgbdFrame& frame) {
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
    const float scale = static_cast<float>(1.0 / static_cast<double>(obs->rangeUnits));
    for (int r = 0; r < K.height_px; ++r) {
      const float* d = frame.depth_m.ptr<float>(r);
      std::uint16_t* out = &obs->rangeImage(r, 0);  // row-major
      for (int c = 0; c < K.width_px; ++c) {
        const float steps = d[c] * scale;  // NaN fails both comparisons below
        // Round half up by truncation (steps > 0): no libm call in the per-pixel loop.
        out[c] = (steps > 0.0f && steps <= 65535.0f) ? static_cast<std::uint16_t>(steps + 0.5f) : std::uint16_t(0);
      }
    }
    // Colour must round-trip bit-exactly: raw, not JPEG (set once in the writer's constructor).
    obs->hasIntensityImage = true;
    obs->intensityImage = mrpt::img::CImage(frame.colour_bgr8, mrpt::img::SHALLOW_COPY);
    obs->intensityImageChannel = mrpt::obs::CObservation3DRangeScan::CH_VISIBLE;
    return compress(*obs);
  }

  /// The gzip member of a CObservationComment (srp's start and end markers).
  const std::vector<std::uint8_t>& encodeComment(const std::string& text) {
    auto c = mrpt::obs::CObservationComment::Create();
    c->sensorLabel = "srp";
    c->text = text;
    return compress(*c);
  }

 private:
  // One object, serialised and compressed into one gzip member (whose CRC32
  // lets the reader check the frame before parsing it).
  const std::vector<std::uint8_t>& compress(const mrpt::serialization::CSerializable& object) {
    {
      VectorOutStream stream(serialised_);
      auto arch = mrpt::serialization::archiveFrom(stream);
      arch << object;
    }
    compressed_.resize(libdeflate_gzip_compress_bound(compressor_, serialised_.size()));
    const size_t n = libdeflate_gzip_compress(compressor_, serialised_.data(), serialised_.size(), compressed_.data(),
                                              compressed_.size());
    if (n == 0) throw core::Error("rawlog: gzip compression failed");
    compressed_.resize(n);
    return compressed_;
  }

  double depthUnit_m_;
  libdeflate_compressor* compressor_;
  std::vector<std::uint8_t> serialised_, compressed_;
};

}  // namespace

struct RawlogWriter::Impl {
  std::FILE* file = nullptr;
  double depthUnit_m = 1e-4;
  int level = 1;
  std::unique_ptr<FrameEncoder> syncEncoder;    // encoderThreads == 0
  std::unique_ptr<FrameEncoder> markerEncoder;  // encoderThreads > 0: for the end marker
  std::uint64_t bytes = 0;
  double cpu_s = 0.0;

  // Threaded mode: frames numbered in write() order, appended in that order.
  std::vector<std::thread> workers;
  std::mutex mutex;
  std::condition_variable queued, dequeued, turn;
  std::deque<std::pair<long, RgbdFrame>> queue;
  std::size_t maxQueued = 0;
  long nextSequence = 0, nextToAppend = 0;
  bool closing = false;
  std::exception_ptr error;

  void append(const std::vector<std::uint8_t>& member, const std::string& path) {
    if (std::fwrite(member.data(), 1, member.size(), file) != member.size())
      throw core::FileError(path, std::string("cannot write the rawlog (disk full?): ") + std::strerror(errno));
    bytes += member.size();
  }

  void workerLoop(const std::string& path) {
    FrameEncoder encoder(depthUnit_m, level);
    for (;;) {
      std::pair<long, RgbdFrame> job;
      {
        std::unique_lock<std::mutex> lock(mutex);
        queued.wait(lock, [this] { return !queue.empty() || closing || error; });
        if (queue.empty() || error) return;
        job = std::move(queue.front());
        queue.pop_front();
        dequeued.notify_all();
      }
      try {
        const double t0 = threadCpuTime_s();
        const auto& member = encoder.encode(job.second);
        std::unique_lock<std::mutex> lock(mutex);
        turn.wait(lock, [&] { return nextToAppend == job.first || error; });
        if (error) return;
        append(member, path);  // under the lock: appends are ordered and short
        ++nextToAppend;
        cpu_s += threadCpuTime_s() - t0;
        turn.notify_all();
      } catch (...) {
        std::lock_guard<std::mutex> lock(mutex);
        if (!error) error = std::current_exception();
        queued.notify_all();
        dequeued.notify_all();
        turn.notify_all();
        return;
      }
    }
  }

  void rethrowLocked() {
    if (error) std::rethrow_exception(error);
  }
};

RawlogWriter::RawlogWriter(const std::string& path, double depthUnit_m, int compressionLevel, int encoderThreads)
    : impl_(std::make_unique<Impl>()), path_(path) {
  if (!(depthUnit_m > 0.0)) throw core::InvalidInputError("rawlog depth unit must be positive");
  if (compressionLevel < 0 || compressionLevel > 12)
    throw core::InvalidInputError("rawlog compression level " + std::to_string(compressionLevel) +
                                  " is not in 0..12 (0: stored, 1: fastest)");
  if (encoderThreads < 0) throw core::InvalidInputError("rawlog encoder threads must be 0 or more");
  impl_->depthUnit_m = depthUnit_m;
  impl_->level = compressionLevel;
  mrpt::img::CImage::DISABLE_JPEG_COMPRESSION(true);  // colour raw, lossless
  impl_->file = std::fopen(path.c_str(), "wb");
  if (!impl_->file) throw core::FileError(path, "cannot create rawlog (is the folder there and writable?)");
  impl_->syncEncoder = std::make_unique<FrameEncoder>(depthUnit_m, compressionLevel);
  // The start marker tells readers that this file ends with an end marker.
  impl_->append(impl_->syncEncoder->encodeComment(detail::kStartMarker), path_);
  if (encoderThreads > 0) {
    impl_->markerEncoder = std::move(impl_->syncEncoder);
    impl_->maxQueued = static_cast<std::size_t>(encoderThreads) + 2;
    for (int i = 0; i < encoderThreads; ++i) impl_->workers.emplace_back([this, path] { impl_->workerLoop(path); });
  }
}

RawlogWriter::~RawlogWriter() {
  try {
    close();
  } catch (...) {
  }
}

void RawlogWriter::write(const RgbdFrame& frame) {
  if (impl_->syncEncoder) {
    if (!impl_->file) throw core::FileError(path_, "rawlog already closed");
    frame.validate(path_);
    const double t0 = threadCpuTime_s();
    impl_->append(impl_->syncEncoder->encode(frame), path_);
    impl_->cpu_s += threadCpuTime_s() - t0;
    ++framesWritten_;
    return;
  }
  // The queued frame must not share pixels with the caller's, who may reuse them.
  RgbdFrame copy = frame;
  copy.colour_bgr8 = frame.colour_bgr8.clone();
  copy.depth_m = frame.depth_m.clone();
  write(std::move(copy));
}

void RawlogWriter::write(RgbdFrame&& frame) {
  if (impl_->syncEncoder) {
    write(static_cast<const RgbdFrame&>(frame));
    return;
  }
  frame.validate(path_);
  std::unique_lock<std::mutex> lock(impl_->mutex);
  if (impl_->closing) throw core::FileError(path_, "rawlog already closed");
  impl_->dequeued.wait(lock, [this] { return impl_->queue.size() < impl_->maxQueued || impl_->error; });
  impl_->rethrowLocked();
  impl_->queue.emplace_back(impl_->nextSequence++, std::move(frame));
  impl_->queued.notify_one();
  ++framesWritten_;
}

void RawlogWriter::close() {
  if (!impl_ || !impl_->file) return;
  {
    std::lock_guard<std::mutex> lock(impl_->mutex);
    impl_->closing = true;
    impl_->queued.notify_all();
  }
  for (auto& w : impl_->workers)
    if (w.joinable()) w.join();
  std::exception_ptr markerError;
  {
    std::lock_guard<std::mutex> lock(impl_->mutex);
    // The end marker with the frame count, only when every frame is in: a
    // file without it reads as truncated.
    if (!impl_->error) {
      try {
        FrameEncoder& enc = impl_->syncEncoder ? *impl_->syncEncoder : *impl_->markerEncoder;
        impl_->append(enc.encodeComment(detail::kEndMarker + std::to_string(framesWritten_)), path_);
      } catch (...) {
        markerError = std::current_exception();
      }
    }
  }
  const bool flushed = std::fclose(impl_->file) == 0;
  impl_->file = nullptr;
  std::lock_guard<std::mutex> lock(impl_->mutex);
  impl_->rethrowLocked();
  if (markerError) std::rethrow_exception(markerError);
  if (!flushed) throw core::FileError(path_, "cannot finish the rawlog (disk full?)");
}

double RawlogWriter::encodeCpuTime_s() const {
  std::lock_guard<std::mutex> lock(impl_->mutex);
  return impl_->cpu_s;
}

std::uint64_t RawlogWriter::bytesWritten() const {
  std::lock_guard<std::mutex> lock(impl_->mutex);
  return impl_->bytes;
}

}  // namespace srp::rawlog
