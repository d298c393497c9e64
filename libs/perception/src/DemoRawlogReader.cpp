#include "srp/perception/DemoRawlogReader.h"

#include <filesystem>
#include <system_error>
#include <utility>

#include "srp/core/Error.h"

namespace srp::perception {

namespace {

double bytesOf(const rawlog::RgbdFrame& f) {
  return static_cast<double>(f.colour_bgr8.total() * f.colour_bgr8.elemSize() +
                             f.depth_m.total() * f.depth_m.elemSize());
}

}  // namespace

DemoRawlogReader::DemoRawlogReader(const std::string& path) : DemoRawlogReader(path, Options{}) {}

DemoRawlogReader::DemoRawlogReader(const std::string& path, const Options& options)
    : path_(path), options_(options), reader_(std::make_unique<rawlog::RawlogReader>(path)) {}

DemoRawlogReader::~DemoRawlogReader() = default;

std::optional<rawlog::RgbdFrame> DemoRawlogReader::read() {
  if (readerEnded_) return std::nullopt;
  auto f = reader_->next();
  if (!f) {
    readerEnded_ = true;
    return std::nullopt;
  }
  ++decoded_;
  if (options_.intrinsics) f->intrinsics = *options_.intrinsics;
  return f;
}

int DemoRawlogReader::preview(DemoPerceiver& perceiver, const std::function<void(int)>& progress) {
  core::require(!previewDone_ && decoded_ == 0,
                "DemoRawlogReader::preview: call it once, before the first next() (" + path_ + ")");
  previewDone_ = true;
  // A file larger than the budget cannot fit once decoded (a frame decodes to
  // more bytes than its gzip member holds): nothing is kept.
  const double budget = 1e6 * options_.keptFrames_MB;
  std::error_code ec;
  const auto fileBytes = std::filesystem::file_size(path_, ec);
  bool keep = budget > 0.0 && !ec && static_cast<double>(fileBytes) <= budget;
  while (!perceiver.previewComplete()) {
    auto f = read();
    if (!f) {
      previewedToEnd_ = true;
      break;
    }
    perceiver.preview(*f);
    ++previewed_;
    if (keep && keptBytes_ + bytesOf(*f) <= budget) {
      keptBytes_ += bytesOf(*f);
      kept_.push_back(std::move(*f));
    } else if (keep) {  // over the budget: none kept, the perception pass reads the file again
      keep = false;
      kept_.clear();
      keptBytes_ = 0.0;
    }
    if (progress) progress(previewed_);
  }
  if (previewed_ > 0 && !keep) {
    readsTwice_ = true;
    reader_ = std::make_unique<rawlog::RawlogReader>(path_);
    readerEnded_ = false;
  }
  return previewed_;
}

std::optional<rawlog::RgbdFrame> DemoRawlogReader::next() {
  previewDone_ = true;
  if (!kept_.empty()) {
    rawlog::RgbdFrame f = std::move(kept_.front());
    kept_.pop_front();
    return f;
  }
  return read();
}

}  // namespace srp::perception
