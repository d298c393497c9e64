#include "srp/perception/PreviewRawlog.h"

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

}  // namespace srp::perception
