#pragma once
/// \file PreviewRawlog.h
/// \brief The preview pass over a recorded demo: every frame of a rawlog
/// shown to DemoPerceiver::preview() before the perception pass.

#include <functional>
#include <optional>
#include <string>

#include "srp/core/CameraIntrinsics.h"
#include "srp/perception/DemoPerception.h"

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

}  // namespace srp::perception
