#pragma once
/// \file RawlogWriter.h
/// \brief Writes RGB-D frames as an MRPT rawlog of CObservation3DRangeScan
/// (gzip-compressed, observations-only format; readable by MRPT's RawLogViewer).

#include <memory>
#include <string>

#include "srp/rawlog/RgbdFrame.h"

namespace srp::rawlog {

/// Streams frames to a rawlog file. Each frame becomes one
/// `mrpt::obs::CObservation3DRangeScan` with `range_is_depth = true`, the depth
/// as uint16 in `depthUnit_m` steps (depths beyond 65535 steps are stored as
/// invalid), the colour as intensity image, and the same intrinsics for the
/// depth and the intensity camera (registered).
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
  /// default; real cameras use 1 mm).
  explicit RawlogWriter(const std::string& path, double depthUnit_m = 1e-4, int compressionLevel = 1);
  ~RawlogWriter();
  RawlogWriter(const RawlogWriter&) = delete;
  RawlogWriter& operator=(const RawlogWriter&) = delete;

  /// Validates and appends one frame; throws InvalidInputError for a bad frame.
  void write(const RgbdFrame& frame);
  /// Flushes and closes; called by the destructor too.
  void close();
  int framesWritten() const { return framesWritten_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::string path_;
  double depthUnit_m_;
  int framesWritten_ = 0;
};

}  // namespace srp::rawlog
