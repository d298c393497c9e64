#include "srp/perception/RawlogPerception.h"

#include <string>

#include "srp/core/Error.h"
#include "srp/perception/DemoRawlogReader.h"

namespace srp::perception {

PerceptionResult perceiveRawlog(const std::string& rawlogPath, const core::ObjectCatalogue& catalogue,
                                const PerceptionOptions& options, const std::function<void(int, int)>& progress,
                                const FrameHook& onFrame) {
  DemoPerceiver perceiver(catalogue, options);
  // The marker-free hand learns from the whole recording before its first
  // detection: a preview pass, whose frames the perception pass then takes
  // (DemoRawlogReader). Otherwise a stream: one frame at a time.
  DemoRawlogReader reader(rawlogPath);
  if (perceiver.wantsPreview()) reader.preview(perceiver);
  const int frameCount = reader.previewedWholeFile() ? reader.framesPreviewed() : -1;
  while (auto f = reader.next()) {
    perceiver.add(*f);
    if (onFrame) onFrame(*f, perceiver.framesAdded() - 1);
    if (progress) progress(perceiver.framesAdded() - 1, frameCount);
  }
  if (reader.damage()) throw core::FileError(rawlogPath, "unreadable rawlog, " + *reader.damage());
  if (perceiver.framesAdded() == 0)
    throw core::FileError(rawlogPath, "no RGB-D frames with depth in this rawlog (" +
                                          std::to_string(reader.objectsSkipped()) +
                                          " other objects skipped): record CObservation3DRangeScan with depth");
  if (frameCount >= 0 && perceiver.framesAdded() != frameCount)
    throw core::FileError(rawlogPath, "the rawlog changed between the preview and the perception pass (" +
                                          std::to_string(frameCount) + " then " +
                                          std::to_string(perceiver.framesAdded()) + " frames)");
  return perceiver.finish();
}

}  // namespace srp::perception
