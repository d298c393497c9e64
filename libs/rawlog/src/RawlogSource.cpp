#include "RawlogSource.h"

#include <mrpt/rtti/CObject.h>

#include <algorithm>
#include <cmath>
#include <cstring>

#include "srp/core/Error.h"

namespace srp::rawlog::detail {

namespace {
constexpr std::size_t kInputChunk = 1 << 18;
constexpr std::size_t kOutputChunk = 1 << 20;
// Largest gzip member (compressed or decoded) decoded whole; a 1280x720 RGB-D
// frame is ~5 MB decoded.
constexpr std::size_t kMaxWholeMember = std::size_t(16) << 20;
}  // namespace

std::string printable(const std::string& text, std::size_t max) {
  std::string out;
  for (const char c : text) {
    if (out.size() >= max) {
      out += "...";
      break;
    }
    out += (c >= 32 && c < 127) ? c : '?';
  }
  return out;
}

RawlogSource::RawlogSource(const std::string& path) : path_(path) {
  file_ = std::fopen(path.c_str(), "rb");
  if (!file_) throw core::FileError(path, "cannot open rawlog (permissions?)");
  in_.resize(kInputChunk);
  const std::size_t n = std::fread(in_.data(), 1, 2, file_);
  fileRead_ = n;
  gzip_ = n == 2 && in_[0] == 0x1f && in_[1] == 0x8b;
  if (gzip_) {
    if (inflateInit2(&z_, 15 + 16) != Z_OK) throw core::Error("rawlog: zlib initialisation failed");
    zInit_ = true;
    z_.next_in = in_.data();
    z_.avail_in = static_cast<uInt>(n);
    whole_ = libdeflate_alloc_decompressor();
    memberFresh_ = whole_ != nullptr;
  } else {
    buf_.assign(in_.begin(), in_.begin() + static_cast<std::ptrdiff_t>(n));
    len_ = n;
  }
}

RawlogSource::~RawlogSource() {
  if (zInit_) inflateEnd(&z_);
  if (whole_) libdeflate_free_decompressor(whole_);
  if (file_) std::fclose(file_);
}

size_t RawlogSource::Write(const void*, size_t) { throw core::Error("RawlogSource is read-only"); }
uint64_t RawlogSource::Seek(int64_t, CStream::TSeekOrigin) { throw core::Error("RawlogSource cannot seek"); }

bool RawlogSource::readInput() {
  if (fileEnded_) return false;
  // Keep the unread input at the front.
  if (z_.avail_in > 0 && z_.next_in != in_.data()) std::memmove(in_.data(), z_.next_in, z_.avail_in);
  z_.next_in = in_.data();  // also when nothing more comes: the input moved
  const std::size_t n = std::fread(in_.data() + z_.avail_in, 1, in_.size() - z_.avail_in, file_);
  if (n == 0) {
    fileEnded_ = true;
    return false;
  }
  fileRead_ += n;
  z_.next_in = in_.data();
  z_.avail_in += static_cast<uInt>(n);
  return true;
}

void RawlogSource::reserveInput(std::size_t bytes) {
  if (in_.size() >= bytes) return;
  if (z_.avail_in > 0 && z_.next_in != in_.data()) std::memmove(in_.data(), z_.next_in, z_.avail_in);
  in_.resize(bytes);
  z_.next_in = in_.data();
}

// The current member decoded in one call when it (compressed and decoded)
// fits in kMaxWholeMember; false leaves the member to zlib's stream, from its
// start (too large, or damaged: zlib then says how).
bool RawlogSource::decodeWholeMember() {
  memberFresh_ = false;
  std::size_t wantIn = std::max(kInputChunk, 2 * lastMemberIn_);
  std::size_t room = std::max(kOutputChunk, lastMemberOut_ + lastMemberOut_ / 4);
  while (wantIn <= kMaxWholeMember && room <= kMaxWholeMember) {
    reserveInput(wantIn);
    while (z_.avail_in < wantIn && readInput()) {
    }
    if (buf_.size() < len_ + room) buf_.resize(len_ + room);
    std::size_t used = 0, made = 0;
    const libdeflate_result r =
        libdeflate_gzip_decompress_ex(whole_, z_.next_in, z_.avail_in, buf_.data() + len_, room, &used, &made);
    if (r == LIBDEFLATE_SUCCESS) {  // libdeflate checked the member's CRC32 and length
      z_.next_in += used;
      z_.avail_in -= static_cast<uInt>(used);
      len_ += made;
      lastMemberIn_ = used;
      lastMemberOut_ = made;
      memberEnded_ = true;
      return true;
    }
    if (r == LIBDEFLATE_INSUFFICIENT_SPACE)
      room *= 2;
    else if (!fileEnded_ && z_.avail_in >= wantIn)
      wantIn *= 2;  // the member may go on past the input read so far
    else
      break;
  }
  return false;
}

// Decodes one more chunk; returns false when nothing more can come.
bool RawlogSource::decodeMore(bool crossMembers) {
  if (error_ || done_) return false;
  // Room for the output (the consumed front is dropped first).
  if (pos_ > 0 && (pos_ == len_ || pos_ > buf_.size() / 2)) {
    std::memmove(buf_.data(), buf_.data() + pos_, len_ - pos_);
    len_ -= pos_;
    pos_ = 0;
  }
  if (!gzip_) {
    if (fileEnded_) {
      memberEnded_ = true;
      done_ = true;
      return false;
    }
    if (buf_.size() < len_ + kOutputChunk) buf_.resize(len_ + kOutputChunk);
    const std::size_t n = std::fread(buf_.data() + len_, 1, kOutputChunk, file_);
    len_ += n;
    if (n == 0) {
      fileEnded_ = memberEnded_ = done_ = true;
      return false;
    }
    return true;
  }
  if (memberEnded_) {
    if (!crossMembers || len_ > pos_) return false;
    // The next gzip member, if any: nothing but members may follow.
    if (z_.avail_in == 0 && !readInput()) {
      done_ = true;
      return false;
    }
    if (z_.avail_in < 2) readInput();
    const uint64_t at = fileRead_ - z_.avail_in;
    if (z_.avail_in < 2 || z_.next_in[0] != 0x1f || z_.next_in[1] != 0x8b) {
      error_ = "the " + std::to_string(fileRead_ - at) + " bytes at byte " + std::to_string(at) +
               " after the last complete gzip member are not gzip data (damaged or appended garbage)";
      return false;
    }
    inflateReset(&z_);
    memberStart_ = at;
    memberEnded_ = false;
    memberFresh_ = whole_ != nullptr;
  }
  if (memberFresh_ && decodeWholeMember()) return true;
  if (z_.avail_in == 0 && !readInput()) {
    error_ = "the file ends inside the gzip member starting at byte " + std::to_string(memberStart_) +
             " (truncated)";
    return false;
  }
  if (buf_.size() < len_ + kOutputChunk) buf_.resize(len_ + kOutputChunk);
  z_.next_out = buf_.data() + len_;
  z_.avail_out = static_cast<uInt>(kOutputChunk);
  const int r = inflate(&z_, Z_NO_FLUSH);
  len_ += kOutputChunk - z_.avail_out;
  if (r == Z_STREAM_END) {
    memberEnded_ = true;  // zlib checked the member's CRC32 and length
  } else if (r == Z_BUF_ERROR && z_.avail_in == 0) {
    // needs more input: the next call reads it
  } else if (r != Z_OK) {
    error_ = "corrupt gzip data in the member starting at byte " + std::to_string(memberStart_) + " (zlib: " +
             printable(z_.msg ? z_.msg : std::to_string(r)) + ")";
    return false;
  }
  return true;
}

void RawlogSource::prefetch(std::size_t bytes) {
  while (available() < bytes && !memberEnded_ && decodeMore(false)) {
  }
  if (available() == 0 && memberEnded_) {
    // Start the next member so that available() > 0 unless the data ended.
    while (available() == 0 && decodeMore(true)) {
    }
    while (available() < bytes && !memberEnded_ && decodeMore(false)) {
    }
  }
}

size_t RawlogSource::Read(void* buffer, size_t count) {
  auto* out = static_cast<std::uint8_t*>(buffer);
  size_t done = 0;
  while (done < count) {
    if (available() == 0 && !decodeMore(true)) break;
    const size_t n = std::min(count - done, available());
    std::memcpy(out + done, buf_.data() + pos_, n);
    pos_ += n;
    done += n;
    consumed_ += n;
  }
  return done;
}

// ---- Header and size checks before MRPT allocates ----

namespace {

class Cursor {
 public:
  Cursor(const std::uint8_t* p, std::size_t n, bool bounded) : p_(p), n_(n), bounded_(bounded) {}
  /// False when the bytes are not there (then `short_` says whether that is damage).
  bool take(void* out, std::size_t k) {
    if (k > n_ - i_) {
      short_ = true;
      return false;
    }
    std::memcpy(out, p_ + i_, k);
    i_ += k;
    return true;
  }
  bool skip(std::uint64_t k) {
    if (k > n_ - i_) {
      short_ = true;
      return false;
    }
    i_ += static_cast<std::size_t>(k);
    return true;
  }
  std::uint64_t left() const { return n_ - i_; }
  std::size_t at() const { return i_; }
  bool bounded() const { return bounded_; }
  bool ranShort() const { return short_; }

 private:
  const std::uint8_t* p_;
  std::size_t n_, i_ = 0;
  bool bounded_;
  bool short_ = false;
};

struct Header {
  std::string className;
  int version = 0;
  bool oldFormat = false;
};

// Reads an MRPT object header the way CArchive does, but refuses what
// CArchive would print unterminated or unreadable.
std::optional<std::string> readHeader(Cursor& c, Header& h) {
  std::uint8_t len = 0;
  if (!c.take(&len, 1)) return std::string();
  h.oldFormat = !(len & 0x80);
  if (h.oldFormat) {
    std::uint8_t zeros[3];
    if (!c.take(zeros, 3)) return std::string();
    if (zeros[0] || zeros[1] || zeros[2]) return std::string("no MRPT object header (not a rawlog, or damaged)");
  }
  len &= 0x7f;
  if (len == 0 || len > 120)
    return "no MRPT object header (class name length " + std::to_string(len) + "; not a rawlog, or damaged)";
  std::string name(len, '\0');
  if (!c.take(name.data(), len)) return std::string();
  for (const char ch : name)
    if (!(std::isalnum(static_cast<unsigned char>(ch)) || ch == '_' || ch == ':'))
      return "no MRPT object header (class name '" + printable(name) + "' is not a name; not a rawlog, or damaged)";
  if (!mrpt::rtti::findRegisteredClass(name))
    return "unknown object class '" + name + "' (damaged, or written by a program srp does not know)";
  h.className = name;
  if (h.oldFormat) {
    std::int32_t v = 0;
    if (!c.take(&v, 4)) return std::string();
    h.version = v;
  } else {
    std::uint8_t v = 0;
    if (!c.take(&v, 1)) return std::string();
    h.version = v;
  }
  return std::nullopt;
}

// Flags are written as 0 or 1; anything else is a flipped byte.
std::optional<std::string> readFlag(Cursor& c, bool& flag, const char* what) {
  std::uint8_t b = 0;
  if (!c.take(&b, 1)) return std::string();
  if (b > 1) return std::string(what) + " flag byte is " + std::to_string(b) + " (0 or 1 expected)";
  flag = b == 1;
  return std::nullopt;
}

std::optional<std::string> checkBytes(const Cursor& c, std::uint64_t bytes, const std::string& what) {
  if (c.bounded() && bytes > c.left())
    return what + " declares " + std::to_string(bytes) + " bytes but only " + std::to_string(c.left()) +
           " are left in the frame (a damaged size field)";
  return std::nullopt;
}

std::optional<std::string> checkSide(std::int64_t side, const std::string& what) {
  if (side < 0 || side > kMaxImageSide_px)
    return what + " of " + std::to_string(side) + " px is outside 0.." + std::to_string(kMaxImageSide_px) +
           " (a damaged size field)";
  return std::nullopt;
}

// An MRPT string (uint32 length + bytes): the length is checked before
// MRPT allocates it (a flipped length byte asked for gigabytes).
std::optional<std::string> skipString(Cursor& c, std::uint32_t maxBytes, const char* what) {
  std::uint32_t n = 0;
  if (!c.take(&n, 4)) return std::string();
  if (n > maxBytes)
    return std::string(what) + " of " + std::to_string(n) + " bytes (at most " + std::to_string(maxBytes) +
           " expected; a damaged length field)";
  if (auto e = checkBytes(c, n, what)) return e;
  if (!c.skip(n)) return std::string();
  return std::nullopt;
}

std::optional<std::string> endFlag(Cursor& c, const char* what) {
  std::uint8_t end = 0;
  if (!c.take(&end, 1)) return std::string();
  if (end != 0x88) return std::string(what) + " does not end where its sizes say (damaged)";
  return std::nullopt;
}

// A CPose3D: v2 x y z + quaternion, v3 rotation matrix + x y z (doubles).
// Sets `known` false for other versions (the rest is then left to MRPT).
std::optional<std::string> scanPose(Cursor& c, const char* what, bool& known) {
  Header pose;
  if (auto e = readHeader(c, pose)) return e->empty() ? *e : std::string(what) + ": " + *e;
  if (pose.className != "mrpt::poses::CPose3D" && pose.className != "CPose3D")
    return std::string(what) + " is a '" + pose.className + "' (damaged)";
  known = !pose.oldFormat && (pose.version == 2 || pose.version == 3);
  if (!known) return std::nullopt;
  if (!c.skip(pose.version == 2 ? 7 * 8 : 12 * 8)) return std::string();
  return endFlag(c, what);
}

// An mrpt::img::TCamera v5/v6: focal length, 8 distortion terms, fx fy cx cy
// (doubles), nrows ncols (uint32), name (string), v6: distortion model (uint8).
std::optional<std::string> scanCamera(Cursor& c, const char* what, bool& known) {
  Header h;
  if (auto e = readHeader(c, h)) return e->empty() ? *e : std::string(what) + ": " + *e;
  if (h.className != "mrpt::img::TCamera" && h.className != "TCamera")
    return std::string(what) + " is a '" + h.className + "' (damaged)";
  known = !h.oldFormat && (h.version == 5 || h.version == 6);
  if (!known) return std::nullopt;
  if (!c.skip(13 * 8)) return std::string();
  std::uint32_t rows = 0, cols = 0;
  if (!c.take(&rows, 4) || !c.take(&cols, 4)) return std::string();
  if (auto e = checkSide(rows, std::string(what) + " height")) return e;
  if (auto e = checkSide(cols, std::string(what) + " width")) return e;
  if (auto e = skipString(c, 1024, "camera name")) return e;
  if (h.version >= 6 && !c.skip(1)) return std::string();
  return endFlag(c, what);
}

// An mrpt::img::CImage (versions 2..9) inside a scan.
std::optional<std::string> scanImage(Cursor& c, const char* what, bool& known) {
  Header h;
  if (auto e = readHeader(c, h)) return e;
  if (h.className != "mrpt::img::CImage" && h.className != "CImage")
    return std::string(what) + " is a '" + h.className + "', not an image";
  known = !h.oldFormat && h.version >= 7 && h.version <= 9;
  if (!known) return std::nullopt;  // older layouts: left to MRPT
  bool external = false;
  if (auto e = readFlag(c, external, "external-image")) return e;
  if (external) {
    std::uint32_t n = 0;
    if (!c.take(&n, 4)) return std::string();
    if (n > 4096) return std::string(what) + " file name of " + std::to_string(n) + " bytes (a damaged size field)";
    if (!c.skip(n)) return std::string();
  } else {
    bool colour = false;
    if (auto e = readFlag(c, colour, "colour")) return e;
    std::int32_t w = 0, h2 = 0;
    if (!c.take(&w, 4) || !c.take(&h2, 4)) return std::string();
    if (!colour) {
      std::int32_t origin = 0, size = 0, depth = 0;
      if (!c.take(&origin, 4) || !c.take(&size, 4)) return std::string();
      if (h.version >= 9 && !c.take(&depth, 4)) return std::string();
      if (auto e = checkSide(w, std::string(what) + " width")) return e;
      if (auto e = checkSide(h2, std::string(what) + " height")) return e;
      if (size < 0) return std::string(what) + " size is negative (a damaged size field)";
      bool zip = false;
      if (auto e = readFlag(c, zip, "zip")) return e;
      if (zip) return std::nullopt;  // MRPT refuses it with its own message
      if (auto e = checkBytes(c, static_cast<std::uint64_t>(size), what)) return e;
      if (!c.skip(static_cast<std::uint64_t>(size))) return std::string();
    } else if (w < 0 && h2 < 0) {  // raw colour
      if (auto e = checkSide(-static_cast<std::int64_t>(w), std::string(what) + " width")) return e;
      if (auto e = checkSide(-static_cast<std::int64_t>(h2), std::string(what) + " height")) return e;
      const std::uint64_t bytes = 3ull * static_cast<std::uint64_t>(-static_cast<std::int64_t>(w)) *
                                  static_cast<std::uint64_t>(-static_cast<std::int64_t>(h2));
      if (auto e = checkBytes(c, bytes, what)) return e;
      if (!c.skip(bytes)) return std::string();
    } else if (w >= 1 && h2 >= 1) {  // JPEG
      if (auto e = checkSide(w, std::string(what) + " width")) return e;
      if (auto e = checkSide(h2, std::string(what) + " height")) return e;
      std::uint32_t n = 0;
      if (!c.take(&n, 4)) return std::string();
      if (auto e = checkBytes(c, n, what)) return e;
      if (!c.skip(n)) return std::string();
    } else {
      if (auto e = checkSide(std::abs(static_cast<std::int64_t>(w)), std::string(what) + " width")) return e;
      if (auto e = checkSide(std::abs(static_cast<std::int64_t>(h2)), std::string(what) + " height")) return e;
    }
  }
  std::uint8_t end = 0;
  if (!c.take(&end, 1)) return std::string();
  if (end != 0x88) return std::string(what) + " does not end where its sizes say (damaged)";
  return std::nullopt;
}

// CObservation3DRangeScan versions 9 and 10 (MRPT 2.x), up to its images.
std::optional<std::string> scanRgbd(Cursor& c, int version) {
  if (version < 9 || version > 10) return std::nullopt;  // older layouts: left to MRPT
  float maxRange = 0;
  if (!c.take(&maxRange, 4)) return std::string();
  bool known = true;
  if (auto e = scanPose(c, "sensor pose", known)) return e;
  if (!known) return std::nullopt;
  bool hasPoints = false;
  if (auto e = readFlag(c, hasPoints, "3D-points")) return e;
  if (hasPoints) {
    std::uint32_t n = 0;
    if (!c.take(&n, 4)) return std::string();
    if (n > kMaxPoints) return "3D point count " + std::to_string(n) + " is beyond any sensor (a damaged size field)";
    const std::uint64_t bytes = std::uint64_t(n) * (3 * 4 + 2 * 2);
    if (auto e = checkBytes(c, bytes, "3D points")) return e;
    if (!c.skip(bytes)) return std::string();
  }
  bool hasRange = false;
  if (auto e = readFlag(c, hasRange, "range-image")) return e;
  float units = 0;
  if (!c.take(&units, 4)) return std::string();
  if (!std::isfinite(units) || units <= 0.0f || units > 1.0f)
    return "depth unit " + std::to_string(units) + " m is not in (0, 1] (a damaged field)";
  if (hasRange) {
    std::uint32_t rows = 0, cols = 0;
    if (!c.take(&rows, 4) || !c.take(&cols, 4)) return std::string();
    if (auto e = checkSide(rows, "depth image height")) return e;
    if (auto e = checkSide(cols, "depth image width")) return e;
    const std::uint64_t bytes = 2ull * rows * cols;
    if (auto e = checkBytes(c, bytes, "depth image")) return e;
    if (!c.skip(bytes)) return std::string();
  }
  bool hasIntensity = false;
  if (auto e = readFlag(c, hasIntensity, "colour-image")) return e;
  if (hasIntensity) {
    if (auto e = scanImage(c, "colour image", known)) return e;
    if (!known) return std::nullopt;
  }
  bool hasConfidence = false;
  if (auto e = readFlag(c, hasConfidence, "confidence-image")) return e;
  if (hasConfidence) {
    if (auto e = scanImage(c, "confidence image", known)) return e;
    if (!known) return std::nullopt;
  }
  // The rest (MRPT 2.x, versions 9 and 10): cameras, pose, strings, layers.
  for (const char* camera : {"depth camera", "colour camera"}) {
    if (auto e = scanCamera(c, camera, known)) return e;
    if (!known) return std::nullopt;
  }
  if (auto e = scanPose(c, "colour camera pose", known)) return e;
  if (!known) return std::nullopt;
  if (!c.skip(4 + 8)) return std::string();  // stdError, timestamp
  if (auto e = skipString(c, 1024, "sensor label")) return e;
  for (const char* file : {"external 3D points file name", "external depth file name"}) {
    bool external = false;
    if (auto e = readFlag(c, external, "external-storage")) return e;
    if (auto e = skipString(c, 4096, file)) return e;
  }
  bool rangeIsDepth = false, hasLabels = false;
  if (auto e = readFlag(c, rangeIsDepth, "range-is-depth")) return e;
  if (!c.skip(1)) return std::string();  // intensity channel
  if (auto e = readFlag(c, hasLabels, "pixel-labels")) return e;
  if (hasLabels) return std::nullopt;  // a layout of its own: left to MRPT
  if (version >= 10) {
    std::uint8_t layers = 0;
    if (!c.take(&layers, 1)) return std::string();
    for (int i = 0; i < layers; ++i) {
      if (auto e = skipString(c, 1024, "depth layer name")) return e;
      std::uint32_t a = 0, b = 0;
      if (!c.take(&a, 4) || !c.take(&b, 4)) return std::string();
      if (auto e = checkSide(a, "depth layer side")) return e;
      if (auto e = checkSide(b, "depth layer side")) return e;
      const std::uint64_t bytes = 2ull * a * b;
      if (auto e = checkBytes(c, bytes, "depth layer")) return e;
      if (!c.skip(bytes)) return std::string();
    }
  }
  return endFlag(c, "the RGB-D scan");
}

// mrpt::obs::CObservationComment (srp's markers): text, timestamp.
std::optional<std::string> scanComment(Cursor& c, int version) {
  if (version != 0) return std::nullopt;
  if (auto e = skipString(c, 1 << 20, "comment text")) return e;
  if (!c.skip(8)) return std::string();
  return endFlag(c, "the comment");
}

}  // namespace

std::optional<std::string> prescanObject(const std::uint8_t* p, std::size_t n, bool bounded) {
  Cursor c(p, n, bounded);
  Header h;
  std::optional<std::string> problem = readHeader(c, h);
  if (!problem && !h.oldFormat &&
      (h.className == "CObservation3DRangeScan" || h.className == "mrpt::obs::CObservation3DRangeScan"))
    problem = scanRgbd(c, h.version);
  if (!problem && !h.oldFormat &&
      (h.className == "CObservationComment" || h.className == "mrpt::obs::CObservationComment"))
    problem = scanComment(c, h.version);
  if (problem && problem->empty()) {
    // Ran out of bytes: damage when the object had to fit, else left to MRPT.
    if (!bounded) return std::nullopt;
    return "the object ends early, at byte " + std::to_string(c.at()) + " of its " + std::to_string(n) +
           " (truncated or damaged)";
  }
  return problem;
}

}  // namespace srp::rawlog::detail
