// Outputs that cannot destroy inputs or be left half-written, and small files
// that must not become huge allocations:
// - a full disk at every byte of a URScript + ROS 2 YAML export
//   (core::injectOutputWriteFailureAfter): both files the previous ones, or both
//   the new ones, never one of each, never a truncated file;
// - a process killed at random moments while it re-exports: every file on disk
//   is a complete program (its `end`, its last YAML point);
// - image headers declaring gigapixels (PNG, JPEG, BMP, PNM, TIFF) are refused
//   before decoding; calibration boards too large to render are refused.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <thread>

#include "ScratchFolder.h"
#include "srp/calib/CalibrationPattern.h"
#include "srp/calib/ImageHeader.h"
#include "srp/core/Error.h"
#include "srp/core/OutputFile.h"

namespace fs = std::filesystem;

namespace {

std::string readFile(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

/// A program-like and a trajectory-like text whose last line proves they are whole.
std::pair<std::string, std::string> exportPair(int version, std::size_t lines) {
  std::string script = "def srp_task():\n  # version " + std::to_string(version) + "\n";
  std::string yaml = "# version " + std::to_string(version) + "\npoints:\n";
  for (std::size_t i = 0; i < lines; ++i) {
    script += "  servoj([0.1, 0.2, 0.3, 0.4, 0.5, 0.6], 0, 0, 0.008, 0.1, 300)\n";
    yaml += "- positions: [0.100000000, 0.200000000, 0.300000000, 0.400000000, 0.500000000, 0.600000000]\n";
  }
  return {script + "end\n", yaml + "# end\n"};
}

/// N of the first "version N" in a text (-1 if none).
int versionOf(const std::string& text) {
  const std::size_t at = text.find("version ");
  return at == std::string::npos ? -1 : std::atoi(text.c_str() + at + 8);
}

using Dir = srp::safety::ScratchFolder;

}  // namespace

TEST(ExportWriteFailure, ScriptAndYamlAreBothOrNeitherAtEveryFailingByte) {
  const Dir dir("disk_full");
  const fs::path script = dir.path / "task.script", yaml = dir.path / "trajectory.yaml";
  const auto [oldScript, oldYaml] = exportPair(1, 20);
  const auto [newScript, newYaml] = exportPair(2, 25);
  srp::core::writeFilesTogether({{script, oldScript}, {yaml, oldYaml}});
  const std::int64_t total = static_cast<std::int64_t>(newScript.size() + newYaml.size());
  int failed = 0, written = 0, mixed = 0;
  std::vector<std::int64_t> budgets;
  for (std::int64_t b = 0; b < total; b += 7) budgets.push_back(b);
  budgets.push_back(total);  // enough for both files: written
  for (const std::int64_t budget : budgets) {
    srp::core::injectOutputWriteFailureAfter(budget);
    try {
      srp::core::writeFilesTogether({{script, newScript}, {yaml, newYaml}});
      ++written;
    } catch (const srp::core::FileError&) {
      ++failed;
    }
    srp::core::injectOutputWriteFailureAfter(-1);
    const std::string s = readFile(script), y = readFile(yaml);
    const bool old = s == oldScript && y == oldYaml, fresh = s == newScript && y == newYaml;
    if (!old && !fresh) ++mixed;
    if (fresh) srp::core::writeFilesTogether({{script, oldScript}, {yaml, oldYaml}});  // back to the old pair
    EXPECT_EQ(std::distance(fs::directory_iterator(dir.path), {}), 2) << "a temporary was left at budget " << budget;
  }
  std::printf("[ sweep ] disk full during an export: %d budgets, %d failed (old pair kept), %d written, %d mixed\n",
              failed + written, failed, written, mixed);
  EXPECT_EQ(mixed, 0);
  EXPECT_GT(failed, 100);
  EXPECT_EQ(written, 1);
}

TEST(ExportKill, AKilledExportLeavesWholeFiles) {
  const Dir dir("kill");
  const fs::path script = dir.path / "task.script", yaml = dir.path / "trajectory.yaml";
  constexpr int kKills = 40;
  std::mt19937 rng(35);
  int whole = 0, broken = 0, pairsOfOneVersion = 0;
  srp::core::writeFilesTogether({{script, exportPair(0, 2000).first}, {yaml, exportPair(0, 2000).second}});
  for (int k = 0; k < kKills; ++k) {
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
      for (int version = 1;; ++version) {
        const auto [s, y] = exportPair(version, 2000);
        srp::core::writeFilesTogether({{script, s}, {yaml, y}});
      }
    }
    std::this_thread::sleep_for(std::chrono::microseconds(2000 + rng() % 30000));
    ::kill(child, SIGKILL);
    ::waitpid(child, nullptr, 0);
    const std::string s = readFile(script), y = readFile(yaml);
    const bool ok = s.size() > 20 && s.compare(s.size() - 4, 4, "end\n") == 0 && y.size() > 10 &&
                    y.compare(y.size() - 6, 6, "# end\n") == 0;
    (ok ? whole : broken)++;
    pairsOfOneVersion += versionOf(s) == versionOf(y);
    for (const auto& e : fs::directory_iterator(dir.path))  // a killed writer's temporaries: never the outputs
      if (e.path().filename().string().rfind(".", 0) == 0) fs::remove(e.path());
  }
  std::printf("[ sweep ] killed during an export: %d kills, %d left whole files, %d broken, %d pairs of one version\n",
              kKills, whole, broken, pairsOfOneVersion);
  EXPECT_EQ(broken, 0);
}

namespace {

std::string pngHeader(std::uint32_t w, std::uint32_t h) {
  std::string b = "\x89PNG\r\n\x1a\n";
  b += std::string("\0\0\0\x0dIHDR", 8);
  for (std::uint32_t v : {w, h})
    for (int s = 24; s >= 0; s -= 8) b += static_cast<char>((v >> s) & 0xFF);
  b += std::string("\x08\x02\0\0\0", 5);
  b += std::string(4, '\0');               // CRC (not checked before decoding)
  b += std::string(2000, '\0');            // a little "compressed" data
  return b;
}

std::string jpegHeader(std::uint16_t w, std::uint16_t h) {
  std::string b = "\xFF\xD8";
  b += std::string("\xFF\xE0\0\x10JFIF\0\x01\x01\0\0\x01\0\x01\0\0", 18);
  b += std::string("\xFF\xC0\0\x11\x08", 5);
  b += static_cast<char>(h >> 8), b += static_cast<char>(h & 0xFF), b += static_cast<char>(w >> 8),
      b += static_cast<char>(w & 0xFF);
  b += std::string("\x03\x01\x22\0\x02\x11\x01\x03\x11\x01", 10);
  return b + std::string(500, '\0');
}

}  // namespace

TEST(DecompressionBombs, ImageHeadersAreCheckedBeforeDecoding) {
  const Dir dir("bombs");
  struct Bomb {
    std::string name, bytes;
    bool refused;
  };
  std::vector<Bomb> bombs = {
      {"huge.png", pngHeader(100000, 100000), true},
      {"wide.png", pngHeader(0x7FFFFFFF, 1), true},
      {"zero.png", pngHeader(0, 480), true},
      {"max.png", pngHeader(0xFFFFFFFF, 0xFFFFFFFF), true},
      {"ok.png", pngHeader(640, 480), false},
      {"huge.jpg", jpegHeader(65535, 65535), true},
      {"ok.jpg", jpegHeader(1280, 720), false},
      {"huge.bmp", std::string("BM") + std::string(16, '\0') + std::string("\xFF\xFF\0\0\xFF\xFF\0\0", 8) + std::string(40, '\0'), true},
      {"huge.pgm", "P5\n# comment\n99999 99999\n255\n" + std::string(100, '\0'), true},
      {"huge.tif", std::string("II*\0\x08\0\0\0\x02\0\0\x01\x04\0\x01\0\0\0\xFF\xFF\0\0\x01\x01\x04\0\x01\0\0\0\xFF\xFF\0\0", 34), true},
      {"unknown.webp", "RIFF\0\0\0\0WEBPVP8 ", true},
      {"empty.png", "", true},
  };
  int refused = 0, accepted = 0;
  for (const auto& b : bombs) {
    const fs::path p = dir.path / b.name;
    std::ofstream(p, std::ios::binary) << b.bytes;
    try {
      srp::calib::checkImageFile(p.string());
      ++accepted;
      EXPECT_FALSE(b.refused) << b.name << " accepted";
    } catch (const srp::core::FileError& e) {
      ++refused;
      EXPECT_TRUE(b.refused) << b.name << " refused: " << e.what();
      EXPECT_NE(std::string(e.what()).find(b.name), std::string::npos) << e.what();
    }
  }
  // Boards: a pattern or a resolution that would render gigapixels is refused.
  int boardsRefused = 0;
  for (const char* spec : {"chessboard:200x200:1.0", "chessboard:9x6:0.025", "apriltag:100x100:0.5:0.1"}) {
    const auto pattern = srp::calib::CalibrationPattern::parse(spec);
    try {
      pattern.renderBoard(4800 / 0.0254, 0.01);
    } catch (const srp::core::InvalidInputError&) {
      ++boardsRefused;
    }
  }
  for (const char* spec : {"chessboard:100000x6:0.025", "chessboard:9x6:1e9", "chessboard:99999999999x6:0.025"})
    EXPECT_THROW(srp::calib::CalibrationPattern::parse(spec), srp::core::InvalidInputError) << spec;
  std::printf("[ sweep ] decompression bombs: %zu image files, %d refused before decoding, %d accepted; %d of 3 boards "
              "at 4800 dpi refused, 3 of 3 oversized patterns refused\n",
              bombs.size(), refused, accepted, boardsRefused);
  EXPECT_EQ(boardsRefused, 3);
}
