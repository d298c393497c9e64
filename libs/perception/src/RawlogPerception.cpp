#include "srp/perception/RawlogPerception.h"

#include <string>

#include "srp/core/Error.h"
#include "srp/rawlog/RawlogReader.h"

namespace srp::perception {

int previewRawlog(DemoPerceiver& perceiver, const std::string& rawlogPath,
                  const std::optional<core::CameraIntrinsics>& intrinsics, const std::function<void(int)>& progress) {
  rawlog::RawlogReader reader(rawlogPath);
  int previewed = 0;
  while (!perceiver.previewComplete()) {
    auto f = reader.next();
    if (!f) break;
    if (intrinsics) f->intrinsics = *intrinsics;
    perceiver.preview(*f);
    ++previewed;
    if (progress) progress(previewed);
  }
  return previewed;
}

PerceptionResult perceiveRawlog(const std::string& rawlogPath, const core::ObjectCatalogue& catalogue,
                                const PerceptionOptions& options, const std::function<void(int, int)>& progress,
                                const FrameHook& onFrame) {
  DemoPerceiver perceiver(catalogue, options);
  // The marker-free hand learns from the whole recording before its first
  // detection: a preview pass (previewRawlog), then the perception pass over a
  // second read. Otherwise a stream: one frame at a time.
  const bool preview = perceiver.wantsPreview();
  const int previewed = preview ? previewRawlog(perceiver, rawlogPath) : -1;
  const bool wholePreview = preview && !perceiver.previewComplete();  // not stopped early
  rawlog::RawlogReader reader(rawlogPath);
  while (auto f = reader.next()) {
    perceiver.add(*f);
    if (onFrame) onFrame(*f, perceiver.framesAdded() - 1);
    if (progress) progress(perceiver.framesAdded() - 1, wholePreview ? previewed : -1);
  }
  if (reader.damage()) throw core::FileError(rawlogPath, "unreadable rawlog, " + *reader.damage());
  if (perceiver.framesAdded() == 0)
    throw core::FileError(rawlogPath, "no RGB-D frames with depth in this rawlog (" +
                                          std::to_string(reader.objectsSkipped()) +
                                          " other objects skipped): record CObservation3DRangeScan with depth");
  if (wholePreview && perceiver.framesAdded() != previewed)
    throw core::FileError(rawlogPath, "the rawlog changed between the preview and the perception pass (" +
                                          std::to_string(previewed) + " then " +
                                          std::to_string(perceiver.framesAdded()) + " frames)");
  return perceiver.finish();
}

}  // namespace srp::perception
