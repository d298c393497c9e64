// Issue 21: a damaged rawlog is an error naming the frame and the byte, never
// a shorter recording, a huge allocation or garbage in a message; and a fuzz
// test: thousands of seeded single-byte mutations and truncations of a small
// rawlog each read either the exact original frames or an error naming the damage.
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>
#include <zlib.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>

#include "srp/core/Error.h"
#include "srp/rawlog/RawlogReader.h"
#include "srp/rawlog/RawlogWriter.h"
#include "TestFrames.h"

using namespace srp::rawlog;

namespace {
const srp::core::CameraIntrinsics kSmallK{40.0, 41.0, 15.5, 11.5, 32, 24};
constexpr double kUnit_m = 1e-3;

RgbdFrame smallFrame(int i) {
  return srp::rawlog::testing::testFrame(i, kSmallK, 99 + i, [i](int r, int c) { return 0.5f + 0.01f * ((r * 7 + c * 3 + i) % 50); });
}

std::string tempPath(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("srp_rawlog_damage_" + std::to_string(getpid()) + "_" + name))
      .string();
}

std::string bytesOf(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}
void writeBytes(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary | std::ios::trunc).write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

/// Writes `frames` small frames; returns the file offset where each gzip member ends.
std::vector<std::uint64_t> writeSmall(const std::string& path, int frames, int level = 1) {
  std::vector<std::uint64_t> ends;
  RawlogWriter writer(path, kUnit_m, level);
  ends.push_back(writer.bytesWritten());  // the start marker
  for (int i = 0; i < frames; ++i) {
    writer.write(smallFrame(i));
    ends.push_back(writer.bytesWritten());
  }
  writer.close();
  return ends;
}

/// The decompressed (plain) rawlog: MRPT reads plain rawlogs too, without any CRC.
std::string gunzip(const std::string& path) {
  gzFile g = gzopen(path.c_str(), "rb");
  std::string out;
  char buf[65536];
  int n = 0;
  while ((n = gzread(g, buf, sizeof buf)) > 0) out.append(buf, static_cast<std::size_t>(n));
  gzclose(g);
  return out;
}

struct ReadOutcome {
  std::vector<RgbdFrame> frames;
  std::optional<std::string> damage;
  std::optional<std::string> thrown;
};

ReadOutcome readAllFrames(const std::string& path) {
  ReadOutcome r;
  try {
    RawlogReader reader(path, 0);
    while (auto f = reader.next()) r.frames.push_back(std::move(*f));
    r.damage = reader.damage();
  } catch (const std::exception& e) {
    r.thrown = e.what();
  }
  return r;
}

bool sameFrame(const RgbdFrame& a, const RgbdFrame& b) {
  return a.index == b.index && a.t_s == b.t_s && a.intrinsics.width_px == b.intrinsics.width_px &&
         a.intrinsics.height_px == b.intrinsics.height_px && a.intrinsics.fx_px == b.intrinsics.fx_px &&
         a.intrinsics.fy_px == b.intrinsics.fy_px && a.intrinsics.cx_px == b.intrinsics.cx_px &&
         a.intrinsics.cy_px == b.intrinsics.cy_px && a.colour_bgr8.size() == b.colour_bgr8.size() &&
         cv::norm(a.colour_bgr8, b.colour_bgr8, cv::NORM_INF) == 0.0 && a.depth_m.size() == b.depth_m.size() &&
         cv::norm(a.depth_m, b.depth_m, cv::NORM_INF) == 0.0;
}

bool allPrintable(const std::string& s) {
  for (const char c : s)
    if (c < 32 || c >= 127) return false;
  return true;
}

// The message of a damaged read must name the frame and the byte offset.
bool namesTheDamage(const std::string& m) {
  return m.find("damaged after frame ") != std::string::npos && m.find(" at byte ") != std::string::npos &&
         allPrintable(m);
}
}  // namespace

TEST(RawlogDamage, FlippedSizeFieldIsAnErrorBeforeAnyAllocation) {
  // The issue: one flipped byte in a frame's size field made MRPT allocate
  // ~4 GB and the reader end "cleanly" after the frames before it.
  const std::string gz = tempPath("flip.rawlog"), plain = tempPath("flip_plain.rawlog");
  writeSmall(gz, 5);
  std::string bytes = gunzip(gz);
  // Depth unit 0.001f, rows = 24, cols = 32 (little endian): the depth size
  // field of each frame (the cameras' nrows/ncols carry the same numbers).
  const std::string field("\x6f\x12\x83\x3a\x18\0\0\0\x20\0\0\0", 12);
  std::size_t at = 0;
  for (int k = 0; k < 3; ++k) at = bytes.find(field, k == 0 ? 0 : at + 1);  // the third frame's
  ASSERT_NE(at, std::string::npos);
  bytes[at + 7] = '\x40';  // rows = 0x40000018: 2 GB of depth
  writeBytes(plain, bytes);
  rlimit old{};
  getrlimit(RLIMIT_AS, &old);
  const ReadOutcome r = readAllFrames(plain);
  ASSERT_FALSE(r.thrown) << *r.thrown;
  EXPECT_EQ(r.frames.size(), 2u);
  ASSERT_TRUE(r.damage);
  EXPECT_TRUE(namesTheDamage(*r.damage)) << *r.damage;
  EXPECT_NE(r.damage->find("frame 2"), std::string::npos) << *r.damage;
  EXPECT_NE(r.damage->find("depth image height"), std::string::npos) << *r.damage;
  EXPECT_THROW(RawlogReader::readAll(plain), srp::core::FileError);

  // The same flip in the compressed file is caught by the frame's gzip CRC.
  std::string compressed = bytesOf(gz);
  compressed[compressed.size() / 2] ^= 0x01;
  writeBytes(gz, compressed);
  const ReadOutcome c = readAllFrames(gz);
  ASSERT_TRUE(c.damage);
  EXPECT_TRUE(namesTheDamage(*c.damage)) << *c.damage;
  EXPECT_LT(c.frames.size(), 5u);
  std::filesystem::remove(gz);
  std::filesystem::remove(plain);
}

TEST(RawlogDamage, FileCutAtAFrameBoundaryIsTruncatedNotShorter) {
  const std::string path = tempPath("cut.rawlog");
  const auto ends = writeSmall(path, 6);
  ASSERT_EQ(readAllFrames(path).frames.size(), 6u);
  ASSERT_FALSE(readAllFrames(path).damage);
  std::filesystem::resize_file(path, ends[4]);  // after the 4th frame's member, exactly
  const ReadOutcome r = readAllFrames(path);
  EXPECT_EQ(r.frames.size(), 4u);
  ASSERT_TRUE(r.damage);
  EXPECT_TRUE(namesTheDamage(*r.damage)) << *r.damage;
  EXPECT_NE(r.damage->find("end marker"), std::string::npos) << *r.damage;
  std::filesystem::remove(path);
}

TEST(RawlogDamage, AMissingFrameIsCaughtByTheEndMarkersCount) {
  const std::string path = tempPath("gap.rawlog");
  const auto ends = writeSmall(path, 5);
  std::string bytes = bytesOf(path);
  bytes.erase(ends[2], ends[3] - ends[2]);  // the third frame's member, cleanly cut out
  writeBytes(path, bytes);
  const ReadOutcome r = readAllFrames(path);
  EXPECT_EQ(r.frames.size(), 4u);
  ASSERT_TRUE(r.damage);
  EXPECT_NE(r.damage->find("end marker counts 5 frames but 4 were read"), std::string::npos) << *r.damage;
  std::filesystem::remove(path);
}

TEST(RawlogDamage, GarbageAndTinyFilesGiveCleanMessages) {
  const std::string path = tempPath("tiny.rawlog");
  // 100 bytes of a plain rawlog (the valgrind case), 100 random bytes,
  // and a header whose class name is binary.
  const std::string full = tempPath("full.rawlog");
  writeSmall(full, 2);
  std::mt19937 rng(5);
  std::string random(100, '\0');
  for (auto& c : random) c = static_cast<char>(rng());
  std::string binaryName = "\x85\x01\x02\xff\xfe\x07";
  binaryName += std::string(94, '\x11');
  for (const std::string& bytes : {gunzip(full).substr(0, 100), bytesOf(full).substr(0, 100), random, binaryName}) {
    writeBytes(path, bytes);
    std::string message;
    try {
      RawlogReader::readAll(path);
    } catch (const srp::core::Error& e) {
      message = e.what();
    }
    EXPECT_FALSE(message.empty());
    EXPECT_TRUE(allPrintable(message)) << message;
    EXPECT_LT(message.size(), 600u) << message;
  }
  std::filesystem::remove(path);
  std::filesystem::remove(full);
}

// ---- The fuzz test ----

namespace {
struct FuzzStats {
  int cases = 0, exact = 0, damaged = 0, failures = 0;
  std::string firstFailure;
};

// Every mutation of `original` (written to `path`) must read the exact
// original frames or report damage naming it (`strict`: CRC-protected data);
// for plain rawlogs (no CRC: a flipped pixel is a valid picture) only no
// crash, no exception but srp's errors, and a clean message.
void fuzzOne(const std::string& path, const std::string& mutated, const std::vector<RgbdFrame>& truth, bool strict,
             FuzzStats& s, const std::string& what) {
  writeBytes(path, mutated);
  if (std::getenv("SRP_FUZZ_VERBOSE")) std::fprintf(stderr, "%s\n", what.c_str());
  const ReadOutcome r = readAllFrames(path);
  ++s.cases;
  std::string problem;
  if (r.thrown) {
    problem = "threw: " + *r.thrown;
  } else if (r.damage) {
    ++s.damaged;
    if (!namesTheDamage(*r.damage)) problem = "damage message does not name frame and byte: " + *r.damage;
    for (std::size_t i = 0; i < r.frames.size() && strict && problem.empty(); ++i)
      if (i >= truth.size() || !sameFrame(r.frames[i], truth[i])) problem = "frame before the damage differs";
  } else if (strict) {
    bool same = r.frames.size() == truth.size();
    for (std::size_t i = 0; same && i < truth.size(); ++i) same = sameFrame(r.frames[i], truth[i]);
    if (same) ++s.exact;
    else problem = "read " + std::to_string(r.frames.size()) + " frames without an error, not the original";
  } else {
    ++s.exact;
  }
  if (!problem.empty()) {
    ++s.failures;
    if (s.firstFailure.empty()) s.firstFailure = what + ": " + problem;
  }
}
}  // namespace

TEST(RawlogFuzz, MutationsAndTruncationsReadExactlyOrNameTheDamage) {
  constexpr int kMutations = 2000, kTruncations = 300, kPlainMutations = 600;
  constexpr long kMemoryLimit_B = 1L << 30;  // 1 GB of address space for the reading child
  const std::string original = tempPath("fuzz_original.rawlog");
  writeSmall(original, 3);
  const std::string gz = bytesOf(original), plain = gunzip(original);
  const auto truth = readAllFrames(original).frames;
  ASSERT_EQ(truth.size(), 3u);

  // The reading runs in a child under an address-space limit: a damaged size
  // field that made the reader allocate gigabytes fails the child, not the machine.
  int fd[2];
  ASSERT_EQ(pipe(fd), 0);
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    close(fd[0]);
#if !defined(__SANITIZE_ADDRESS__)
    const rlimit limit{static_cast<rlim_t>(kMemoryLimit_B), static_cast<rlim_t>(kMemoryLimit_B)};
    setrlimit(RLIMIT_AS, &limit);
#endif
    FuzzStats gzStats, plainStats;
    const std::string path = tempPath("fuzz_case.rawlog");
    std::mt19937 rng(20261124);
    for (int i = 0; i < kMutations; ++i) {
      std::string m = gz;
      const std::size_t at = rng() % m.size();
      m[at] = static_cast<char>(m[at] ^ static_cast<char>(1 + rng() % 255));
      fuzzOne(path, m, truth, true, gzStats, "gzip byte " + std::to_string(at));
    }
    for (int i = 0; i < kTruncations; ++i) {
      const std::size_t keep = rng() % gz.size();
      fuzzOne(path, gz.substr(0, keep), truth, true, gzStats, "gzip cut at " + std::to_string(keep));
    }
    for (int i = 0; i < kPlainMutations; ++i) {
      std::string m = plain;
      const std::size_t at = rng() % m.size();
      m[at] = static_cast<char>(m[at] ^ static_cast<char>(1 + rng() % 255));
      fuzzOne(path, m, truth, false, plainStats, "plain byte " + std::to_string(at));
    }
    std::filesystem::remove(path);
    const std::string report = std::to_string(gzStats.cases) + " " + std::to_string(gzStats.exact) + " " +
                               std::to_string(gzStats.damaged) + " " + std::to_string(gzStats.failures) + " " +
                               std::to_string(plainStats.cases) + " " + std::to_string(plainStats.failures) + "\n" +
                               gzStats.firstFailure + "\n" + plainStats.firstFailure + "\n";
    if (write(fd[1], report.data(), report.size()) != static_cast<ssize_t>(report.size())) _exit(3);
    _exit(0);
  }
  close(fd[1]);
  std::string report;
  char buf[4096];
  ssize_t n = 0;
  while ((n = read(fd[0], buf, sizeof buf)) > 0) report.append(buf, static_cast<std::size_t>(n));
  close(fd[0]);
  int status = 0;
  waitpid(child, &status, 0);
  std::filesystem::remove(original);
  ASSERT_TRUE(WIFEXITED(status)) << "the reading child crashed (signal " << WTERMSIG(status) << ")";
  ASSERT_EQ(WEXITSTATUS(status), 0);
  std::istringstream in(report);
  int cases = 0, exact = 0, damaged = 0, failures = 0, plainCases = 0, plainFailures = 0;
  in >> cases >> exact >> damaged >> failures >> plainCases >> plainFailures;
  std::string firstGz, firstPlain;
  std::getline(in, firstGz);
  std::getline(in, firstGz);
  std::getline(in, firstPlain);
  EXPECT_EQ(cases, kMutations + kTruncations);
  EXPECT_EQ(failures, 0) << firstGz;
  EXPECT_EQ(plainCases, kPlainMutations);
  EXPECT_EQ(plainFailures, 0) << firstPlain;
  EXPECT_GT(damaged, kMutations / 2) << "most flips must be caught";
  std::cout << "[ fuzz ] gzip: " << cases << " cases, " << exact << " exact, " << damaged << " damage reported; plain: "
            << plainCases << " cases\n";
  rusage usage{};
  getrusage(RUSAGE_CHILDREN, &usage);
  EXPECT_LT(usage.ru_maxrss * 1024L, kMemoryLimit_B) << "peak memory of the reading child";
}
