#pragma once
/// \file SafeText.h
/// \brief Text from a user or a file, made harmless where a robot program or a
/// trajectory is written, and names checked where they enter srp.
///
/// An exported URScript program or ROS 2 trajectory is code a controller runs.
/// A line break inside a comment ends the comment, and what follows becomes a
/// statement (URScript) or a document (YAML: `---` and a second trajectory).
/// Controllers and YAML readers disagree on what a line break is (LF, CR, NEL
/// U+0085, LINE SEPARATOR U+2028, PARAGRAPH SEPARATOR U+2029, ...), so the
/// exporters write no character but printable ASCII into a comment:
/// exportSafeText() keeps the bytes 0x20-0x7E and writes everything else as an
/// escape (`\n`, `\r`, `\t`, `\u2028`, `\x85` for a byte that is no UTF-8),
/// doubling the backslash so an escape in the input cannot pose as one of ours.
///
/// Names (task model names, scene object ids, class names and nouns, colour
/// words) are refused where they enter (scene and catalogue files, `--name`,
/// `srp kb add`) unless they are made of a small character set (isSafeName()).
///
/// \code
///   const std::string line = "# instruction: " + srp::core::exportSafeText(instruction);
///   srp::core::requireSafeName(options.name, "--name");   // throws InvalidInputError
/// \endcode

#include <cstddef>
#include <string>
#include <string_view>

namespace srp::core {

/// Longest text exportSafeText() writes by default [characters]; longer text is
/// cut (at a character boundary) and ends in "...".
constexpr std::size_t kMaxExportTextLength = 400;

/// `text` as printable ASCII only (0x20-0x7E, no line break of any kind):
/// backslash doubled, `\n` `\r` `\t` for those controls, `\uXXXX` / `\UXXXXXXXX`
/// for every other character of valid UTF-8 (controls, NEL, U+2028/2029, bidi
/// controls, letters with accents), `\xHH` for a byte that is not valid UTF-8.
/// At most `maxLength` characters (then cut and ending in "...").
std::string exportSafeText(std::string_view text, std::size_t maxLength = kMaxExportTextLength);

/// Longest name isSafeName() accepts [characters].
constexpr std::size_t kMaxNameLength = 64;

/// True when `name` is 1-kMaxNameLength characters of ASCII letters, digits,
/// space, '_', '-' and '.', starting with a letter or a digit and not ending in
/// a space ("blue box", "cuboid_red", "thesis-1").
bool isSafeName(std::string_view name);

/// Throws InvalidInputError naming `what` (e.g. "--name", "scene 'x.json':
/// objects[2] field 'id'") and the allowed characters unless isSafeName(name).
void requireSafeName(std::string_view name, const std::string& what);

/// `name` as one file name: ASCII letters, digits, '-', '_' and '.' kept, every
/// other byte (a space, '/', a control) written as '_', no leading '.' (so no
/// "..", no hidden file), at most kMaxNameLength characters; "_" for "".
std::string safeFileName(std::string_view name);

}  // namespace srp::core
