#pragma once
/// \file RawlogPerception.h
/// \brief The Environment module on a recorded demo (an MRPT rawlog) read
/// from the file (perceiveRawlog), as `srp perceive` runs it.

#include <functional>
#include <string>

#include "srp/perception/DemoPerception.h"
#include "srp/rawlog/RgbdFrame.h"

namespace srp::perception {

/// Called with each frame of the perception pass, after DemoPerceiver::add(),
/// and its index (0-based): a study scores its own detector on the frames the
/// module perceives, without reading the rawlog again.
using FrameHook = std::function<void(const rawlog::RgbdFrame& frame, int frameIndex)>;

/// Reads the demo rawlog (DemoRawlogReader) and runs it as perceiveFrames: the
/// Environment module as `srp perceive` runs it. With the marker-free hand
/// the preview pass goes over the whole recording and the perception pass
/// takes its frames (each frame decoded once; a recording over
/// DemoRawlogReader::Options::keptFrames_MB is read twice so memory stays
/// flat); otherwise frames are perceived as they are read.
/// `progress(frameIndex, frameCount)` and `onFrame` are called after each
/// frame of the perception pass when given (frameCount -1 until known).
/// Throws FileError for an unreadable or damaged rawlog, one without RGB-D
/// frames, or one that changes between two reads.
PerceptionResult perceiveRawlog(const std::string& rawlogPath, const core::ObjectCatalogue& catalogue,
                                const PerceptionOptions& options, const std::function<void(int, int)>& progress = {},
                                const FrameHook& onFrame = {});

}  // namespace srp::perception
