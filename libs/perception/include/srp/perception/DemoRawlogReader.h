#pragma once
/// \file DemoRawlogReader.h
/// \brief A demonstration rawlog read for DemoPerceiver: the preview pass and
/// the perception pass over one decode of each frame.

#include <deque>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "srp/core/CameraIntrinsics.h"
#include "srp/perception/DemoPerception.h"
#include "srp/rawlog/RawlogReader.h"
#include "srp/rawlog/RgbdFrame.h"

namespace srp::perception {

/// Reads a demonstration rawlog (rawlog::RawlogReader, read-ahead thread) for
/// a DemoPerceiver: first preview() (the frames DemoPerceiver::preview()
/// needs, in order: the whole recording for the marker-free hand, the first
/// few for HandMethod::Auto when the glove's tag is seen), then next() for
/// DemoPerceiver::add(). The frames the preview decoded are kept and next()
/// hands them out first, then reads on: each frame is decoded once. When the
/// file is larger than `Options::keptFrames_MB`, or the previewed frames would
/// take more (a 640x480 frame takes 2.1 MB decoded, 0.3-0.6 MB in the file),
/// none are kept and next() reads the file a second time from its start:
/// memory stays flat on long recordings and grows by at most the budget.
///
/// ```cpp
/// DemoPerceiver perceiver(catalogue, options);
/// DemoRawlogReader reader("demo.rawlog");
/// if (perceiver.wantsPreview()) reader.preview(perceiver);
/// while (auto f = reader.next()) perceiver.add(*f);
/// if (reader.damage()) ...;  // the damaged frame, as RawlogReader says it
/// const PerceptionResult result = perceiver.finish();
/// ```
///
/// The frames are those of a RawlogReader, bit for bit, whichever way they
/// come: the perception results do not depend on `keptFrames_MB`. Reading
/// stops at a damaged object without an error, in both passes; damage()
/// names it.
class DemoRawlogReader {
 public:
  struct Options {
    /// Replace every frame's intrinsics (a calibration given by the user).
    std::optional<core::CameraIntrinsics> intrinsics;
    /// Memory for the previewed frames kept for the perception pass [MB]
    /// (decimal); 0: never kept, the file is read twice. 128 MB holds a
    /// 640x480 recording of up to 59 frames (6 s at 10 Hz).
    double keptFrames_MB = 128.0;
  };

  /// Opens the file; throws FileError naming it when missing or unreadable.
  explicit DemoRawlogReader(const std::string& path);
  DemoRawlogReader(const std::string& path, const Options& options);
  ~DemoRawlogReader();
  DemoRawlogReader(const DemoRawlogReader&) = delete;
  DemoRawlogReader& operator=(const DemoRawlogReader&) = delete;

  /// The preview pass: shows each frame, in order, to `perceiver.preview()`
  /// until the perceiver's preview is complete or the file ends; returns how
  /// many it showed. `progress(framesPreviewed)` after each frame when given.
  /// Call once, before the first next(). Throws what DemoPerceiver::preview throws.
  int preview(DemoPerceiver& perceiver, const std::function<void(int)>& progress = {});

  /// The perception pass: the next frame (index 0 first), nullopt at the end
  /// of the file or at damage.
  std::optional<rawlog::RgbdFrame> next();

  /// Set when reading stopped at a damaged object (RawlogReader::damage()).
  const std::optional<std::string>& damage() const { return reader_->damage(); }
  /// RGB-D frames of the file read so far (up to the damage), both passes counted once.
  int framesRead() const { return reader_->framesRead(); }
  /// Objects other than RGB-D frames skipped so far.
  int objectsSkipped() const { return reader_->objectsSkipped(); }
  /// Frames preview() showed.
  int framesPreviewed() const { return previewed_; }
  /// True when the preview went through the whole file (it did not stop early).
  bool previewedWholeFile() const { return previewedToEnd_; }
  /// True when the perception pass reads the file a second time (the previewed
  /// frames were over `keptFrames_MB`).
  bool readsTwice() const { return readsTwice_; }
  /// Frames decoded in all (each pass's reads): the file's frame count when
  /// every frame is decoded once.
  int framesDecoded() const { return decoded_; }

 private:
  std::optional<rawlog::RgbdFrame> read();

  std::string path_;
  Options options_;
  std::unique_ptr<rawlog::RawlogReader> reader_;
  std::deque<rawlog::RgbdFrame> kept_;  ///< previewed frames, for next()
  double keptBytes_ = 0.0;
  int previewed_ = 0, decoded_ = 0;
  bool previewDone_ = false, previewedToEnd_ = false, readerEnded_ = false, readsTwice_ = false;
};

}  // namespace srp::perception
