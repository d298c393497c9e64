#pragma once
/// \file RawlogReader.h
/// \brief Reads RGB-D frames from an MRPT rawlog (CObservation3DRangeScan),
/// whatever wrote it: srp's writer, MRPT's grabbers, or MRPT's sample datasets.

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "srp/rawlog/RgbdFrame.h"

namespace srp::rawlog {

/// Streaming reader. Objects other than CObservation3DRangeScan (and scans
/// without depth) are skipped and counted. A damaged file (truncated, corrupt)
/// ends the stream early: next() returns nullopt and damage() says after which
/// frame and why, so the frames before the damage stay usable.
///
/// Colour: the intensity image (grey images are converted to BGR); when the
/// scan has no intensity image, colour is left empty. Depth: rangeImage times
/// rangeUnits, as recorded when the scan's two cameras coincide, else
/// re-projected into the colour camera (frameFromObservation in
/// ObservationToFrame.h says when; RgbdFrame::depthRegisteredOnRead tells).
///
/// Read-ahead: by default a background thread decompresses and converts the
/// next few frames while the caller works on the current one (decoding a
/// 640x480 frame costs 2-5 ms, a fifth to a third of what perception spends
/// on it).
/// Frames, counters and damage are reported exactly as a synchronous read
/// would, in the same order; `readAheadFrames = 0` decodes in next() instead.
class RawlogReader {
 public:
  /// How many decoded frames may wait in the read-ahead queue (0: no thread).
  static constexpr int kDefaultReadAheadFrames = 4;

  /// Opens the file; throws FileError naming it when missing or unreadable.
  explicit RawlogReader(const std::string& path, int readAheadFrames = kDefaultReadAheadFrames);
  ~RawlogReader();
  RawlogReader(const RawlogReader&) = delete;
  RawlogReader& operator=(const RawlogReader&) = delete;

  /// The next RGB-D frame, or nullopt at the end of the file (or at damage).
  std::optional<RgbdFrame> next();

  /// Set when reading stopped at a damaged object: "after frame N: <reason>".
  const std::optional<std::string>& damage() const { return damage_; }
  int framesRead() const { return framesRead_; }
  /// Depth quantisation step [m] of the last frame read (its rangeUnits), 0
  /// before the first frame: writing depth PNGs in this unit is lossless.
  double depthUnit_m() const { return depthUnit_m_; }
  int objectsSkipped() const { return objectsSkipped_; }
  const std::string& path() const { return path_; }

  /// Reads all frames; throws FileError when the file is damaged, has no RGB-D
  /// frames, or (requireDepth) a frame without depth.
  static std::vector<RgbdFrame> readAll(const std::string& path);

 private:
  struct Impl;
  struct Decoded;
  Decoded decodeNext();
  void startReadAhead(int frames);

  std::unique_ptr<Impl> impl_;
  std::string path_;
  std::optional<std::string> damage_;
  int framesRead_ = 0;
  int objectsSkipped_ = 0;
  double depthUnit_m_ = 0.0;
};

}  // namespace srp::rawlog
