#pragma once
// The byte layer under RawlogReader (private to rawlog): a gzip (or plain)
// rawlog as an MRPT input stream that knows where it is in the file, decodes
// whole gzip members (CRC32-checked by zlib) before MRPT sees their bytes, and
// checks each object's header and sizes before MRPT allocates for them.
#include <mrpt/io/CStream.h>
#include <zlib.h>

#include <libdeflate.h>

#include <cstdint>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

namespace srp::rawlog::detail {

/// Text of the CObservationComment srp writes first ("this file ends with an end marker").
inline constexpr const char* kStartMarker = "srp-rawlog v2: RGB-D frames, then an end marker with their count";
/// Text prefix of the CObservationComment srp writes last, followed by the frame count.
inline constexpr const char* kEndMarker = "srp-rawlog end: frames=";

/// Largest image side and point count a frame may declare (sane bounds checked before allocation).
inline constexpr std::uint32_t kMaxImageSide_px = 16384;
inline constexpr std::uint64_t kMaxPoints = std::uint64_t(1) << 27;

class RawlogSource : public mrpt::io::CStream {
 public:
  /// Opens the file; throws FileError naming it when it cannot.
  explicit RawlogSource(const std::string& path);
  ~RawlogSource() override;
  RawlogSource(const RawlogSource&) = delete;
  RawlogSource& operator=(const RawlogSource&) = delete;

  size_t Read(void* buffer, size_t count) override;
  size_t Write(const void*, size_t) override;
  uint64_t Seek(int64_t, CStream::TSeekOrigin) override;
  uint64_t getTotalBytesCount() const override { return 0; }
  /// Bytes of (decompressed) rawlog data consumed so far.
  uint64_t getPosition() const override { return consumed_; }

  /// Decodes ahead until `bytes` are available or the current gzip member
  /// (plain file: the file) ends; then available() bytes are checked data.
  void prefetch(std::size_t bytes);
  std::size_t available() const { return len_ - pos_; }
  const std::uint8_t* peek() const { return buf_.data() + pos_; }
  /// True when available() is all that is left of the current member/file.
  bool bounded() const { return memberEnded_; }
  /// Set when the bytes cannot be decoded (truncated, corrupt gzip data, CRC mismatch).
  const std::optional<std::string>& error() const { return error_; }
  /// Byte offset in the file of the gzip member holding the next byte (plain: of the next byte).
  uint64_t fileOffset() const { return gzip_ ? memberStart_ : consumed_; }
  bool gzip() const { return gzip_; }

 private:
  bool decodeMore(bool crossMembers);
  bool decodeWholeMember();
  bool readInput();
  void reserveInput(std::size_t bytes);

  std::string path_;
  std::FILE* file_ = nullptr;
  bool gzip_ = false;
  z_stream z_{};
  bool zInit_ = false;
  // Whole members (srp's one-frame members) decode in one libdeflate call,
  // 2-3x faster than zlib's stream; zlib decodes what does not fit
  // (MRPT's one-member files) and reports damage.
  libdeflate_decompressor* whole_ = nullptr;
  bool memberFresh_ = false;  // zlib has read nothing of the current member yet
  std::size_t lastMemberIn_ = 0, lastMemberOut_ = 0;
  std::vector<std::uint8_t> in_, buf_;
  std::size_t pos_ = 0, len_ = 0;
  uint64_t consumed_ = 0, fileRead_ = 0, memberStart_ = 0;
  bool memberEnded_ = false, fileEnded_ = false, done_ = false;
  std::optional<std::string> error_;
};

/// Checks the header of the object at `p` (class name readable and
/// registered) and, for the RGB-D scans and images srp reads, the sizes the
/// object declares against sane bounds and against the `n` bytes available
/// (when `bounded`, the object must fit in them). Returns the problem, or
/// nullopt when the object may be handed to MRPT.
std::optional<std::string> prescanObject(const std::uint8_t* p, std::size_t n, bool bounded);

/// Printable ASCII of `text`, at most `max` characters (for messages).
std::string printable(const std::string& text, std::size_t max = 200);

}  // namespace srp::rawlog::detail
