#pragma once
/// \file RawlogPerception.h
/// \brief The Environment module on a recorded demo (an MRPT rawlog): the
/// preview pass (every frame shown to DemoPerceiver::preview()) and the whole
/// module read from the file (perceiveRawlog), as `srp perceive` and
/// `srp program` run it.

#include <functional>
#include <optional>
#include <string>

#include "srp/core/CameraIntrinsics.h"
#include "srp/perception/DemoPerception.h"
#include "srp/rawlog/RgbdFrame.h"

namespace srp::perception {

/// Reads the rawlog at `rawlogPath` (RawlogReader) and shows each RGB-D frame,
/// in order, to `perceiver.preview()`; returns how many it showed. The
/// marker-free hand learns its background and skin colour from the whole
/// recording (a demonstrator may be in view from the first frame), so a
/// caller previews, then reads the rawlog a second time for DemoPerceiver::add():
/// holding the frames instead would cost ~1.5 MB per 640x480 frame (a minute
/// at 30 Hz: ~2.7 GB), reading twice ~3 % of the perception time.
///
/// `intrinsics`, when given, replace every frame's (as the caller's
/// perception pass must do too). `progress(framesPreviewed)` is called after
/// each frame when given. Reading stops at a damaged object without an error:
/// the perception pass reads the same frames and reports the damage as its
/// caller decides (perceiveRawlog throws; `srp program --allow-truncated`
/// uses the frames before it). Throws FileError when the file is missing or
/// unreadable, and what DemoPerceiver::preview throws.
int previewRawlog(DemoPerceiver& perceiver, const std::string& rawlogPath,
                  const std::optional<core::CameraIntrinsics>& intrinsics = std::nullopt,
                  const std::function<void(int)>& progress = {});

/// Called with each frame of the perception pass, after DemoPerceiver::add(),
/// and its index (0-based): a study scores its own detector on the frames the
/// module perceives, without reading the rawlog again.
using FrameHook = std::function<void(const rawlog::RgbdFrame& frame, int frameIndex)>;

/// Reads the demo rawlog (RawlogReader) and runs it as perceiveFrames: the
/// Environment module as `srp perceive` runs it. With the marker-free hand the
/// file is read twice (previewRawlog over the whole recording, then
/// perception) so memory stays flat on long demos; otherwise frames are
/// perceived as they are read. `progress(frameIndex, frameCount)` and
/// `onFrame` are called after each frame of the perception pass when given.
/// Throws FileError for an unreadable or damaged rawlog, one without RGB-D
/// frames, or one that changes between the two reads.
PerceptionResult perceiveRawlog(const std::string& rawlogPath, const core::ObjectCatalogue& catalogue,
                                const PerceptionOptions& options, const std::function<void(int, int)>& progress = {},
                                const FrameHook& onFrame = {});

}  // namespace srp::perception
