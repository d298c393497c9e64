#pragma once
/// \file ProgressLine.h
/// \brief The one progress reporter of the srp commands: a line on stderr,
/// redrawn in place ("\r<label> [#####-----]  50% 5/10 <detail>", or
/// "\r<label> 5 <detail>" when the total is unknown), ended with a newline by
/// finish() or the destructor. A new label starts a new line (a new stage).
///
/// \code
///   ProgressLine line(progressWanted(json));  // CommonOptions.h: a terminal, no -q, no --json
///   for (int k = 0; k < n; ++k) line.show("synth-demo: frame", k + 1, n);
///   line.finish();
/// \endcode

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>

namespace srp::app {

class ProgressLine {
 public:
  /// `enabled` false: silent (--quiet, --json). `minInterval`: redraws of
  /// one label closer together than this are skipped, except the last (done == total).
  explicit ProgressLine(bool enabled, std::chrono::milliseconds minInterval = std::chrono::milliseconds(0))
      : enabled_(enabled), minInterval_(minInterval) {}
  ProgressLine(const ProgressLine&) = delete;
  ProgressLine& operator=(const ProgressLine&) = delete;
  ~ProgressLine() { finish(); }

  /// Draws `done` of `total` (0: unknown) under `label`, with an optional detail.
  void show(const std::string& label, std::size_t done, std::size_t total = 0, const std::string& detail = "") {
    if (!enabled_) return;
    const auto now = std::chrono::steady_clock::now();
    if (open_ && label == label_ && now - last_ < minInterval_ && done != total) return;
    if (open_ && label != label_) std::fputc('\n', stderr);
    label_ = label;
    last_ = now;
    std::string text = label;
    if (total > 0) {
      const std::size_t width = 30, filled = std::min(width, width * done / total);
      text += " [" + std::string(filled, '#') + std::string(width - filled, '-') + "] ";
      const std::string percent = std::to_string(100 * done / total);
      text += std::string(percent.size() < 3 ? 3 - percent.size() : 0, ' ') + percent + "% " + std::to_string(done) +
              "/" + std::to_string(total);
    } else {
      text += " " + std::to_string(done);
    }
    if (!detail.empty()) text += " " + detail;
    draw(text);
  }

  /// Ends the line; a non-empty `text` is drawn over it first (a summary).
  void finish(const std::string& text = "") {
    if (!enabled_) return;
    if (!text.empty()) draw(text);
    if (open_) std::fputc('\n', stderr);
    std::fflush(stderr);
    open_ = false;
  }

 private:
  void draw(const std::string& text) {
    // Padded to the previous line's length so that no old character stays.
    std::fprintf(stderr, "\r%s%s", text.c_str(), std::string(drawn_ > text.size() ? drawn_ - text.size() : 0, ' ').c_str());
    std::fflush(stderr);
    drawn_ = text.size();
    open_ = true;
  }

  bool enabled_;
  std::chrono::milliseconds minInterval_;
  std::string label_;
  std::chrono::steady_clock::time_point last_;
  std::size_t drawn_ = 0;
  bool open_ = false;
};

}  // namespace srp::app
