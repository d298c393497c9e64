#pragma once
/// \file RawlogWriter.h
/// \brief Writes RGB-D frames as an MRPT rawlog of CObservation3DRangeScan
/// (gzip-compressed, observations-only format; readable by MRPT's RawLogViewer).

#include <cstdint>
#include <memory>
#include <string>

#include "srp/rawlog/RgbdFrame.h"

namespace srp::rawlog {

/// Streams frames to a rawlog file. Each frame becomes one
/// `mrpt::obs::CObservation3DRangeScan` with `range_is_depth = true`, the depth
/// as uint16 in `depthUnit_m` steps (depths beyond 65535 steps are stored as
/// invalid), the colour as raw (lossless) intensity image, and the same
/// intrinsics for the depth and the intensity camera (registered).
///
/// File format: each observation is compressed on its own into one gzip member
/// (libdeflate) and the members are concatenated, which is a valid gzip file
/// (RFC 1952) that zlib's gzread — and so MRPT's CFileGZInputStream, RawLogViewer
/// and RawlogReader — reads as one stream. Compressing frames independently lets
/// several threads compress at once (`encoderThreads`).
///
/// \code
///   srp::rawlog::RawlogWriter writer("demo.rawlog");
///   for (const auto& frame : frames) writer.write(frame);
///   writer.close();
/// \endcode
class RawlogWriter {
 public:
  /// Opens `path` for writing (truncates); throws FileError when it cannot.
  /// depthUnit_m: depth quantisation step stored in the file (0.1 mm by
  /// default; real cameras use 1 mm). compressionLevel: 0 (stored) to 12
  /// (libdeflate's levels; 1 is fastest and, on noisy images, within 10 % of
  /// the best). encoderThreads: 0 converts and compresses inside write();
  /// N > 0 hands frames to N background threads (write() returns at once,
  /// unless N + 2 frames are already waiting) that append them in order.
  explicit RawlogWriter(const std::string& path, double depthUnit_m = 1e-4, int compressionLevel = 1,
                        int encoderThreads = 0);
  ~RawlogWriter();
  RawlogWriter(const RawlogWriter&) = delete;
  RawlogWriter& operator=(const RawlogWriter&) = delete;

  /// Validates and appends one frame; throws InvalidInputError for a bad frame,
  /// FileError when the disk refuses (with threads: at a later write() or close()).
  void write(const RgbdFrame& frame);
  /// As above without copying the images (with threads): the caller must not
  /// modify the frame's pixels afterwards (other cv::Mat headers may still read them).
  void write(RgbdFrame&& frame);
  /// Waits for queued frames, flushes and closes; called by the destructor too.
  void close();
  /// Frames accepted by write() so far (with threads, some may still be queued until close()).
  int framesWritten() const { return framesWritten_; }
  /// CPU time [s] spent converting, serialising, compressing and writing the
  /// frames, summed over the threads that did it (complete after close()).
  double encodeCpuTime_s() const;
  /// Bytes written to the file so far (complete after close()).
  std::uint64_t bytesWritten() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::string path_;
  int framesWritten_ = 0;
};

}  // namespace srp::rawlog
