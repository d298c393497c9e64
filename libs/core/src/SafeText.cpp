#include "srp/core/SafeText.h"

#include <cstdint>
#include <cstdio>

#include "srp/core/Error.h"

namespace srp::core {
namespace {

/// Decodes one UTF-8 character at text[i]; returns its length (0: not valid
/// UTF-8 there: overlong, surrogate, beyond U+10FFFF or truncated).
std::size_t decodeUtf8(std::string_view text, std::size_t i, std::uint32_t& codePoint) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(text[k]); };
  const unsigned char b0 = byte(i);
  std::size_t length = 0;
  std::uint32_t cp = 0, minimum = 0;
  if (b0 < 0x80) return codePoint = b0, 1;
  if ((b0 & 0xE0) == 0xC0) length = 2, cp = b0 & 0x1F, minimum = 0x80;
  else if ((b0 & 0xF0) == 0xE0) length = 3, cp = b0 & 0x0F, minimum = 0x800;
  else if ((b0 & 0xF8) == 0xF0) length = 4, cp = b0 & 0x07, minimum = 0x10000;
  else return 0;
  if (i + length > text.size()) return 0;
  for (std::size_t k = 1; k < length; ++k) {
    if ((byte(i + k) & 0xC0) != 0x80) return 0;
    cp = (cp << 6) | (byte(i + k) & 0x3F);
  }
  if (cp < minimum || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF)) return 0;
  codePoint = cp;
  return length;
}

std::string escaped(std::uint32_t codePoint) {
  char buffer[16];
  if (codePoint == '\n') return "\\n";
  if (codePoint == '\r') return "\\r";
  if (codePoint == '\t') return "\\t";
  if (codePoint <= 0xFFFF) std::snprintf(buffer, sizeof(buffer), "\\u%04X", static_cast<unsigned>(codePoint));
  else std::snprintf(buffer, sizeof(buffer), "\\U%08X", static_cast<unsigned>(codePoint));
  return buffer;
}

}  // namespace

std::string exportSafeText(std::string_view text, std::size_t maxLength) {
  static const std::string kCut = "...";
  if (maxLength < kCut.size()) maxLength = kCut.size();
  std::string out;
  std::size_t lastFit = 0;  // length of `out` at the last character boundary that leaves room for kCut
  for (std::size_t i = 0; i < text.size();) {
    std::uint32_t cp = 0;
    const std::size_t length = decodeUtf8(text, i, cp);
    if (length == 0) {
      char buffer[8];
      std::snprintf(buffer, sizeof(buffer), "\\x%02X", static_cast<unsigned>(static_cast<unsigned char>(text[i])));
      out += buffer;
    } else if (cp == '\\') {
      out += "\\\\";
    } else if (cp >= 0x20 && cp <= 0x7E) {
      out += static_cast<char>(cp);
    } else {
      out += escaped(cp);
    }
    i += length == 0 ? 1 : length;
    if (out.size() > maxLength) return out.substr(0, lastFit) + kCut;
    if (out.size() + kCut.size() <= maxLength) lastFit = out.size();
  }
  return out;
}

bool isSafeName(std::string_view name) {
  if (name.empty() || name.size() > kMaxNameLength || name.back() == ' ') return false;
  const auto alnum = [](char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9'); };
  if (!alnum(name.front())) return false;
  for (char c : name)
    if (!alnum(c) && c != ' ' && c != '_' && c != '-' && c != '.') return false;
  return true;
}

void requireSafeName(std::string_view name, const std::string& what) {
  if (isSafeName(name)) return;
  throw InvalidInputError(what + ": '" + exportSafeText(name, 80) + "' is not a usable name; use 1-" +
                          std::to_string(kMaxNameLength) +
                          " characters of ASCII letters, digits, space, '_', '-' and '.', starting with a letter or "
                          "a digit (e.g. \"blue box\", \"cuboid_red\", \"thesis-1\")");
}

std::string safeFileName(std::string_view name) {
  std::string out;
  for (char c : name.substr(0, kMaxNameLength)) {
    const bool keep = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '-' ||
                      c == '_' || (c == '.' && !out.empty());
    out += keep ? c : '_';
  }
  return out.empty() ? "_" : out;
}

}  // namespace srp::core
